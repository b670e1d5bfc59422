#!/usr/bin/env python3
"""The newest MPM3D-F90's three 3D landslides (311,550 particles of clay: bimp, gimp, sgmp),
serially, side by side: the CPU time a step takes in the newest program and in mpm3d.

usage: tools/landslide_speed.py BUILD_DIR --newest EXE [--newest-decks DIR] [--runs DIR]
                                [--reps 3] [--t1 0.005] [--t2 0.025] [--csv FILE] [--decks BS,GIMP,SG]

Each deck runs to two end times t1 < t2 in both programs (mpm3d on one thread, --no-output;
the original writes its frames at t = 0 and at its outtime, after t2), the runs of one deck
interleaved (original t1, mpm3d t1, original t2, mpm3d t2) and repeated --reps times. A step's
cost is (CPU(t2) - CPU(t1)) / (steps(t2) - steps(t1)), user plus system time from the
process's rusage: the deck reading and the set-up drop out, and the figure holds on a machine
that runs other work too (wall times would not). The median over the repetitions is
printed with the ratio and, for the whole run to t = 5.5, the time it implies. The newest
program is built outside the repository (docs/CURRENT_DECKS.md says how); the decks are written
by the shared folder's make_landslide_decks.py into --runs.
"""
import argparse
import csv
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DECKS = ("BS", "GIMP", "SG")


def cut(src, dst, end):
    with open(src) as f:
        text = f.read()
    with open(dst, "w") as f:
        f.write(re.sub(r"(?m)^endtime .*$", "endtime %s" % end, text, count=1))


def cpu_run(cmd, cwd):
    """(CPU seconds of the child, its stdout+stderr)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.exit("landslide_speed: %s failed:\n%s" % (" ".join(cmd), p.stdout[-2000:]))
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), p.stdout


def original_steps(work):
    with open(os.path.join(work, "EnergyPlot.dat")) as f:
        return sum(1 for line in f if line.strip())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build")
    ap.add_argument("--newest", required=True)
    ap.add_argument("--newest-decks", default=os.path.join(ROOT, "..", "shared", "decks", "newest"))
    ap.add_argument("--runs", default="landslide_speed_runs")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--t1", default="0.005")
    ap.add_argument("--t2", default="0.025")
    ap.add_argument("--csv", default="")
    ap.add_argument("--decks", default=",".join(DECKS), help="which of BS, GIMP, SG (default: all)")
    a = ap.parse_args()
    mpm3d = os.path.join(os.path.abspath(a.build), "cxx", "mpm3d")
    newest = os.path.abspath(a.newest)
    runs = os.path.abspath(a.runs)
    os.makedirs(runs, exist_ok=True)
    if not all(os.path.exists(os.path.join(runs, d + ".mpm")) for d in DECKS):
        subprocess.run([sys.executable, os.path.join(a.newest_decks, "make_landslide_decks.py"), runs],
                       check=True, stdout=subprocess.DEVNULL)
    rows = []
    for d in a.decks.split(","):
        per = {"original": [], "mpm3d": []}
        steps = {}
        for rep in range(a.reps):
            cost = {}
            for t in (a.t1, a.t2):
                for who in ("original", "mpm3d"):
                    work = os.path.join(runs, "%s_%s_%s" % (d, who, t))
                    os.makedirs(work, exist_ok=True)
                    cut(os.path.join(runs, d + ".mpm"), os.path.join(work, d + ".mpm"), t)
                    if who == "original":
                        cpu, _ = cpu_run([newest, d + ".mpm"], work)
                        n = original_steps(work)
                    else:
                        cpu, _ = cpu_run([mpm3d, "--threads", "1", "--no-output", "--quiet", "--summary",
                                          "summary.json", d + ".mpm"], work)
                        with open(os.path.join(work, "summary.json")) as f:
                            n = json.load(f)["steps"]
                    cost[(who, t)] = (cpu, n)
            for who in ("original", "mpm3d"):
                (c1, n1), (c2, n2) = cost[(who, a.t1)], cost[(who, a.t2)]
                per[who].append((c2 - c1) / (n2 - n1))
                steps[who] = n2 - n1
            print("%s rep %d: original %.3f s/step, mpm3d %.3f s/step" % (d, rep + 1, per["original"][-1],
                                                                          per["mpm3d"][-1]), flush=True)
        o, m = statistics.median(per["original"]), statistics.median(per["mpm3d"])
        rows.append({"deck": d, "steps_compared": steps["mpm3d"], "original_s_per_step": "%.4f" % o,
                     "mpm3d_s_per_step": "%.4f" % m, "ratio": "%.2f" % (o / m),
                     "original_ns_per_particle_step": "%.0f" % (o / 311550 * 1e9),
                     "mpm3d_ns_per_particle_step": "%.0f" % (m / 311550 * 1e9),
                     "date": time.strftime("%Y-%m-%d"), "reps": a.reps})
        print("%s: original %.3f s, mpm3d %.3f s a step (serial CPU time): %.2fx" % (d, o, m, o / m), flush=True)
    if a.csv:
        new = not os.path.exists(a.csv)
        with open(a.csv, "a", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            if new:
                w.writeheader()
            w.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
