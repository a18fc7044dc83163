#!/usr/bin/python3
"""Conforming water mesh benchmark (issue 33): Lake Superior at 196,843 shore points.

Makes the ring file: the GSHHG rings of ../shared/data/coast/lake_superior_lonlat.csv (lon/lat degrees) with
every ring edge cut into equal pieces of at most 0.0002 degrees (Euclidean length in degrees). Then, in
rounds (so that a change in the machine's load hits every program alike), runs each shoremesh build given
with --tool as

    taskset -c CPU /usr/bin/time -v SHOREMESH mesh RINGS.csv --lonlat -o WORK/LABEL.msh

and the CGAL peer (bench/cgal_cdt_peer.cpp) as

    taskset -c CPU /usr/bin/time -v cgal_cdt_peer RINGS.csv --lonlat

and, with --triangle PATH (a binary the user built from Shewchuk's public triangle.c: it is not shipped, its
license is not ours), Triangle on the same projected polygon written by the peer as a .poly (--write-poly):

    taskset -c CPU /usr/bin/time -v triangle -pq20.7 -Q WORK/superior.poly

Wall time and peak RSS come from /usr/bin/time (the whole process: reading, projecting, meshing, writing for
shoremesh; reading and projecting included for the peer too, whose own line also gives the CGAL-only time).
shoremesh's summary lines (quality, shoreline, 'at the shore') are parsed; independently, the exported .msh
is read back: water vertices (the vertices of its triangles), triangles, triangles whose smallest angle is
below arcsin(1/(2 sqrt 2)) = 20.705 deg, and which projected shore segments (written by the peer with
--write-segments, same reader and projection as shoremesh) are unions of mesh edges (exact rational
walk, within rounding of the line).

Usage:
  bench/superior_conforming.py --tool base=/path/shoremesh --tool new=/path/shoremesh \
      --peer BUILD/bench/cgal_cdt_peer [--triangle PATH] [--repeats 3] [--cpu 1] [--work DIR]
"""
import argparse
import math
import os
import re
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.normpath(os.path.join(HERE, "..", "..", "shared", "data", "coast", "lake_superior_lonlat.csv"))
STEP_DEG = 0.0002
BOUND_DEG = math.degrees(math.asin(1 / (2 * math.sqrt(2))))


def read_rings(path):
    rings, cur = [], []
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s or s[0] in "#>":
                if cur:
                    rings.append(cur)
                    cur = []
                continue
            x, y = s.split(",")[:2]
            cur.append((float(x), float(y)))
    if cur:
        rings.append(cur)
    for r in rings:
        if r[0] != r[-1]:
            sys.exit(f"{path}: a ring is not closed (first point {r[0]} repeated at its end expected)")
    return rings


def cut_rings(rings, step):
    """Each edge a-b into n = ceil(|b-a| / step) equal pieces; the ring stays closed by its first point."""
    out = []
    for r in rings:
        pts = []
        for a, b in zip(r, r[1:]):
            n = max(1, math.ceil(math.hypot(b[0] - a[0], b[1] - a[1]) / step))
            for k in range(n):
                pts.append((a[0] + (b[0] - a[0]) * k / n, a[1] + (b[1] - a[1]) * k / n))
        out.append(pts)
    return out


def write_ring_file(path, rings):
    with open(path, "w") as f:
        # No column names in the comment: a first line naming lat and lon columns reads as a GPS track.
        f.write(f"# Lake Superior shore (GSHHG high), every edge cut into equal pieces of at most {STEP_DEG} degrees\n")
        for r in rings:
            f.write("\n")
            for x, y in r + [r[0]]:
                f.write(f"{x!r},{y!r}\n")


def run_timed(cmd, cpu):
    full = ["taskset", "-c", str(cpu), "/usr/bin/time", "-v"] + cmd
    with open("/proc/loadavg") as f:
        load = float(f.read().split()[0])  # the 1-minute load when the run starts (2 cores, shared)
    p = subprocess.run(full, capture_output=True, text=True)
    err = p.stderr
    m = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (?:(\d+):)?(\d+):([\d.]+)", err)
    wall = (int(m.group(1) or 0) * 3600 + int(m.group(2)) * 60 + float(m.group(3))) if m else float("nan")
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", err).group(1)) / 1024
    user = float(re.search(r"User time \(seconds\): ([\d.]+)", err).group(1))
    sys_t = float(re.search(r"System time \(seconds\): ([\d.]+)", err).group(1))
    return {"cmd": " ".join(full), "rc": p.returncode, "wall_s": wall, "cpu_s": user + sys_t, "rss_mb": rss, "load": load,
            "stdout": p.stdout, "stderr": err}


