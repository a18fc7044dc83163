#!/usr/bin/env bash
# Static benchmark: StableWS vs CGAL's refine_Delaunay_mesh_2, one process per configuration (so that peak
# memory is per algorithm), written to bench/RESULTS.md between the static:begin/end markers. Other
# sections of RESULTS.md are left alone.
#
#   bench/run.sh BUILD_DIR [--algo stablews|cgal|none] [--dim 2|3] [--n N] [--max-repeats K]
#
# --algo, --dim and --n select some of the configurations below; the others keep their previous lines from
# RESULTS.md (the raw lines are stored in the section itself), so parts can be measured at different
# times (--algo none only rewrites the section). --max-repeats caps the repeats, for a machine too busy
# to run the large configurations five times; the repeats used are in the section's command list.
set -euo pipefail

usage() { echo "usage: $0 BUILD_DIR [--algo stablews|cgal|none] [--dim 2|3] [--n N] [--max-repeats K]" >&2; exit 2; }
[[ $# -ge 1 ]] || usage
build_dir=$1
shift
only_algo="" only_dim="" only_n="" max_repeats=""
while [[ $# -gt 0 ]]; do
  [[ $# -ge 2 ]] || usage
  case $1 in
    --algo) only_algo=$2 ;;
    --dim) only_dim=$2 ;;
    --n) only_n=$2 ;;
    --max-repeats) max_repeats=$2 ;;
    *) usage ;;
  esac
  shift 2
done
selected() {  # algo dim n
  [[ (-z $only_algo || $1 == "$only_algo") && (-z $only_dim || $2 == "$only_dim") && (-z $only_n || $3 == "$only_n") ]]
}
bench=$build_dir/bench/bench_static
[[ -x $bench ]] || { echo "$0: $bench not built (cmake --build $build_dir --target bench_static)" >&2; exit 1; }
here=$(cd "$(dirname "$0")" && pwd)
results=$here/RESULTS.md
family=uniform
seed=1
# The commit the build dir was configured from ("+dirty" with local changes), recorded with every line.
source_dir=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build_dir/CMakeCache.txt" 2>/dev/null || true)
source=$(git -C "${source_dir:-.}" describe --always --dirty=+dirty 2>/dev/null || echo unknown)

# algo dim n repeats
configs=(
  "cgal 2 10000 5" "cgal 2 100000 5" "cgal 2 1000000 3"
  "stablews 2 10000 5" "stablews 2 100000 5" "stablews 2 1000000 3"
  "stablews 3 10000 5" "stablews 3 100000 5"
)

begin='<!-- static:begin -->'
end='<!-- static:end -->'
raw=$(mktemp)
trap 'rm -f "$raw" "$raw.new"' EXIT

# Keep the previous raw lines of the configurations not being rerun.
if [[ -f $results ]]; then
  sed -n "/^$begin\$/,/^$end\$/p" "$results" | grep '^algo=' | while read -r line; do
    algo=$(grep -o 'algo=[^ ]*' <<<"$line" | cut -d= -f2)
    dim=$(grep -o 'dim=[^ ]*' <<<"$line" | cut -d= -f2)
    n=$(grep -o ' n=[^ ]*' <<<"$line" | cut -d= -f2)
    selected "$algo" "$dim" "$n" || echo "$line"
  done >"$raw"
fi

cpu=$(grep -m1 '^model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')

# The section: machine, commands, one table of all runs, the 2D ratios, the raw lines.
section() {
  echo "$begin"
  echo "## Static: StableWS vs CGAL refine_Delaunay_mesh_2"
  echo
  echo "Machine: $(nproc) CPUs ($cpu); written $(date -u +%Y-%m-%dT%H:%MZ). Input family \`$family\`, seed $seed,"
  echo "unit box. StableWS: \`stable_well_spaced\` with the default rho = sqrt(2). CGAL: constrained Delaunay"
  echo "triangulation of the square and the points, \`refine_Delaunay_mesh_2(cdt, Criteria(0.125, 0))\`"
  echo "(shape bound sin^2(20.7°), no size bound). Time: median over the repeats, algorithm only, as wall"
  echo "seconds and as process CPU seconds (on a shared machine the wall time grows with the load; \`load\` is"
  echo "the 1-minute load average when the run started). Peak RSS: the whole process (getrusage), input"
  echo "included. Each run's date and source commit are in its raw line."
  echo
  echo "Command: \`bench/run.sh BUILD_DIR\` (or a part of it: \`--algo\`, \`--dim\`, \`--n\`, \`--max-repeats\`), which runs"
  echo "from BUILD_DIR/bench:"
  echo
  echo '```sh'
  awk '{ delete f; for (i = 1; i <= NF; ++i) { split($i, kv, "="); f[kv[1]] = kv[2] }
         printf "bench_static --algo %s --dim %s --n %s --family %s --repeats %s --seed %s\n", f["algo"], f["dim"], f["n"],
           f["family"], f["repeats"], f["seed"] }' "$raw" | sort -k3,3 -k5,5n -k7,7n
  echo '```'
  echo
  echo "| algo | dim | n | output vertices | median wall s | median CPU s | CPU µs / output vertex | ops / output vertex | peak RSS MB | bytes / output vertex | engine bytes / output vertex | load |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
  awk '
    { delete f; for (i = 1; i <= NF; ++i) { split($i, kv, "="); f[kv[1]] = kv[2] } }
    { out = f["output_vertices"]; engine = f["engine_memory_bytes"]
      printf "| %s | %s | %s | %s | %.3f | %.3f | %.2f | %s | %.1f | %.0f | %s | %s |\n", f["algo"], f["dim"], f["n"], out,
        f["median_seconds"], f["median_cpu_seconds"], 1e6 * f["median_cpu_seconds"] / out,
        f["ops_per_vertex"] == "nan" ? "–" : f["ops_per_vertex"], f["peak_rss_bytes"] / 1048576,
        f["bytes_per_vertex"], engine == "nan" ? "–" : sprintf("%.0f", engine / out), f["load"] }' "$raw" |
    sort -t'|' -k2,2 -k3,3n -k4,4n
  echo
  echo "Ratios StableWS / CGAL (2D, same input):"
  echo
  echo "| n | CPU time | wall time | output size | peak bytes per output vertex |"
  echo "|---|---|---|---|---|"
  awk '
    { delete f; for (i = 1; i <= NF; ++i) { split($i, kv, "="); f[kv[1]] = kv[2] } }
    f["dim"] == 2 { key = f["n"]; t[f["algo"], key] = f["median_seconds"]; c[f["algo"], key] = f["median_cpu_seconds"]
                    o[f["algo"], key] = f["output_vertices"]
                    b[f["algo"], key] = f["bytes_per_vertex"]; ns[key] = 1 }
    END { for (k in ns) if ((("stablews", k) in t) && (("cgal", k) in t))
            printf "| %s | %.2f | %.2f | %.2f | %.2f |\n", k, c["stablews", k] / c["cgal", k], t["stablews", k] / t["cgal", k],
                   o["stablews", k] / o["cgal", k],
                   b["stablews", k] / b["cgal", k] }' "$raw" | sort -t'|' -k2,2n
  echo
  echo "<details><summary>Raw lines (bench_static output)</summary>"
  echo
  echo '```text'
  sort "$raw"
  echo '```'
  echo
  echo "</details>"
  echo "$end"
}

