#!/usr/bin/env bash
# Builds the libFuzzer targets of the input parsers (fuzz/fuzz_*.cpp) with Debian's clang, directly from the
# io sources (not through the main CMake build), and runs each one for a bounded time.
#
#   FUZZ_SECONDS   seconds per target (default 30)
#   FUZZ_RUNS      executions per target instead of a time (e.g. 1000000; bench/RESULTS.md records such runs)
#   FUZZ_MAX_LEN   largest input in bytes (default 65536; smaller inputs run many times faster)
#   FUZZ_TARGETS   space-separated subset, e.g. "gpx geojson" (default: every fuzz/fuzz_*.cpp)
#   FUZZ_BUILD     build and corpus directory (default: build-fuzz)
#   FUZZ_JOBS      parallel compile jobs (default 2)
#
# Each target runs on a corpus seeded from samples/ and a few hand-written inputs; new interesting inputs are
# kept in $FUZZ_BUILD/corpus/<target>. Any crash, sanitizer report (AddressSanitizer, UBSan) or exception other
# than shoremesh::InputError fails the run; the reproducer is left in $FUZZ_BUILD/crashes/<target>/.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
SECONDS_PER_TARGET=${FUZZ_SECONDS:-30}
MAX_LEN=${FUZZ_MAX_LEN:-65536}
if [ -n "${FUZZ_RUNS:-}" ]; then LIMIT="-runs=$FUZZ_RUNS"; else LIMIT="-max_total_time=$SECONDS_PER_TARGET"; fi
OUT=${FUZZ_BUILD:-$ROOT/build-fuzz}
JOBS=${FUZZ_JOBS:-2}