def parse_summary(text):
    s = {}
    m = re.search(r"quality: (\d+) triangles, (\d+) points \((\d+) input, (\d+) Steiner\); bound met by (\d+) of (\d+)",
                  text)
    if m:
        s.update(triangles=int(m.group(1)), points=int(m.group(2)), input=int(m.group(3)), steiner=int(m.group(4)),
                 covered_meeting=int(m.group(5)), covered=int(m.group(6)))
    m = re.search(r"(\d+) of (\d+) meet it overall", text)
    if m:
        s["meeting_overall"] = int(m.group(1))
    for key in ("shoreline", "at the shore", "angles", "input", "projected"):
        m = re.search(r"^\s*" + key + r"[: ].*$", text, re.M)
        if m:
            s[key + "_line"] = m.group(0).strip()
    return s


def read_msh(path):
    """Gmsh 4.1 ASCII as shoremesh writes it: (node coordinates as text, triangles as node indices)."""
    with open(path) as f:
        lines = f.read().split("\n")
    i = lines.index("$Nodes")
    nblocks = int(lines[i + 1].split()[0])
    j = i + 2
    tags, coords = [], []
    for _ in range(nblocks):
        _, _, _, n = map(int, lines[j].split())
        tags += [int(t) for t in lines[j + 1:j + 1 + n]]
        coords += [tuple(lines[k].split()[:2]) for k in range(j + 1 + n, j + 1 + 2 * n)]
        j += 1 + 2 * n
    node = dict(zip(tags, coords))
    i = lines.index("$Elements")
    nblocks = int(lines[i + 1].split()[0])
    j = i + 2
    tris = []
    for _ in range(nblocks):
        _, _, etype, n = map(int, lines[j].split())
        if etype == 2:
            tris += [tuple(int(v) for v in lines[k].split()[1:4]) for k in range(j + 1, j + 1 + n)]
        j += 1 + n
    return node, tris


def read_triangle(prefix):
    """Triangle's PREFIX.node and PREFIX.ele (first attribute-free columns), in read_msh's form."""
    def rows(path):
        with open(path) as f:
            out = [l.split("#", 1)[0].split() for l in f]
        return [r for r in out if r]
    nodes = rows(prefix + ".node")
    node = {int(r[0]): (r[1], r[2]) for r in nodes[1:1 + int(nodes[0][0])]}
    eles = rows(prefix + ".ele")
    tris = [tuple(int(v) for v in r[1:4]) for r in eles[1:1 + int(eles[0][0])]]
    return node, tris


def analyse_mesh(msh, segments_path):
    return analyse_elements(*read_msh(msh), segments_path)