# Replace the section between the markers, or append it; everything else in the file stays as it was.
write_results() {
  if [[ -f $results ]] && grep -q "^$begin\$" "$results"; then
    section >"$raw.new"
    awk -v begin="$begin" -v end="$end" -v body="$raw.new" '
      $0 == begin { while ((getline line < body) > 0) print line; skip = 1; next }
      $0 == end { skip = 0; next }
      !skip { print }' "$results" >"$results.tmp" && mv "$results.tmp" "$results"
  else
    { [[ -f $results ]] && { cat "$results"; echo; } || echo "# Benchmark results"; echo; section; } >"$results.tmp"
    mv "$results.tmp" "$results"
  fi
}

# Run the configurations; the section is rewritten after each one, so an interrupted run keeps what it got.
for config in "${configs[@]}"; do
  read -r algo dim n repeats <<<"$config"
  selected "$algo" "$dim" "$n" || continue
  [[ -z $max_repeats || $repeats -le $max_repeats ]] || repeats=$max_repeats
  cmd="$bench --algo $algo --dim $dim --n $n --family $family --repeats $repeats --seed $seed"
  echo "running: $cmd" >&2
  load=$(cut -d' ' -f1 /proc/loadavg)  # the machine may be shared: say how busy it was
  if line=$($cmd); then
    echo "$line run_at=$(date -u +%Y-%m-%dT%H:%M:%SZ) load=$load source=$source" | tee -a "$raw" >&2
  else
    echo "$0: failed: $cmd" >&2
  fi
  write_results
done
write_results
echo "wrote $results" >&2

