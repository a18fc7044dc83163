#!/usr/bin/python3
"""Dynamic benchmark (the paper's Figure 7, right): PropagateWS unit changes against StableWS from scratch.

    bench/run_dynamic.py BUILD_DIR [--dim 2|3] [--n N] [--write-only]

Runs bench_dynamic once per configuration below (one process each), then rewrites the section between
the dynamic:begin/end markers of bench/RESULTS.md (tables, targets, raw lines) and the plot
bench/dynamic_speedup.png. --dim and --n select some configurations; the others keep their raw lines
from RESULTS.md, so parts can be measured at different times. --write-only reruns nothing.
Needs Debian's python3-matplotlib for the plot (`apt-get install python3-matplotlib`).
"""
import argparse
import datetime
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
RESULTS = os.path.join(HERE, "RESULTS.md")
PLOT = os.path.join(HERE, "dynamic_speedup.png")
BEGIN, END = "<!-- dynamic:begin -->", "<!-- dynamic:end -->"
SEED = 1

# (dim, n, inputs, changes per input): 100 unit changes on each of several inputs, as in the paper;
# fewer inputs where one from-scratch run takes minutes.
CONFIGS = [
    (2, 1000, 10, 100), (2, 10000, 3, 100), (2, 100000, 3, 100), (2, 1000000, 2, 100),
    (3, 1000, 3, 100), (3, 10000, 3, 100), (3, 100000, 1, 100),
]
# The targets: median single-update latency, and speedup over a from-scratch run.
TARGETS = {(2, 1000000): (100e-6, 1e4), (3, 100000): (1e-3, None)}


def parse(line):
    return dict(kv.split("=", 1) for kv in line.split() if "=" in kv)


