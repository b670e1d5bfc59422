#!/usr/bin/env python3
"""Side-by-side speed of two mpm3d builds (A and B), interleaved: every round runs A then B
(then B then A in the next round, so neither always goes first) on each deck at each thread
count. Prints, per deck and thread count, the median ns per particle-step of each build
over the rounds and the median of the per-round ratios B/A (below 1: B is faster). A
round's two runs are seconds apart, so the ratio of a round is what this noisy machine can
measure; compare builds only this way, never with a figure from another hour.

usage: ab_speed.py EXE_A EXE_B [--threads 1,2] [--rounds 7] [--steps 100] DECK...
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile


def ns_per_particle_step(exe, deck, threads, steps, summary):
    subprocess.run([exe, "--threads", str(threads), "--steps", str(steps), "--no-output", "--quiet",
                    "--summary", summary, deck], check=True)
    with open(summary) as f:
        return json.load(f)["ns_per_particle_step"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("exe_a")
    ap.add_argument("exe_b")
    ap.add_argument("decks", nargs="+")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--steps", type=int, default=100)
    a = ap.parse_args()
    threads = [int(t) for t in a.threads.split(",")]
    with tempfile.TemporaryDirectory() as tmp:
        summary = os.path.join(tmp, "s.json")
        print(f"{'deck':28s} {'threads':>7s} {'A ns':>9s} {'B ns':>9s} {'B/A':>7s}  (medians of {a.rounds} rounds)")
        for deck in a.decks:
            for t in threads:
                ta, tb, ratio = [], [], []
                for r in range(a.rounds):
                    order = [(a.exe_a, ta), (a.exe_b, tb)]
                    if r % 2:
                        order.reverse()
                    for exe, into in order:
                        into.append(ns_per_particle_step(exe, deck, t, a.steps, summary))
                    ratio.append(tb[-1] / ta[-1])
                print(f"{os.path.basename(deck):28s} {t:7d} {statistics.median(ta):9.1f} "
                      f"{statistics.median(tb):9.1f} {statistics.median(ratio):7.3f}", flush=True)


if __name__ == "__main__":
    main()
