#!/usr/bin/env bash
# The shoremesh demo (`make demo`): the bundled Lake Superior water mask to a quality mesh and a preview,
# then a short edit session (shoreline points moved, points added) with per-edit timings, a check that
# the edited result equals a fresh run on the edited input, and exports for Gmsh and for a GIS.
# Everything goes to OUTDIR.
#
#   scripts/demo.sh SHOREMESH OUTDIR
set -euo pipefail

[[ $# -eq 2 ]] || { echo "usage: $0 SHOREMESH OUTDIR" >&2; exit 2; }
tool=$1
out=$2
here=$(cd "$(dirname "$0")/.." && pwd)
[[ -x $tool ]] || { echo "$0: $tool is not an executable (build it first: make build)" >&2; exit 1; }

# The bundled sample: GSHHG water mask of Lake Superior with its world file and .prj (samples/superior/NOTICE).
image=$here/samples/superior/superior_watermask_h.png
[[ -f $image ]] || { echo "$0: the Lake Superior sample $image is missing" >&2; exit 1; }

mkdir -p "$out"
out=$(cd "$out" && pwd)
start=$(date +%s.%N)
# The lake only (not the inland lakes around it), shore samples at most 4 km apart: about 2,900 points.
read_opts=("$image" --largest-water --spacing 4000)
step() { printf '\n== %s\n' "$*"; }

step "1. What the image holds"
"$tool" info "${read_opts[@]}"

step "2. The image to a mesh (Gmsh) and a preview"
"$tool" mesh "${read_opts[@]}" -o "$out/superior.msh" --preview "$out/superior.png" --preview-width 800

step "3. The point set (input points by id, then Steiner points) to choose edits from, and a quality preview"
"$tool" mesh -q "${read_opts[@]}" -o "$out/superior_points.csv" --preview "$out/superior_quality.png" \
  --preview-colour quality --preview-width 800 >/dev/null 2>&1
n=$("$tool" info "${read_opts[@]}" | sed -n 's/^input: \([0-9]*\) .*/\1/p')
echo "$n input points (ids 0..$((n - 1))) in $out/superior_points.csv"

# Shore point k moved across the chord of its neighbours k-1, k+1 by 1.2 chord lengths (sign s), and two
# points added to the new shoreline (ring vertices, halfway along its edges): the edit lines.
awk -F, -v n="$n" -v out="$out" '
  NR > 1 && NR <= n + 1 { k = NR - 2; x[k] = $1 + 0; y[k] = $2 + 0; sx[k] = $1; sy[k] = $2 }
  function put(k, px, py) {  # the text the session and the fresh run both read
    sx[k] = sprintf("%.3f", px); sy[k] = sprintf("%.3f", py); x[k] = sx[k] + 0; y[k] = sy[k] + 0
  }
  function move(k, s,   tx, ty, len) {
    tx = x[k + 1] - x[k - 1]; ty = y[k + 1] - y[k - 1]; len = sqrt(tx * tx + ty * ty)
    put(k, x[k] + s * 1.2 * len * (-ty / len), y[k] + s * 1.2 * len * (tx / len))
    printf "move %d %s %s\n", k, sx[k], sy[k]
  }
  function add(a, b) {  # onto the shoreline, between shore points a and b
    put(n, (x[a] + x[b]) / 2, (y[a] + y[b]) / 2)
    printf "add %s %s after %d\n", sx[n], sy[n], a; ++n
  }
  END {
    print "stats"
    move(600, 1)
    printf "preview-change %s/change_move.png\n", out
    move(700, -1)
    move(900, 1)
    add(599, 600)
    add(600, 601)
    printf "preview-change %s/change_add.png\n", out
    print "stats"
    printf "export %s/superior_edited.msh\n", out
    printf "export %s/superior_edited.geojson\n", out
    printf "export %s/superior_edited.csv\n", out
    printf "export %s/superior_edited.rings\n", out
    printf "preview %s/superior_edited.png\n", out
  }' "$out/superior_points.csv" >"$out/edits.txt"
step "4. Edits, applied dynamically (edits.txt), one reply each with its timing"
cat "$out/edits.txt"
echo
"$tool" edit "${read_opts[@]}" --edits "$out/edits.txt" --preview-width 800 | tee "$out/edit_log.txt"

step "5. The edited result equals a fresh run on the edited input (same box)"
box=$(head -1 "$out/superior_edited.csv" | sed 's/^# box //')
# The session's shoreline (superior_edited.rings) read afresh: the same points, the shore's canonical
# splits included (the fresh run lists the ring points in ring order, the session by id: compared sorted).
"$tool" mesh -q "$out/superior_edited.rings" --box $box -o "$out/fresh.csv" >/dev/null 2>&1
if cmp -s <(sort "$out/fresh.csv") <(sort "$out/superior_edited.csv"); then
  echo "identical: superior_edited.csv = shoremesh mesh superior_edited.rings --box $box -o fresh.csv (as sets)"
else
  echo "DIFFERENT: $out/superior_edited.csv and $out/fresh.csv" >&2
  exit 1
fi

end=$(date +%s.%N)
step "Done in $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }') s. Look at:"
cat <<EOF2
  $out/superior.png            the mesh of the lake (input points red, Steiner points blue)
  $out/superior_quality.png    the same, triangles coloured by their smallest angle
  $out/change_move.png         what moving shore point 600 changed (red: removed, green: added)
  $out/change_add.png          what adding two shore points changed
  $out/superior_edited.png     the mesh after all edits
  $out/superior.msh            for Gmsh (gmsh $out/superior.msh); superior_edited.msh after the edits
  $out/superior_edited.geojson for a GIS (lon/lat, e.g. QGIS: Layer > Add Vector Layer)
  $out/edit_log.txt            the edit replies with their timings
EOF2
echo
echo "Edit it in the browser (drag shore points, watch the mesh follow; exports go to $out):"
echo "  $tool serve ${read_opts[*]} --export-dir $out"
echo "and open the http://127.0.0.1:PORT/ address it prints."
