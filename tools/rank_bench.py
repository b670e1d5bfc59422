#!/usr/bin/env python3
"""MPI ranks against OpenMP threads, side by side: mpm3d at ranks x threads 1x1, 1x2, 2x1.

usage: tools/rank_bench.py BUILD_DIR CSV [--configs 1x1,1x2,2x1] [--rounds 5] [--steps 100]
                           DECK...

Each round runs every deck at every configuration once, so a round's figures are seconds
apart (interleaved: this machine's speed drifts). The figure is the step loop's own ns per
particle-step on the root (summary JSON; it includes the time a rank waits for the others).
Per deck and configuration the CSV gets the best and the median over the rounds, the
median of each round's speed against that round's 1x1 run (speedup; efficiency = speedup /
cores used), the ranks' particle imbalance and the bytes the busiest rank sent per step.
The ranks run unbound (--bind-to none), as the threads do.
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import tempfile


def run(exe, mpirun, deck, ranks, threads, steps, tmp):
    summary = os.path.join(tmp, "s.json")
    cmd = [exe, "--threads", str(threads), "--steps", str(steps), "--no-output", "--quiet",
           "--summary", summary, deck]
    if ranks > 1:
        cmd = [mpirun, "--bind-to", "none", "-np", str(ranks)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    subprocess.run(cmd, check=True, cwd=tmp, env=env)
    with open(summary) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("csv")
    ap.add_argument("decks", nargs="+")
    ap.add_argument("--configs", default="1x1,1x2,2x1")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument("--mpirun", default="mpirun")
    a = ap.parse_args()
    exe = os.path.abspath(os.path.join(a.build, "cxx", "mpm3d"))
    configs = [tuple(int(v) for v in c.split("x")) for c in a.configs.split(",")]
    decks = [os.path.abspath(d) for d in a.decks]
    ns = {(d, c): [] for d in decks for c in configs}
    rel = {(d, c): [] for d in decks for c in configs}
    last = {}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            for d in decks:
                here = {}
                for c in configs:
                    s = run(exe, a.mpirun, d, c[0], c[1], a.steps, tmp)
                    here[c] = s["ns_per_particle_step"]
                    ns[(d, c)].append(here[c])
                    last[(d, c)] = s
                for c in configs:
                    if (1, 1) in here:
                        rel[(d, c)].append(here[(1, 1)] / here[c])
                print(f"round {r + 1}: {os.path.basename(d)} " +
                      "  ".join(f"{c[0]}x{c[1]} {here[c]:.1f}" for c in configs), flush=True)
    rows = []
    for d in decks:
        for c in configs:
            s = last[(d, c)]
            sp = statistics.median(rel[(d, c)]) if rel[(d, c)] else float("nan")
            rows.append({
                "deck": os.path.basename(d), "particles": s["particles"], "ranks": c[0], "threads": c[1],
                "best_ns": f"{min(ns[(d, c)]):.1f}", "median_ns": f"{statistics.median(ns[(d, c)]):.1f}",
                "speedup_median": f"{sp:.3f}", "efficiency_median": f"{sp / (c[0] * c[1]):.3f}",
                "rank_imbalance": f"{s.get('rank_imbalance', 1.0):.3f}",
                "bytes_per_step_per_rank": f"{s.get('rank_bytes_sent_per_step', 0.0):.0f}"})
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    for row in rows:
        print(",".join(str(v) for v in row.values()))


if __name__ == "__main__":
    main()