def analyse_elements(node, tris, segments_path):
    xy = {t: (float(c[0]), float(c[1])) for t, c in node.items()}
    used = set()
    below, min_angle = 0, 180.0
    adj = {}
    for tri in tris:
        used.update(tri)
        pts = [xy[v] for v in tri]
        smallest = 180.0
        for k in range(3):
            a, b, c = pts[k], pts[(k + 1) % 3], pts[(k + 2) % 3]
            u = (b[0] - a[0], b[1] - a[1])
            w = (c[0] - a[0], c[1] - a[1])
            smallest = min(smallest, math.degrees(math.atan2(abs(u[0] * w[1] - u[1] * w[0]), u[0] * w[0] + u[1] * w[1])))
        min_angle = min(min_angle, smallest)
        below += smallest < BOUND_DEG - 1e-9
        for k in range(3):
            a, b = tri[k], tri[(k + 1) % 3]
            adj.setdefault(a, set()).add(b)
            adj.setdefault(b, set()).add(a)
    result = {"water_vertices": len(used), "triangles": len(tris), "below_bound": below, "min_angle": min_angle}
    if segments_path:
        # A shore point is the mesh vertex with the very same double (both written as shortest round-trip
        # decimals). A segment a-b is covered when a walk from a along mesh edges, each to a vertex that is
        # no shore point (or is b), nearer b and within 1e-9 of the segment's length of its line, reaches b.
        # Not exact collinearity: a split point (shoremesh's canonical midpoint, CGAL's midpoint) is computed
        # in doubles and lies off the line by a rounding; the largest such distance is reported.
        by_xy = {xy[t]: t for t in used}
        segs = []
        with open(segments_path) as f:
            for line in f:
                x1, y1, x2, y2 = map(float, line.split())
                segs.append(((x1, y1), (x2, y2)))
        shore = {p for s in segs for p in s}
        total = covered = missing_ends = 0
        off_line = 0.0
        for pa, pb in segs:
            total += 1
            a, b = by_xy.get(pa), by_xy.get(pb)
            if a is None or b is None:
                missing_ends += 1
                continue
            length = math.hypot(pb[0] - pa[0], pb[1] - pa[1])
            v, steps = a, 0
            while v != b and steps < 100000:
                pv = xy[v]
                remaining = math.hypot(pb[0] - pv[0], pb[1] - pv[1])
                nxt = None
                for w in adj.get(v, ()):
                    pw = xy[w]
                    if w != b and pw in shore:
                        continue
                    d = 0.0 if w == b else abs((pb[0] - pa[0]) * (pw[1] - pa[1]) - (pb[1] - pa[1]) * (pw[0] - pa[0])) / length
                    if d <= 1e-9 * length and math.hypot(pb[0] - pw[0], pb[1] - pw[1]) < remaining:
                        nxt = w
                        off_line = max(off_line, d)
                        break
                if nxt is None:
                    break
                v, steps = nxt, steps + 1
            covered += v == b
        result.update(segments=total, segments_covered=covered, segment_ends_not_vertices=missing_ends,
                      split_off_line_m=off_line)
    return result


