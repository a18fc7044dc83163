#!/usr/bin/env bash
# Element size control on Lake Superior (issue 35, docs/sizing.md) against gmsh on the same shoreline, in
# the same run. Prints one line per run (time, nodes, triangles) and the median per configuration.
#
#   bench/sizing.sh BUILD_DIR [REPEATS] [CONFIG...]     CONFIG: max (default both), shore
#
# shoremesh: `mesh superior_watermask_h.png --largest-water --spacing 4000` with --max-size 5000 --grade 0.15
# (max) or --size-from-shore 200 0.05 (shore). gmsh (Debian's, `gmsh -2`, default algorithm): the rings
# shoremesh traced (an `edit` session's `export X.rings`) as a .geo (bench/sizing_geo.py), with
# Mesh.MeshSizeMax 5000 and the shore points at 5000, boundary extension off (max), or a Distance field on every shore curve
# (NumPointsPerCurve 40) and a MathEval background field 200 + 0.05 * distance (shore), sizes from points,
# curvature and boundary off. gmsh has no gradient limit: the max run's field is uniform, and the shore
# term grows by 0.05, below the grade.
set -euo pipefail
build_dir=${1:?usage: $0 BUILD_DIR [REPEATS] [CONFIG...]}
repeats=${2:-3}
shift $(( $# >= 2 ? 2 : 1 ))
configs=("$@")
[[ ${#configs[@]} -gt 0 ]] || configs=(max shore)
here=$(cd "$(dirname "$0")" && pwd)
bin=$build_dir/tool/shoremesh
mask=$here/../samples/superior/superior_watermask_h.png
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
common=(--largest-water --spacing 4000 -q)
echo "machine: $(nproc) CPUs ($(grep -m1 '^model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')), load $(cut -d' ' -f1 /proc/loadavg)"
echo "commit: $(git -C "$here" describe --always --dirty=+dirty), gmsh $(gmsh --version 2>&1 | tail -1)"
echo "export $work/superior.rings" | "$bin" edit "$mask" "${common[@]}" --edits - >/dev/null

median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }

for config in "${configs[@]}"; do
  case $config in
    max) options=(--max-size 5000 --grade 0.15); python3 "$here/sizing_geo.py" "$work/superior.rings" "$work/s.geo" max 5000 ;;
    shore) options=(--size-from-shore 200 0.05); python3 "$here/sizing_geo.py" "$work/superior.rings" "$work/s.geo" shore 200 0.05 ;;
    *) echo "unknown config $config" >&2; exit 2 ;;
  esac
  : >"$work/ours" ; : >"$work/peer"
  for ((i = 0; i < repeats; i++)); do
    start=$(date +%s.%N)
    "$bin" mesh "$mask" "${common[@]}" "${options[@]}" -o "$work/out.msh" >"$work/log" 2>&1
    end=$(date +%s.%N)
    points=$(sed -n 's/^quality: \([0-9]*\) triangles, \([0-9]*\) points.*/\2 \1/p' "$work/log")
    seeds=$(sed -n 's/.*; \([0-9]*\) size seeds.*/\1/p' "$work/log")
    ratio=$(sed -n 's/.*longest edge \/ h(centroid) <= \([0-9.e+-]*\).*/\1/p' "$work/log")
    t=$(echo "$end - $start" | bc)
    echo "shoremesh $config run $i: ${t} s, nodes triangles: $points, seeds $seeds, worst longest/h $ratio, load $(cut -d' ' -f1 /proc/loadavg)"
    echo "$t" >>"$work/ours"
    start=$(date +%s.%N)
    status=0
    gmsh "$work/s.geo" -2 -format msh4 -o "$work/peer.msh" >"$work/glog" 2>&1 || status=$?
    end=$(date +%s.%N)
    t=$(echo "$end - $start" | bc)
    gnodes=$(awk '/^\$Nodes/{getline; print $2; exit}' "$work/peer.msh" 2>/dev/null || true)
    gtris=$(grep -o 'Info *: [0-9]* nodes [0-9]* elements' "$work/glog" | tail -1 || true)
    echo "gmsh $config run $i: ${t} s, exit $status, nodes $gnodes ($gtris)"
    [[ $status == 0 ]] || tail -5 "$work/glog"
    echo "$t" >>"$work/peer"
  done
  echo "median $config: shoremesh $(median <"$work/ours") s, gmsh $(median <"$work/peer") s"
done
