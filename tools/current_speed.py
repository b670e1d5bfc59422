#!/usr/bin/env python3
"""mpm3d against the current MPM3D-F90 itself, side by side, on its public decks.

usage: tools/current_speed.py BUILD_DIR ORIGINAL_EXE [--threads 2[,4,...]] [--rounds 3] [--steps 1000]
                              [--decks NAME[,NAME...]]

ORIGINAL_EXE is the current public program built on this machine (it is not part of the
repository: build it from github.com/xzhang66/MPM3D-F90 at commit 4a6275f for this
measurement only). Each deck of ../shared/decks/current is cut to its first STEPS steps (the
end time set to the time of that step in ../shared/reference/current, and QuLo's run-on rule
taken out, so that both programs stop there), then each round runs the original and mpm3d
one after the other (alternating which goes first; mpm3d once at each thread count given) and
takes both programs' own "time per particle-step". Prints per deck and thread count the
medians and the median of the per-round ratios original / mpm3d: this machine is noisy, and
a ratio of two runs seconds apart is what it can measure.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(os.path.dirname(ROOT), "shared")
DECKS = os.path.join(SHARED, "decks", "current")
REFS = os.path.join(SHARED, "reference", "current")


def shortened(deck, end_time, out):
    with open(deck) as f:
        lines = f.readlines()
    with open(out, "w") as f:
        for line in lines:
            words = line.split()
            key = words[0].lower()[:4] if words else ""
            if key == "endt":
                line = "endtime %.9g\n" % end_time
            elif key == "qulo":
                continue  # the run-on rule would carry the run to t = 100
            f.write(line)


def original_ns(exe, deck, work):
    run = subprocess.run([exe, deck], cwd=work, capture_output=True, text=True, input="")
    text = run.stdout
    for name in os.listdir(work):
        if name.endswith(".out"):
            with open(os.path.join(work, name), errors="replace") as f:
                text += f.read()
    m = re.search(r"Time per particle cycle:\s*([0-9.Ee+-]+)", text)
    return float(m.group(1)) if m else None


def mpm3d_ns(exe, deck, threads, work):
    summary = os.path.join(work, "summary.json")
    subprocess.run([exe, "--threads", str(threads), "--no-output", "--quiet", "--summary", summary, deck],
                   check=True, cwd=work)
    with open(summary) as f:
        return json.load(f)["ns_per_particle_step"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build")
    ap.add_argument("original")
    ap.add_argument("--threads", default="2", help="thread counts, comma separated")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--decks", default="", help="only the decks whose names contain one of these, comma separated")
    a = ap.parse_args()
    wanted = [w for w in a.decks.split(",") if w]
    threads = [int(t) for t in a.threads.split(",")]
    mpm3d = os.path.join(os.path.abspath(a.build), "cxx", "mpm3d")
    original = os.path.abspath(a.original)
    print("%-38s %7s %10s %10s %8s" % ("deck", "threads", "orig ns", "mpm3d ns", "ratio"))
    for name in sorted(f[:-4] for f in os.listdir(DECKS) if f.endswith(".mpm")):
        if wanted and not any(w in name for w in wanted):
            continue
        with open(os.path.join(REFS, name, "EnergyPlot.dat")) as f:
            times = [float(l.split()[0]) for l in f if l.strip()]
        end = times[min(a.steps, len(times)) - 1]
        orig, ours, ratios = [], {t: [] for t in threads}, {t: [] for t in threads}
        with tempfile.TemporaryDirectory() as work:
            deck = os.path.join(work, name + ".mpm")
            shortened(os.path.join(DECKS, name + ".mpm"), end, deck)
            for r in range(a.rounds):
                order = ["orig"] + threads if r % 2 == 0 else threads[::-1] + ["orig"]
                pair = {}
                for who in order:
                    if who == "orig":
                        pair[who] = original_ns(original, deck, work)
                    else:
                        pair[who] = mpm3d_ns(mpm3d, deck, who, work)
                if pair["orig"]:
                    orig.append(pair["orig"])
                    for t in threads:
                        ours[t].append(pair[t])
                        ratios[t].append(pair["orig"] / pair[t])
        if orig:
            for t in threads:
                print("%-38s %7d %10.1f %10.1f %8.2f" % (name, t, statistics.median(orig),
                                                         statistics.median(ours[t]),
                                                         statistics.median(ratios[t])), flush=True)
        else:
            print("%-38s %7s %10s" % (name, "", "failed"), flush=True)


if __name__ == "__main__":
    main()
