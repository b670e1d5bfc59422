#!/usr/bin/env python3
"""Runs one of the current MPM3D-F90's public decks for STEPS steps and compares the energy
and curve files with the current program's own results (../shared/reference/current):
every column of EnergyPlot.dat and of the deck's curve file, row by row over the steps
run, must agree within TOL of that column's largest magnitude. Exit 77 (skipped) when the
shared deck or its reference is absent.

  current_reference.py [--skip-internal] MPM3D DECK REFDIR STEPS TOL OUTDIR [MPM3D OPTIONS...]

--skip-internal leaves out the internal energy (EnergyPlot's last column, the curve's engi
columns): for a deck whose internal energy is a tiny share of its total and is known to
differ (docs/CURRENT_DECKS.md says why).
"""
import os
import shutil
import subprocess
import sys


def rows(path, skip_header):
    with open(path) as f:
        lines = f.readlines()
    if skip_header:
        lines = lines[1:]
    return [[float(v) for v in l.split()] for l in lines if l.strip()]


def compare(name, ours, ref, n, tol, skip=()):
    if len(ours) < n or len(ref) < n:
        print("%s: %d rows here, %d in the reference, %d needed" % (name, len(ours), len(ref), n))
        return False
    ok = True
    for j in range(len(ref[0])):
        if j in skip:
            print("%s column %d: not compared" % (name, j))
            continue
        scale = max(abs(r[j]) for r in ref[:n])
        worst = max(abs(a[j] - b[j]) for a, b in zip(ours[:n], ref[:n]))
        rel = worst / scale if scale > 0 else worst
        flag = "" if rel <= tol else "  > %g" % tol
        print("%s column %d: largest difference %.3e of %.3e (%.2e)%s" % (name, j, worst, scale, rel, flag))
        ok = ok and rel <= tol
    return ok


def main():
    args = sys.argv[1:]
    skip_internal = bool(args) and args[0] == "--skip-internal"
    if skip_internal:
        args = args[1:]
    mpm3d, deck, refdir, steps, tol, outdir = args[:6]
    steps, tol = int(steps), float(tol)
    if not os.path.isfile(deck) or not os.path.isdir(refdir):
        print("skipped: %s or %s absent" % (deck, refdir))
        return 77
    shutil.rmtree(outdir, ignore_errors=True)
    os.makedirs(outdir)
    run = subprocess.run([mpm3d, "--steps", str(steps), "--out-dir", outdir] + args[6:] + [deck],
                         stdout=subprocess.DEVNULL)
    if run.returncode != 0:
        print("mpm3d exited with %d" % run.returncode)
        return 1
    base = os.path.basename(deck).split(".")[0]
    ok = compare("EnergyPlot", rows(os.path.join(outdir, "EnergyPlot.dat"), False),
                 rows(os.path.join(refdir, "EnergyPlot.dat"), False), steps, tol, (3,) if skip_internal else ())
    curve = base + "_curv.dat"
    if os.path.isfile(os.path.join(refdir, curve)):
        with open(os.path.join(refdir, curve)) as f:
            heads = f.readline().split()
        skip = tuple(j for j, h in enumerate(heads) if skip_internal and h.startswith("engi"))
        ok = compare("curve", rows(os.path.join(outdir, curve), True), rows(os.path.join(refdir, curve), True),
                     steps, tol, skip) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
