#!/usr/bin/env python3
"""A stand-in for the original MPM3D-F90 in the mpm3d-compare tests: run as `fake_original.py
deck.mpm` like the original, it runs the real mpm3d on the deck and leaves EnergyPlot.dat and
NAME_curv.dat in the current directory. Run with mpm3d's options before the deck, it stands
in for mpm3d (passing them on), so that the tests can make that one reject a deck too.

It poses as the book program by its line '# mpm3d-compare: program=book' below, which
mpm3d-compare reads to tell which original program a script is (--original-program auto);
compare.cmake writes copies that pose as the current program (program=current) and as a
program it cannot tell (without the line). Which rules it runs by is MPM3D_FAKE_RULES's.

Environment:
  MPM3D_FAKE_MPM3D   the mpm3d program to run (required)
  MPM3D_FAKE_SCALE   COLUMN:FACTOR[:FROM], e.g. kinetic:1.05: multiply that column of
                     EnergyPlot.dat (total, kinetic, internal) or of the curve file (by its
                     header name), in the rows from time FROM on (default: all rows)
  MPM3D_FAKE_RULES   mpm3d options, e.g. "--rule bulk_book=ignore": the stand-in original runs
                     by these rules (as if the original differed from mpm3d by them)
  MPM3D_FAKE_REJECT  original: fail after the run (a message, exit 1, the files written);
                     stop: as the original's 'stop' (a message, exit 0, no files written);
                     mpm3d: reject the deck when run as mpm3d (exit 1)
"""
# mpm3d-compare: program=book
import json
import os
import subprocess
import sys

ENERGY_COLUMNS = ["Time", "total", "kinetic", "internal"]


def scale_column(path, names, column, factor, since):
    """Rewrite path with one column multiplied in the rows from time since on; the other
    fields keep their text."""
    with open(path) as f:
        lines = f.read().splitlines()
    out = []
    for line in lines:
        tokens = line.split()
        if not tokens or tokens[0] == "Time":
            out.append(line)
            names = tokens or names
            continue
        k = names.index(column)
        if float(tokens[0]) >= since:
            tokens[k] = "%.4E" % (float(tokens[k]) * factor)
        out.append("".join(t.rjust(12) for t in tokens))
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    deck, as_mpm3d = sys.argv[-1], len(sys.argv) > 2
    reject = os.environ.get("MPM3D_FAKE_REJECT", "")
    if as_mpm3d:
        if reject == "mpm3d":
            print("mpm3d: %s: fake mpm3d rejects the deck" % deck, file=sys.stderr)
            return 1
        return subprocess.run([os.environ["MPM3D_FAKE_MPM3D"]] + sys.argv[1:]).returncode
    if reject == "stop":
        print(" *** Error *** fake original: deck %s rejected" % deck)
        return 0
    summary = "fake_summary.json"
    rules = os.environ.get("MPM3D_FAKE_RULES", "").split()
    subprocess.run([os.environ["MPM3D_FAKE_MPM3D"], "--threads", "1", "--quiet", "--out-dir",
                    ".", "--summary", summary] + rules + [deck], check=True)
    with open(summary) as f:
        ns = json.load(f)["ns_per_particle_step"]
    print("** Time per particle cycle: %12.4f nanoseconds" % ns)
    if os.environ.get("MPM3D_FAKE_SCALE"):
        column, factor, since = (os.environ["MPM3D_FAKE_SCALE"] + ":-inf").split(":")[:3]
        curves = os.path.splitext(os.path.basename(deck))[0] + "_curv.dat"
        with open(curves) as f:
            curve_names = f.readline().split()
        if column in ENERGY_COLUMNS:
            scale_column("EnergyPlot.dat", ENERGY_COLUMNS, column, float(factor), float(since))
        else:
            scale_column(curves, curve_names, column, float(factor), float(since))
    if reject == "original":
        print(" *** Error *** fake original: deck %s rejected" % deck)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