def git_source(build_dir):
    source_dir = "."
    try:
        with open(os.path.join(build_dir, "CMakeCache.txt")) as f:
            for line in f:
                if line.startswith("CMAKE_HOME_DIRECTORY:INTERNAL="):
                    source_dir = line.split("=", 1)[1].strip()
        return subprocess.run(["git", "-C", source_dir, "describe", "--always", "--dirty=+dirty"],
                              capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def previous_raw_lines():
    if not os.path.exists(RESULTS):
        return []
    text = open(RESULTS).read()
    if BEGIN not in text:
        return []
    section = text.split(BEGIN, 1)[1].split(END, 1)[0]
    return [l.strip() for l in section.splitlines() if l.startswith("dim=") and "run_at=" in l]


def fmt_time(s):
    s = float(s)
    return f"{s * 1e6:.0f} µs" if s < 1e-3 else f"{s * 1e3:.2f} ms" if s < 1 else f"{s:.2f} s"


def fmt_n(n):
    n = int(n)
    e = len(str(n)) - 1
    return f"1e{e}" if n == 10 ** e else str(n)


def section(lines):
    rows = sorted((parse(l) for l in lines), key=lambda f: (int(f["dim"]), int(f["n"])))
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    out = [BEGIN, "## Dynamic: PropagateWS unit changes vs StableWS from scratch (paper, Figure 7 right)", ""]
    out += [
        f"Machine: {os.cpu_count()} CPUs ({cpu}); section written {datetime.datetime.utcnow():%Y-%m-%dT%H:%MZ}; "
        "each run's date, 1-minute load and source commit are in its raw line. Inputs: `families::uniform(n, seed)` "
        "in the unit box, default rho = sqrt(2). A unit change removes a random input point and updates, then adds "
        "a random point and updates (the paper's definition); every update's output equals a from-scratch run "
        "(tests/engine/dynamic_test.cpp checks that bit for bit). Speedup = one from-scratch StableWS run / the mean "
        "unit change, in operations (dispatches + fills executed, plus those undone, for the update) and in wall "
        "time. Latency: one update (a remove or an add), median and 99th percentile over all updates; first "
        "update: the slower of the two updates of the first change after a build, the slowest over the inputs "
        "(what the first edit after loading costs).",
        "",
        "Command: `bench/run_dynamic.py BUILD_DIR` (`--dim`, `--n` to rerun a part), which runs from BUILD_DIR/bench:",
        "", "```sh"]
    out += [f"bench_dynamic --dim {f['dim']} --n {f['n']} --changes {f['changes_per_input']} --inputs {f['inputs']} "
            f"--seed {SEED}" for f in rows]
    out += ["```", "",
            "| dim | n | inputs × changes | output vertices | StableWS ops | ops per unit change | speedup (ops) | "
            "StableWS s | unit change | speedup (time) | one update: median | p99 | first update | ops per update: median | max |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for f in rows:
        out.append(
            f"| {f['dim']} | {fmt_n(f['n'])} | {f['inputs']} × {f['changes_per_input']} | {float(f['output_vertices']):,.0f} | "
            f"{float(f['build_ops']):,.0f} | {float(f['unit_change_ops']):,.1f} | {float(f['speedup_ops']):,.0f} | "
            f"{float(f['build_seconds']):.2f} | {fmt_time(f['unit_change_seconds'])} | {float(f['speedup_time']):,.0f} | "
            f"{fmt_time(f['update_median_seconds'])} | {fmt_time(f['update_p99_seconds'])} | "
            f"{fmt_time(f['first_update_seconds']) if 'first_update_seconds' in f else '-'} | "
            f"{f['update_median_ops']} | {f['update_max_ops']} |")
    out += ["", "Work per clipped Voronoi cell (what one operation costs), from scratch and during the updates "
            "(cells: computed, and taken again from the propagation's cell cache; searches: box queries to the "
            "tree per computed cell; leaves: those holding a vertex that the neighbour search read; empty ones "
            "are skipped unread):", "",
            "| dim | n | cells per update: computed | reused | searches per cell (build / updates) | "
            "leaves read (build / updates) | candidate vertices | half-spaces clipped |",
            "|---|---|---|---|---|---|---|---|"]
    for f in rows:
        reused = f.get("update_cells_reused", "-")
        searches = f"{f['build_searches_per_cell']} / {f['update_searches_per_cell']}" if "build_searches_per_cell" in f else "-"
        out.append(f"| {f['dim']} | {fmt_n(f['n'])} | {f['update_cells']} | {reused} | {searches} | {f['build_leaves_per_cell']} / "
                   f"{f['update_leaves_per_cell']} | {f['build_candidates_per_cell']} / {f['update_candidates_per_cell']} | "
                   f"{f['build_clips_per_cell']} / {f['update_clips_per_cell']} |")
    out += ["", "Targets of the issue:", ""]
    for (dim, n), (latency, speedup) in TARGETS.items():
        f = next((r for r in rows if int(r["dim"]) == dim and int(r["n"]) == n), None)
        if f is None:
            out.append(f"- {dim}D, n = {fmt_n(n)}: not measured.")
            continue
        median = float(f["update_median_seconds"])
        text = (f"- {dim}D, n = {fmt_n(n)}: median update {fmt_time(median)} against a target of "
                f"{fmt_time(latency)}: {'met' if median < latency else 'not met'} ({median / latency:.1f}× the target)")
        if speedup:
            s_ops, s_time = float(f["speedup_ops"]), float(f["speedup_time"])
            text += (f"; speedup {s_ops:,.0f} in operations and {s_time:,.0f} in time against a target of "
                     f"{speedup:,.0f}: {'met' if min(s_ops, s_time) >= speedup else 'not met'}")
        out.append(text + ".")
    out += ["", "![Speedup and update latency against n](dynamic_speedup.png)", "", "Raw lines:", "", "```text"]
    out += sorted(lines, key=lambda l: (int(parse(l)["dim"]), int(parse(l)["n"])))
    out += ["```", END]
    return "\n".join(out) + "\n"


def write_results(lines):
    body = section(lines)
    text = open(RESULTS).read() if os.path.exists(RESULTS) else "# Benchmark results\n"
    if BEGIN in text and END in text:
        head, rest = text.split(BEGIN, 1)
        text = head + body.rstrip("\n") + rest.split(END, 1)[1]
    else:
        text = text.rstrip("\n") + "\n\n" + body
    tmp = RESULTS + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, RESULTS)


def plot(lines):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("run_dynamic: no matplotlib (apt-get install python3-matplotlib): plot not drawn", file=sys.stderr)
        return
    rows = [parse(l) for l in lines]
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for dim, colour in ((2, "tab:blue"), (3, "tab:red")):
        rs = sorted((r for r in rows if int(r["dim"]) == dim), key=lambda r: int(r["n"]))
        if not rs:
            continue
        n = [int(r["n"]) for r in rs]
        left.plot(n, [float(r["speedup_ops"]) for r in rs], "o-", color=colour, label=f"{dim}D, operations")
        left.plot(n, [float(r["speedup_time"]) for r in rs], "s--", color=colour, label=f"{dim}D, wall time")
        right.plot(n, [float(r["update_median_seconds"]) for r in rs], "o-", color=colour, label=f"{dim}D, median")
        right.plot(n, [float(r["update_p99_seconds"]) for r in rs], "^:", color=colour, label=f"{dim}D, 99th percentile")
    for (dim, n), (latency, speedup) in TARGETS.items():
        colour = "tab:blue" if dim == 2 else "tab:red"
        right.plot([n], [latency], "*", color=colour, markersize=14, markerfacecolor="none",
                   label=f"{dim}D target (median)")
        if speedup:
            left.plot([n], [speedup], "*", color=colour, markersize=14, markerfacecolor="none", label=f"{dim}D target")
    for ax in (left, right):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("input points n (uniform)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    left.set_ylabel("speedup of one unit change over StableWS")
    left.set_title("PropagateWS speedup (paper, Figure 7 right)")
    right.set_ylabel("seconds per update")
    right.set_title("Latency of one update (remove or add)")
    fig.tight_layout()
    tmp = PLOT + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, PLOT)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build_dir")
    ap.add_argument("--dim", type=int)
    ap.add_argument("--n", type=int)
    ap.add_argument("--write-only", action="store_true")
    args = ap.parse_args()
    bench = os.path.join(args.build_dir, "bench", "bench_dynamic")
    if not args.write_only and not os.access(bench, os.X_OK):
        sys.exit(f"run_dynamic: {bench} not built (cmake --build {args.build_dir} --target bench_dynamic)")

    def selected(dim, n):
        return (args.dim is None or dim == args.dim) and (args.n is None or n == args.n)

    lines = previous_raw_lines()
    if not args.write_only:
        lines = [l for l in lines if not selected(int(parse(l)["dim"]), int(parse(l)["n"]))]
        source = git_source(args.build_dir)
        for dim, n, inputs, changes in CONFIGS:
            if not selected(dim, n):
                continue
            cmd = [bench, "--dim", str(dim), "--n", str(n), "--changes", str(changes), "--inputs", str(inputs),
                   "--seed", str(SEED)]
            print("running:", " ".join(cmd), file=sys.stderr, flush=True)
            load = open("/proc/loadavg").read().split()[0]
            run = subprocess.run(cmd, capture_output=True, text=True)
            if run.returncode != 0:
                print(f"run_dynamic: failed ({run.returncode}): {run.stderr.strip()}", file=sys.stderr)
                continue
            line = (run.stdout.strip() + f" run_at={datetime.datetime.utcnow():%Y-%m-%dT%H:%M:%SZ} load={load} "
                    f"source={source}")
            print(line, file=sys.stderr, flush=True)
            lines.append(line)
            write_results(lines)  # after each run: an interrupted run keeps what it measured
    write_results(lines)
    plot(lines)
    print(f"wrote {RESULTS} and {PLOT}", file=sys.stderr)


if __name__ == "__main__":
    main()
