#!/usr/bin/env python3
"""Thread scaling on a many-core machine: mpm3d at 1..N threads, interleaved rounds.

usage: tools/scaling.py BUILD_DIR CSV [--threads 1,2,4,8,16] [--rounds 3] [--steps 100]
                        [--ref] DECK...

Each round runs every deck at every thread count once (`mpm3d --steps S --no-output`), so a
round's figures are seconds apart; the figure is the step loop's own ns per particle-step
(summary JSON). Per deck and thread count the CSV gets the best and the median over the
rounds, the speedup and efficiency of the best times against the best 1-thread time, and
the median over the rounds of each round's own speedup (its T-thread run against its
1-thread run), the figure to quote where the machine's speed drifts. With --ref, each round
also times the Fortran reference program `mpm3d_ref` (serial; (t(S steps) - t(0 steps)) /
(particles * S), deck reading left out) for the yardstick of docs/PERFORMANCE.md.
make bench (tools/bench.py) pins a 1-thread run to every CPU in each round, which suits a
2-core virtual machine; this driver is for 16 cores and more, where that would take hours.
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import tempfile
import time


def run_mpm3d(exe, deck, threads, steps, tmp):
    summary = os.path.join(tmp, "s.json")
    subprocess.run([exe, "--threads", str(threads), "--steps", str(steps), "--no-output", "--quiet",
                    "--summary", summary, deck], check=True, cwd=tmp)
    with open(summary) as f:
        return json.load(f)


def run_ref(ref, deck, steps, tmp):
    def wall(n):
        t0 = time.perf_counter()
        subprocess.run([ref, "--steps", str(n), "--quiet", deck], check=True, cwd=tmp,
                       stdout=subprocess.DEVNULL)
        return time.perf_counter() - t0
    return wall(steps) - wall(0)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("csv")
    ap.add_argument("decks", nargs="+")
    ap.add_argument("--threads", default="1,2,4,8,16")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument("--ref", action="store_true")
    a = ap.parse_args()
    exe = os.path.abspath(os.path.join(a.build, "cxx", "mpm3d"))
    ref = os.path.abspath(os.path.join(a.build, "fortran_ref", "mpm3d_ref"))
    threads = [int(t) for t in a.threads.split(",")]
    decks = [os.path.abspath(d) for d in a.decks]
    ns = {(d, t): [] for d in decks for t in threads}
    ref_ns = {d: [] for d in decks}
    particles = {}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            for d in decks:
                for t in threads:
                    s = run_mpm3d(exe, d, t, a.steps, tmp)
                    particles[d] = s["particles"]
                    ns[(d, t)].append(s["ns_per_particle_step"])
                if a.ref:
                    ref_ns[d].append(1e9 * run_ref(ref, d, a.steps, tmp) / (particles[d] * a.steps))
                print(f"round {r + 1} {os.path.basename(d)}: " +
                      " ".join(f"{t}:{ns[(d, t)][-1]:.1f}" for t in threads) +
                      (f" ref {ref_ns[d][-1]:.1f}" if a.ref else "") + " ns", flush=True)
    fields = ["deck", "particles", "threads", "rounds", "steps", "ns_best", "ns_median", "speedup",
              "efficiency", "round_speedup_median", "ref_ns_best", "ref_over_mpm3d"]
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for d in decks:
            base = min(ns[(d, 1)]) if 1 in threads else None
            for t in threads:
                best = min(ns[(d, t)])
                row = {"deck": os.path.basename(d), "particles": particles[d], "threads": t,
                       "rounds": a.rounds, "steps": a.steps, "ns_best": f"{best:.1f}",
                       "ns_median": f"{statistics.median(ns[(d, t)]):.1f}", "speedup": "", "efficiency": "",
                       "round_speedup_median": "", "ref_ns_best": "", "ref_over_mpm3d": ""}
                if base:
                    row["speedup"] = f"{base / best:.3f}"
                    row["efficiency"] = f"{base / best / t:.3f}"
                    row["round_speedup_median"] = f"{statistics.median(o / n for o, n in zip(ns[(d, 1)], ns[(d, t)])):.3f}"
                if a.ref and ref_ns[d]:
                    row["ref_ns_best"] = f"{min(ref_ns[d]):.1f}"
                    row["ref_over_mpm3d"] = f"{min(ref_ns[d]) / best:.2f}"
                w.writerow(row)
                print(" ".join(f"{k}={row[k]}" for k in fields), flush=True)


if __name__ == "__main__":
    main()
