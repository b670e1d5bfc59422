#!/usr/bin/env python3
"""Cook's membrane decks in the current MPM3D-F90's form, and the tip-displacement study.

The membrane is the trapezoid (0,0) (48,44) (48,60) (0,44), one unit thick, clamped on
x = 0, loaded on its right edge by a vertical force of 1 in total, neo-Hookean (rho 1,
E 70, nu 0.499: nearly incompressible), brought to rest quasi-statically (QuLo 15, Damp 0.3,
run on until the kinetic share of the energy is below 0.005 and t > 100). The particles are
a square lattice of spacing h/2 (two per cell and axis in the plane, one layer at z = 0)
clipped to the trapezoid, each with the trapezoid's area over the particle count as its
volume, as in the public deck; the right column carries the load (half at its two ends).

  cook_membrane.py deck METHOD H OUT.mpm   write one deck (METHOD mpm, gimp, bimp or sgmp)
  cook_membrane.py study MPM3D OUTDIR      run every method at h = 4, 2, 1 and write the
                                           table of tip displacements (OUTDIR/cook.md)
"""
import math
import os
import subprocess
import sys

WIDTH, LEFT_H, RIGHT_LO, RIGHT_HI = 48.0, 44.0, 44.0, 60.0
AREA = WIDTH * ((LEFT_H + (RIGHT_HI - RIGHT_LO)) / 2.0)  # 1440


def lattice(h):
    d = h / 2.0
    n = int(round(WIDTH / d))
    pts = []
    for j in range(int(round(RIGHT_HI / d))):
        y = (j + 0.5) * d
        for i in range(n):
            x = (i + 0.5) * d
            lo = RIGHT_LO * x / WIDTH
            hi = LEFT_H + (RIGHT_HI - LEFT_H) * x / WIDTH
            if lo <= y <= hi:
                pts.append((x, y))
    return pts, n - 1


def write_deck(method, h, path):
    pts, last_col = lattice(h)
    d = h / 2.0
    mass = AREA / len(pts)  # density 1, thickness 1
    right = [k for k, (x, _) in enumerate(pts) if abs(x - (last_col + 0.5) * d) < 1e-9]
    # The tip: the right column's top particle.
    tip = max(right, key=lambda k: pts[k][1]) + 1
    share = 1.0 / (len(right) - 1)
    lo = -h if method != "mpm" else 0.0  # two fixed node layers with 27-node stencils and sgmp
    # One cell across the thickness for sgmp (the particles at its centre, as the public SG
    # deck), two cells (the particles on the middle node layer) otherwise.
    zlo, zhi = (-h / 2.0, h / 2.0) if method == "sgmp" else (-h, h)
    lines = [
        "mpm3d cook membrane, %s, h = %g (our deck, tools/cook_membrane.py)" % (method, h),
        "! Cook's membrane: neo-Hookean, nu 0.499, clamped at x = 0, vertical force 1 on the",
        "! right edge, quasi-static. Units consistent (m kg N s Pa scaled).",
        "nbco 1", "nbbo 1", "nbmp %d" % len(pts), "nmat 1", "",
        "spx %g %g" % (lo, WIDTH + 2 * h),
        "spy %g %g" % (-h, RIGHT_HI + 2 * h),
        "spz %g %g" % (zlo, zhi),
        "dcell %g" % h,
        "fixed 1 0 0 0 2 2", "",
        "dtscale 0.9", "endtime 30", "outtime 10", "rpttime 0.5", "",
        "musl on",
    ]
    if method != "mpm":
        lines.append(method)
    lines += ["smoo", "QuLo 15", "Damp 0.3", "", "curv disy %d" % tip, "",
              "material", "   1  neoh  1  70  0.499", "",
              "part poin 1 %d" % len(pts)]
    for k, (x, y) in enumerate(pts):
        lines.append("%d 1 %.9g %.9g %.9g 0" % (k + 1, mass, x, y))
    lines += ["", "load"]
    for n, k in enumerate(sorted(right, key=lambda k: pts[k][1])):
        f = share * (0.5 if n in (0, len(right) - 1) else 1.0)
        lines.append("part %d 0 %.9g 0" % (k + 1, f))
    lines += ["endl", "", "endi", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))
    return tip


def tip_displacement(curve_file):
    with open(curve_file) as f:
        rows = [l.split() for l in f.readlines()[1:] if l.strip()]
    return float(rows[-1][-1]), float(rows[-1][0])


def study(mpm3d, outdir):
    os.makedirs(outdir, exist_ok=True)
    rows = []
    for method in ("mpm", "gimp", "bimp", "sgmp"):
        for h in (4.0, 2.0, 1.0):
            name = "cook_%s_h%g" % (method, h)
            deck = os.path.join(outdir, name + ".mpm")
            write_deck(method, h, deck)
            run = subprocess.run([mpm3d, "--no-output", "--summary", os.path.join(outdir, name + ".json"),
                                  "--out-dir", outdir, deck], capture_output=True, text=True)
            if run.returncode != 0:
                rows.append((method, h, float("nan"), float("nan"), float("nan")))
                continue
            import json
            with open(os.path.join(outdir, name + ".json")) as f:
                s = json.load(f)
            rows.append((method, h, s.get("curves_last", {}).get("disy", float("nan")), s["wall_s"], s["time"]))
    with open(os.path.join(outdir, "cook.md"), "w") as f:
        f.write("| method | h | tip v | wall s |\n|---|---|---|---|\n")
        for r in rows:
            f.write("| %s | %g | %.4f | %.1f |\n" % (r[0], r[1], r[2], r[3]))
    return rows


if __name__ == "__main__":
    if len(sys.argv) == 5 and sys.argv[1] == "deck":
        print(write_deck(sys.argv[2], float(sys.argv[3]), sys.argv[4]))
    elif len(sys.argv) == 4 and sys.argv[1] == "study":
        study(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
