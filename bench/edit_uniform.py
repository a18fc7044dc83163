#!/usr/bin/env python3
"""`shoremesh edit` on uniform random points: the whole edit's latency (issue 38's 10^6 target).

    bench/edit_uniform.py --tool NAME=SHOREMESH [--tool NAME=SHOREMESH ...] [--n 1000000] [--changes 10000]
                          [--seed 1] [--rounds 1] [--cpu C] [--threads T] [--work DIR]

Writes N points uniform in the unit square (Python's Mersenne Twister, seeded: the same file every run) and
an edit script of CHANGES unit changes, each `remove ID` of a random live point then `add X Y` of a new
uniform point (the paper's unit change, as bench_dynamic makes it; ids as the tool numbers them: inputs 0..N-1,
each add the next). Each tool runs `edit POINTS --box 0 0 1 --json --edits SCRIPT` (pinned with taskset
to core C if given; --threads T passed through, default 1), tools alternated within each round. Prints
per run: the build reply's ms, then the median, 90th and 99th percentile of the edit replies' `ms` (the
whole edit), `engine_ms` and `mesh_ms`, separately for removes and adds and over both, and the process's
user and system CPU seconds (build included). The edit replies of every tool are compared (Steiner points
and elements changed): they must agree edit for edit.
"""
import argparse
import json
import os
import random
import resource
import statistics
import subprocess
import sys
import time


def quantile(values, q):
    v = sorted(values)
    return v[min(len(v) - 1, int(q * len(v)))]


def write_inputs(work, n, changes, seed):
    points = os.path.join(work, f"uniform_{n}_{seed}.csv")
    script = os.path.join(work, f"edits_{n}_{changes}_{seed}.txt")
    rng = random.Random(seed)
    if not os.path.exists(points):
        with open(points + ".tmp", "w") as f:
            f.write("x,y\n")
            for _ in range(n):
                f.write(f"{rng.random()!r},{rng.random()!r}\n")
        os.replace(points + ".tmp", points)
    rng = random.Random(seed * 7919 + 1)
    ids = list(range(n))
    next_id = n
    lines = []
    for _ in range(changes):
        k = rng.randrange(len(ids))
        lines.append(f"remove {ids[k]}")
        lines.append(f"add {rng.random()!r} {rng.random()!r}")
        ids[k] = next_id
        next_id += 1
    with open(script, "w") as f:
        f.write("\n".join(lines) + "\n")
    return points, script


def run_once(binary, points, script, cpu, threads):
    cmd = [binary, "edit", points, "--box", "0", "0", "1", "-q", "--json", "--threads", str(threads), "--edits", script]
    if cpu is not None:
        cmd = ["taskset", "-c", str(cpu)] + cmd
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    out = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({out.returncode}): {out.stderr[-2000:]}")
    replies = [json.loads(line) for line in out.stdout.splitlines() if line.strip()]
    return replies, wall, after.ru_utime - before.ru_utime, after.ru_stime - before.ru_stime


def summary(replies):
    build, edits = replies[0], [r for r in replies[1:] if "engine_ms" in r]
    fields = {"build_ms": build.get("ms", float("nan")), "edits": len(edits)}
    kinds = {"all": edits, "remove": edits[0::2], "add": edits[1::2]}
    for kind, rs in kinds.items():
        for key in ("ms", "engine_ms", "mesh_ms"):
            v = [r[key] for r in rs]
            fields[f"{kind}_{key}_median"] = statistics.median(v)
            if kind == "all":
                fields[f"{kind}_{key}_p90"] = quantile(v, 0.9)
                fields[f"{kind}_{key}_p99"] = quantile(v, 0.99)
    return fields


def fingerprint(replies):
    """What an edit changed, without its times and its work: equal for engines with equal outputs. The count
    of operations an update reran is work, not output: engines that rerun fewer operations (an idle fill
    decided by another witness) give the same points and elements with another count."""
    drop = {"ms", "engine_ms", "mesh_ms", "check_ms", "classify_ms", "rebuild_ms", "shore_ms", "operations"}
    return [json.dumps({k: v for k, v in r.items() if k not in drop and not k.endswith("_ms")}, sort_keys=True)
            for r in replies[1:]]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tool", action="append", required=True, help="NAME=path to the shoremesh binary")
    ap.add_argument("--n", type=int, default=1000000)
    ap.add_argument("--changes", type=int, default=10000, help="unit changes: one remove and one add each")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--cpu", type=int, default=None, help="pin every run to this core (taskset)")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--work", default="/tmp/edit_uniform")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    tools = [t.split("=", 1) for t in a.tool]
    points, script = write_inputs(a.work, a.n, a.changes, a.seed)
    print(f"n={a.n} changes={a.changes} ({2 * a.changes} edits) seed={a.seed} cpu={a.cpu} threads={a.threads} "
          f"points={points} script={script}", flush=True)
    reference = None
    for r in range(a.rounds):
        order = tools if r % 2 == 0 else tools[::-1]
        for name, binary in order:
            load = open("/proc/loadavg").read().split()[0]
            replies, wall, user, system = run_once(binary, points, script, a.cpu, a.threads)
            s = summary(replies)
            fp = fingerprint(replies)
            if reference is None:
                reference = fp
            same = "same" if fp == reference else "DIFFERENT"
            line = " ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}" for k, v in s.items())
            print(f"round={r + 1} tool={name} load_before={load} wall_s={wall:.1f} user_s={user:.1f} sys_s={system:.1f} "
                  f"replies={same} {line}", flush=True)


if __name__ == "__main__":
    main()