def parse_peer(stdout):
    line = next((l for l in stdout.splitlines() if l.startswith("peer=")), "")
    return dict(kv.split("=", 1) for kv in line.split()), line


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tool", action="append", default=[], help="LABEL=PATH of a shoremesh binary (repeatable)")
    ap.add_argument("--peer", help="path of cgal_cdt_peer")
    ap.add_argument("--triangle", help="path of a Triangle binary (needs --peer, which writes the .poly)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cpu", type=int, default=1)
    ap.add_argument("--work", default="/tmp/superior_conforming")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)

    rings = cut_rings(read_rings(SOURCE), STEP_DEG)
    ring_file = os.path.join(args.work, "superior_0.0002deg.csv")
    write_ring_file(ring_file, rings)
    print(f"ring file {ring_file}: {len(rings)} rings, {sum(len(r) for r in rings)} shore points "
          f"(from {SOURCE}, edges cut to <= {STEP_DEG} deg)", flush=True)

    tools = [t.split("=", 1) for t in args.tool]
    segments = None
    runs = {label: [] for label, _ in tools}
    peer_runs = []
    if args.peer:
        segments = os.path.join(args.work, "segments_m.txt")
        r = subprocess.run([args.peer, ring_file, "--lonlat", "--write-segments", segments], capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"peer failed writing the segments: {r.stderr}")
    triangle_runs = []
    poly = os.path.join(args.work, "superior.poly")
    if args.triangle:
        if not args.peer:
            sys.exit("--triangle needs --peer (the peer writes the projected polygon)")
        r = subprocess.run([args.peer, ring_file, "--lonlat", "--write-poly", poly], capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"peer failed writing the .poly: {r.stderr}")
    for rep in range(args.repeats):
        for label, path in tools:
            out = os.path.join(args.work, f"{label}.msh")
            r = run_timed([path, "mesh", ring_file, "--lonlat", "-o", out], args.cpu)
            r["summary"] = parse_summary(r["stdout"] + r["stderr"])
            runs[label].append(r)
            print(f"[{rep + 1}/{args.repeats}] {label}: rc={r['rc']} wall={r['wall_s']:.2f}s cpu={r['cpu_s']:.2f}s "
                  f"rss={r['rss_mb']:.1f}MB load={r['load']:.2f}", flush=True)
            if r["rc"] != 0:
                print(r["stderr"][-3000:], flush=True)
        if args.peer:
            r = run_timed([args.peer, ring_file, "--lonlat"], args.cpu)
            r["peer"], r["line"] = parse_peer(r["stdout"])
            peer_runs.append(r)
            print(f"[{rep + 1}/{args.repeats}] peer: rc={r['rc']} wall={r['wall_s']:.2f}s cpu={r['cpu_s']:.2f}s "
                  f"rss={r['rss_mb']:.1f}MB load={r['load']:.2f} "
                  f"{r['line']}", flush=True)
        if args.triangle:
            r = run_timed([args.triangle, "-pq20.7", "-Q", poly], args.cpu)
            triangle_runs.append(r)
            print(f"[{rep + 1}/{args.repeats}] triangle: rc={r['rc']} wall={r['wall_s']:.2f}s cpu={r['cpu_s']:.2f}s "
                  f"rss={r['rss_mb']:.1f}MB load={r['load']:.2f}", flush=True)

    print("\n## results")
    rows = []
    for label, path in tools:
        rs = runs[label]
        ok = [r for r in rs if r["rc"] == 0]
        print(f"### {label}: {path}")
        print(f"command: {rs[0]['cmd']}")
        out = rs[0]["stdout"] + rs[0]["stderr"]
        print("summary (run 1):")
        for l in out.splitlines():
            if not l.startswith(("\tCommand", "\t")) and "Command being timed" not in l:
                print("  | " + l)
        if not ok:
            rows.append((label, None))
            continue
        m = analyse_mesh(os.path.join(args.work, f"{label}.msh"), segments)
        print(f"exported mesh: {m}")
        rows.append((label, dict(wall=statistics.median(r["wall_s"] for r in ok),
                                 cpu=statistics.median(r["cpu_s"] for r in ok),
                                 rss=statistics.median(r["rss_mb"] for r in ok),
                                 walls=[r["wall_s"] for r in ok], rsss=[r["rss_mb"] for r in ok], **m,
                                 summary=ok[0]["summary"])))
    if peer_runs:
        ok = [r for r in peer_runs if r["rc"] == 0]
        p = ok[0]["peer"]
        print(f"### peer: {args.peer}\ncommand: {peer_runs[0]['cmd']}")
        for r in peer_runs:
            print("  " + r["line"])
        rows.append(("cgal peer", dict(wall=statistics.median(r["wall_s"] for r in ok),
                                       cpu=statistics.median(r["cpu_s"] for r in ok),
                                       rss=statistics.median(r["rss_mb"] for r in ok),
                                       cgal_s=statistics.median(float(r["peer"]["seconds"]) for r in ok),
                                       walls=[r["wall_s"] for r in ok], rsss=[r["rss_mb"] for r in ok],
                                       water_vertices=int(p["water_vertices"]), triangles=int(p["water_triangles"]),
                                       below_bound=int(p["below_20.7deg"]), min_angle=float(p["min_angle_deg"]),
                                       segments=int(p["segments"]), segments_covered=int(p["segments_mesh_edges"]))))

    if triangle_runs:
        ok = [r for r in triangle_runs if r["rc"] == 0]
        print(f"### triangle: {args.triangle}\ncommand: {triangle_runs[0]['cmd']}")
        if ok:
            m = analyse_elements(*read_triangle(poly[:-len(".poly")] + ".1"), segments)
            print(f"triangle's mesh: {m}")
            rows.append(("triangle -pq20.7", dict(wall=statistics.median(r["wall_s"] for r in ok),
                                                 cpu=statistics.median(r["cpu_s"] for r in ok),
                                                 rss=statistics.median(r["rss_mb"] for r in ok),
                                                 walls=[r["wall_s"] for r in ok], rsss=[r["rss_mb"] for r in ok], **m)))
        else:
            rows.append(("triangle -pq20.7", None))

    print("\n| run | median wall s (3 runs) | median CPU s | peak RSS MB (median) | water vertices | water triangles "
          "| shore segments that are mesh edges (exported mesh) | triangles below 20.7° | smallest angle |")
    print("|---|---|---|---|---|---|---|---|---|")
    for label, d in rows:
        if d is None:
            print(f"| {label} | failed | | | | | | | |")
            continue
        seg = f"{d.get('segments_covered', '?')} of {d.get('segments', '?')}"
        print(f"| {label} | {d['wall']:.2f} ({', '.join(f'{w:.2f}' for w in d['walls'])}) | {d['cpu']:.2f} "
              f"| {d['rss']:.0f} | {d['water_vertices']} | {d['triangles']} | {seg} | {d['below_bound']} "
              f"| {d['min_angle']:.2f}° |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