# clang with libFuzzer and the sanitizer runtimes (Debian: clang + libclang-rt-14-dev).
missing=()
command -v clang++ >/dev/null 2>&1 || missing+=(clang)
dpkg-query -W -f='${Status}' libclang-rt-14-dev 2>/dev/null | grep -q "install ok installed" || missing+=(libclang-rt-14-dev)
if [ ${#missing[@]} -gt 0 ]; then
  echo "fuzz: installing ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

CXX=${CXX_FUZZ:-clang++}
SAN="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# Coordinate systems go through GDAL/OGR (PROJ): its headers and library (Debian: libgdal-dev).
CXXFLAGS="-std=c++20 -g -O1 $SAN -frounding-math -I$ROOT/core/include -I$ROOT/io/include -I$ROOT/io/src/input $(gdal-config --cflags)"
# The text parsers and what they call (paths under io/src); no OpenCV (images are not fuzzed here).
# Coordinate systems: raster/crs (GDAL), linked directly as in the tests (docs/raster_module.md).
# The ring checks and the PSLG's domain the parsers call are core's (core/src, by the same relative paths).
SOURCES=(input/point_file input/ring_file input/gps_track input/geojson_input input/poly_file input/georeference
         raster/crs input/projection input/input_set output/atomic_file point_set_csv
         ../../core/src/domain_check ../../core/src/ring_edge_index ../../core/src/pslg)
LIBS="-lGeographicLib -lproj -lgmp -lmpfr -lpugixml -lOpenImageIO -lOpenImageIO_Util $(gdal-config --libs)"

mkdir -p "$OUT/obj" "$OUT/corpus" "$OUT/crashes"
echo "fuzz: compiling the io parsers into $OUT/obj"
pids=()
for s in "${SOURCES[@]}"; do
  src="$ROOT/io/src/$s.cpp" obj="$OUT/obj/${s//\//_}.o"
  if [ ! -f "$obj" ] || [ "$src" -nt "$obj" ] || [ -n "$(find "$ROOT/io/include" "$ROOT/io/src/input" "$ROOT/io/src/raster" "$ROOT/core/include" -name '*.hpp' -newer "$obj" 2>/dev/null | head -1)" ]; then
    $CXX $CXXFLAGS -fsanitize=fuzzer-no-link -c "$src" -o "$obj" &
    pids+=($!)
    if [ ${#pids[@]} -ge "$JOBS" ]; then wait "${pids[0]}"; pids=("${pids[@]:1}"); fi
  fi
done
for p in "${pids[@]}"; do wait "$p"; done
objs=()
for s in "${SOURCES[@]}"; do objs+=("$OUT/obj/${s//\//_}.o"); done

seed() {  # seed <target> <name> <content>
  mkdir -p "$OUT/corpus/$1"
  printf '%s' "$3" > "$OUT/corpus/$1/seed-$2"
}
seed_file() {  # seed_file <target> <file>
  mkdir -p "$OUT/corpus/$1"
  [ -f "$2" ] && cp "$2" "$OUT/corpus/$1/seed-$(basename "$2")"
  return 0
}
seed point_file csv $'x,y\n0,0\n1,0.5 # c\n2,3\n'
seed point_file xyz $'1 2 3\n4 5 6\n'
seed point_file rings $'0,0\n4,0\n4,4\n0,4\n0,0\n\n1,1\n1,2\n2,2\n1,1\n'
seed_file point_file "$ROOT/samples/superior/lake_superior_lonlat.csv"
seed_file gpx "$ROOT/samples/cerknica/cerknicko-jezero.gpx"
seed gpx rte $'<gpx version="1.1"><rte><rtept lat="45" lon="14"><ele>3</ele></rtept><rtept lat="45.001" lon="14.001"/></rte></gpx>'
seed track_csv track $'time,lat,lon,ele\n1,45.0,14.0,3\n2,45.001,14.001,\n3,45.002,14.0005,4\n'
seed geojson poly '{"type":"Feature","geometry":{"type":"Polygon","coordinates":[[[14,45],[14.1,45],[14.1,45.1],[14,45]]]},"properties":{}}'
seed geojson coll '{"type":"FeatureCollection","features":[{"type":"Feature","geometry":{"type":"MultiPoint","coordinates":[[1,2],[3,4,5]]}}]}'
seed_file poly "$ROOT/samples/pslg/double_hex.poly"
seed_file poly "$ROOT/samples/pslg/fish-and-rectangle.poly"
seed_file poly "$ROOT/samples/pslg/dots.node"
seed_file georeference "$ROOT/samples/superior/superior_watermask_h.wld"
seed_file georeference "$ROOT/samples/superior/superior_watermask_h.prj"
seed georeference utm 'UTM 16N'

targets=()
if [ -n "${FUZZ_TARGETS:-}" ]; then
  for t in $FUZZ_TARGETS; do targets+=("$t"); done
else
  for f in "$ROOT"/fuzz/fuzz_*.cpp; do t=$(basename "$f" .cpp); targets+=("${t#fuzz_}"); done
fi

status=0
for t in "${targets[@]}"; do
  bin="$OUT/fuzz_$t"
  echo "fuzz: building fuzz_$t"
  $CXX $CXXFLAGS -fsanitize=fuzzer "$ROOT/fuzz/fuzz_$t.cpp" "${objs[@]}" $LIBS -o "$bin"
  mkdir -p "$OUT/corpus/$t" "$OUT/crashes/$t"
  echo "fuzz: running fuzz_$t ($LIMIT, -max_len=$MAX_LEN)"
  if ! (cd "$OUT/crashes/$t" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
        "$bin" "$LIMIT" -max_len="$MAX_LEN" -rss_limit_mb=2048 -timeout=10 \
        -print_final_stats=1 "$OUT/corpus/$t" > "$OUT/fuzz_$t.log" 2>&1); then
    echo "fuzz: fuzz_$t FAILED — see $OUT/fuzz_$t.log and $OUT/crashes/$t/"
    tail -40 "$OUT/fuzz_$t.log"
    status=1
  else
    grep -E "stat::number_of_executed_units|Done [0-9]+ runs" "$OUT/fuzz_$t.log" | tail -1 | sed "s/^/fuzz: fuzz_$t: /"
  fi
done
exit $status
