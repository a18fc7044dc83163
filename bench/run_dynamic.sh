#!/usr/bin/env bash
# Dynamic benchmark (the paper's Figure 7, right): one process per configuration, raw lines to stdout.
#   bench/run_dynamic.sh BUILD_DIR
set -euo pipefail
bench=${1:?usage: $0 BUILD_DIR}/bench/bench_dynamic
[[ -x $bench ]] || { echo "$0: $bench not built (cmake --build BUILD_DIR --target bench_dynamic)" >&2; exit 1; }
for args in "--dim 2 --n 1000 --changes 100 --inputs 3" "--dim 2 --n 10000 --changes 100 --inputs 1" \
            "--dim 2 --n 100000 --changes 50 --inputs 1" "--dim 2 --n 1000000 --changes 20 --inputs 1" \
            "--dim 3 --n 1000 --changes 30 --inputs 1" "--dim 3 --n 10000 --changes 10 --inputs 1"; do
  echo "cmd: bench_dynamic $args --seed 1"
  "$bench" $args --seed 1
done
