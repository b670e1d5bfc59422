#!/usr/bin/env python3
"""Threads that pay, idle and busy (docs/PERFORMANCE.md): whole-process wall time of mpm3d
on one thread, on two with every step on both (--team fixed) and on two with the time loop
choosing (--team adaptive, the default), on an idle machine and next to one other busy process (a one-thread mpm3d run of the coarse Taylor bar,
restarted as it ends). The variants run one after the other, the order reversed every round;
the figure is the median over the rounds of each variant's time over the one-thread run's
time of the same round.

usage: team_bench.py BUILD CSV [--rounds N] [--decks PATH:STEPS,...]
"""
import argparse
import datetime
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SHARED = os.path.join(ROOT, "..", "shared", "decks")
DEFAULT_DECKS = [
    (os.path.join(ROOT, "inputs/taylor/taylor_coarse.mpm"), 200),
    (os.path.join(SHARED, "Deto1k.mpm"), 600),
    (os.path.join(ROOT, "inputs/impact/two_blocks.mpm"), 207),
    (os.path.join(ROOT, "inputs/granular/slope.mpm"), 2000),
]
VARIANTS = [
    ("one", ["--threads", "1", "--team", "fixed"], {}),
    ("two_fixed", ["--threads", "2", "--team", "fixed"], {}),
    ("two_adaptive", ["--threads", "2", "--team", "adaptive"], {}),
]


def run(mpm3d, deck, steps, opts, env, work):
    e = dict(os.environ, **env)
    t0 = time.perf_counter()
    subprocess.run([mpm3d, "--quiet", "--no-output", "--steps", str(steps)] + opts + [deck],
                   cwd=work, env=e, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build")
    ap.add_argument("csv")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--decks", default="")
    a = ap.parse_args()
    mpm3d = os.path.abspath(os.path.join(a.build, "cxx", "mpm3d"))
    decks = DEFAULT_DECKS
    if a.decks:
        decks = [(os.path.abspath(d.rsplit(":", 1)[0]), int(d.rsplit(":", 1)[1])) for d in a.decks.split(",")]
    decks = [(d, s) for d, s in decks if os.path.exists(d)]
    work = tempfile.mkdtemp(prefix="team-bench-")
    hog_deck = os.path.join(ROOT, "inputs/taylor/taylor_coarse.mpm")
    rows = []
    for condition in ("idle", "busy"):
        hog = None
        if condition == "busy":
            hog = subprocess.Popen(["sh", "-c", 'while :; do "$0" --quiet --no-output --threads 1 --team fixed "$1"; done',
                                    mpm3d, hog_deck], cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            time.sleep(1.0)
        try:
            for deck, steps in decks:
                ratios = {name: [] for name, _, _ in VARIANTS}
                times = {name: [] for name, _, _ in VARIANTS}
                for r in range(a.rounds):
                    order = VARIANTS if r % 2 == 0 else VARIANTS[::-1]
                    t = {name: run(mpm3d, deck, steps, opts, env, work) for name, opts, env in order}
                    for name in t:
                        times[name].append(t[name])
                        ratios[name].append(t[name] / t["one"])
                for name, _, _ in VARIANTS:
                    row = (condition, os.path.basename(deck), steps, name, statistics.median(times[name]),
                           statistics.median(ratios[name]))
                    rows.append(row)
                    print("%-5s %-20s %5d %-18s %7.3f s  %6.3f of one thread" % row, flush=True)
        finally:
            if hog:
                subprocess.run(["pkill", "-P", str(hog.pid)])
                hog.kill()
                hog.wait()
    today = datetime.date.today().isoformat()
    new = not os.path.exists(a.csv)
    with open(a.csv, "a") as f:
        if new:
            f.write("date,machine_cores,condition,deck,steps,variant,median_seconds,median_ratio_to_one_thread\n")
        for row in rows:
            f.write("%s,%d,%s,%s,%d,%s,%.4f,%.4f\n" % ((today, os.cpu_count()) + row))
    return 0


if __name__ == "__main__":
    sys.exit(main())
