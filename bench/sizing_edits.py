#!/usr/bin/python3
"""Per-edit times of an `edit` session under size control (issue 35, docs/sizing.md "Lemma 7.2 under size
control"): N random shore moves on Lake Superior with --size-from-shore, as `edit --json` reports them.

    bench/sizing_edits.py SHOREMESH [N] [H0 RATE] [--seed S] [--spacing D] [--export MESH] [--size-edits] [-- MORE OPTIONS]

Each move takes a random shoreline vertex 30 % of the way towards the next one, a little off the segment
(as the random-edit tests do); moves the session refuses (a crossing) are skipped. Prints the medians
and 90th percentiles of the whole edit and of its parts as `edit` reports them (engine_ms holds h, the splits and the seeds as well as the engine's
propagation). --export writes the mesh (or with .csv the point set) after the last move (to compare two
builds' results). Options after `--` go to both runs (for example `-- --max-size 5000 --grade 0.15`).
--size-edits: `size 0 S` edit lines instead (S random in 1500..4500 m) of one size polygon, a 0.2 x 0.15
degree square in the open lake (87.1-86.9 W, 47.7-47.85 N), given with --size-polygons. --spacing D: the
shoreline's spacing in metres (4000 unless given; smaller gives more shore segments).
"""
import json
import os
import random
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MASK = os.path.join(HERE, "..", "samples", "superior", "superior_watermask_h.png")


def rings_of(path):
    rings, cur = [], []
    for line in open(path):
        line = line.strip()
        if line.startswith("#"):
            continue
        if not line:
            if cur:
                rings.append(cur[:-1] if len(cur) > 1 and cur[0] == cur[-1] else cur)
            cur = []
            continue
        x, y = line.replace(",", " ").split()[:2]
        cur.append((float(x), float(y)))
    if cur:
        rings.append(cur[:-1] if len(cur) > 1 and cur[0] == cur[-1] else cur)
    return rings


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    size_edits = "--size-edits" in argv
    argv = [a for a in argv if a != "--size-edits"]
    sys.argv = sys.argv[:1] + argv
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    seed = int(sys.argv[sys.argv.index("--seed") + 1]) if "--seed" in sys.argv else 35
    if "--seed" in sys.argv:
        args.remove(str(seed))
    spacing = sys.argv[sys.argv.index("--spacing") + 1] if "--spacing" in sys.argv else "4000"
    if "--spacing" in sys.argv:
        args.remove(spacing)
    export = sys.argv[sys.argv.index("--export") + 1] if "--export" in sys.argv else None
    if export:
        args.remove(export)
    binary = args[0]
    n = int(args[1]) if len(args) > 1 else 40
    h0, rate = (args[2], args[3]) if len(args) > 3 else ("1000", "0.05")
    common = [MASK, "--largest-water", "--spacing", spacing, "--size-from-shore", h0, rate, "-q", *extra]
    with tempfile.TemporaryDirectory() as work:
        if size_edits:
            poly = os.path.join(work, "p.geojson")
            with open(poly, "w") as f:
                json.dump({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"size": 3000},
                           "geometry": {"type": "Polygon", "coordinates": [[[-87.1, 47.7], [-86.9, 47.7], [-86.9, 47.85],
                                                                            [-87.1, 47.85], [-87.1, 47.7]]]}}]}, f)
            common += ["--size-polygons", poly]
        rings_path = os.path.join(work, "r.rings")
        subprocess.run([binary, "edit", *common, "--edits", "-"], input=f"export {rings_path}\n", text=True,
                       check=True, capture_output=True)
        rings = rings_of(rings_path)
        ids, first = [], 0
        for r in rings:
            ids.append(list(range(first, first + len(r))))
            first += len(r)
        rng = random.Random(seed)
        lines = []
        for _ in range(n if not size_edits else 0):
            r = rng.randrange(len(rings))
            while len(rings[r]) < 8:
                r = rng.randrange(len(rings))
            k = rng.randrange(len(rings[r]))
            a, b = rings[r][k], rings[r][(k + 1) % len(rings[r])]
            d = 0.1 * (rng.random() - 0.5)
            x = a[0] + 0.3 * (b[0] - a[0]) + d * (b[1] - a[1])
            y = a[1] + 0.3 * (b[1] - a[1]) - d * (b[0] - a[0])
            lines.append(f"move {ids[r][k]} {x!r} {y!r}")
        if size_edits:
            lines = [f"size 0 {1500 + 3000 * rng.random()!r}" for _ in range(n)]
        if export:
            lines.append(f"export {os.path.abspath(export)}")
        out = subprocess.run([binary, "edit", *common, "--json", "--edits", "-"], input="\n".join(lines) + "\n",
                             text=True, capture_output=True)
        replies = [json.loads(l) for l in out.stdout.splitlines() if l.startswith("{")]
        edits = [r for r in replies if "engine_ms" in r]
        refused = sum(1 for r in replies if "error" in r)
        print(f"binary {binary}: --spacing {spacing} --size-from-shore {h0} {rate} {' '.join(extra)}, {len(edits)} {'size edits' if size_edits else 'moves'} timed, "
              f"{refused} refused")
        if replies and "engine_ms" not in replies[0]:
            print("start:", json.dumps(replies[0])[:300])

        def stats(key):
            v = sorted(r[key] for r in edits)
            return f"median {v[len(v) // 2]:.1f} ms, p90 {v[int(0.9 * (len(v) - 1))]:.1f} ms" if v else "-"
        for key in ("ms", "rings_ms", "engine_ms", "mesh_ms"):
            print(f"  {key}: {stats(key)}")


if __name__ == "__main__":
    main()
