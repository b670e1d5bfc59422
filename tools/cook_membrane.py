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
import os
import subprocess
import sys

from study import section_start

WIDTH, LEFT_H, RIGHT_LO, RIGHT_HI = 48.0, 44.0, 44.0, 60.0
AREA = WIDTH * ((LEFT_H + (RIGHT_HI - RIGHT_LO)) / 2.0)  # 1440
# The reference: linear plane-strain elasticity, nearly incompressible (the strains here stay
# near 1 %, where the neo-Hookean solid is linear). The converged mid-edge displacement for
# a unit total shear load is 16.4326 at G = 0.375, lambda = 7500 (nu 0.49998; Krysl's FinEALE
# examples, NICE-T6 elements with Richardson extrapolation); near incompressibility the
# displacement scales with 1 / G, and plane-strain bending with (1 - nu) / (2 G), so nu 0.499
# adds (0.501 / 0.50002 - 1) = 0.2 %.
E, NU = 70.0, 0.499
NU_REF = 0.5 * 7500.0 / (7500.0 + 0.375)
REF_TIP = 16.432584 * 0.375 / (E / (2 * (1 + NU))) * (1 - NU) / (1 - NU_REF)  # 0.2644


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
    """The tip's last vertical displacement and the kinetic share of the energy then (the
    curve file's columns: time, engk1, engi1, disy)."""
    with open(curve_file) as f:
        rows = [l.split() for l in f.readlines()[1:] if l.strip()]
    ke, ie = float(rows[-1][1]), float(rows[-1][2])
    return float(rows[-1][-1]), ke / (ke + ie)


def study(mpm3d, outdir, threads=2):
    """Every method at h = 4, 2, 1: the tip's final vertical displacement and the run time."""
    import json
    os.makedirs(outdir, exist_ok=True)
    rows = []
    for method in ("mpm", "gimp", "bimp", "sgmp"):
        for h in (4.0, 2.0, 1.0):
            name = "cook_%s_h%g" % (method, h)
            deck = os.path.join(outdir, name + ".mpm")
            write_deck(method, h, deck)
            summary = os.path.join(outdir, name + ".json")
            # Every run to t = 200 (past the ramp's 15 and QuLo's 100: --end-time replaces
            # the settling rule, which a locking run would never meet).
            run = subprocess.run([mpm3d, "--threads", str(threads), "--quiet", "--summary", summary,
                                  "--end-time", "200", "--out-dir", outdir, deck], capture_output=True, text=True)
            if run.returncode != 0:
                rows.append((method, h, float("nan"), float("nan"), 0, float("nan")))
                continue
            with open(summary) as f:
                s = json.load(f)
            tip, share = tip_displacement(os.path.join(outdir, name + "_curv.dat"))
            rows.append((method, h, tip, s.get("wall_seconds", float("nan")), s.get("particles", 0), share))
    return rows


CSV = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "docs", "verification",
                   "cook_membrane.csv")


def run(build, threads=2):
    """make report: the study in a scratch folder, its rows in docs/verification/cook_membrane.csv."""
    import csv
    import tempfile
    mpm3d = os.path.join(os.path.abspath(build), "cxx", "mpm3d")
    with tempfile.TemporaryDirectory() as work:
        rows = study(mpm3d, work, threads)
    os.makedirs(os.path.dirname(CSV), exist_ok=True)
    with open(CSV, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["method", "h", "particles", "tip", "kinetic_share", "wall_seconds"])
        for r in rows:
            w.writerow([r[0], r[1], r[4], r[2], r[5], r[3]])
    return rows


def tip_of(rows, method):
    """The finest (smallest h) tip displacement of a method in the CSV rows."""
    r = min((x for x in rows if x["method"] == method), key=lambda x: float(x["h"]))
    return float(r["tip"])


def section_lines():
    """The report's section (docs/VERIFICATION.md) from docs/verification/cook_membrane.csv."""
    L, rows, when = section_start("## Cook's membrane: the locking remedies under refinement",
                                  CSV, "`python3 tools/cook_membrane.py study build/cxx/mpm3d DIR`")
    if rows is None:
        return L
    L += ["`tools/cook_membrane.py` (run %s, 2 threads): the trapezoid (0,0) (48,44) (48,60) (0,44), "
          "clamped at x = 0, a vertical force of 1 on its right edge ramped over t = 15 (`QuLo`), damped "
          "(`Damp 0.3`), neo-Hookean with E 70, nu 0.499, rho 1, one particle layer in plane strain, two "
          "particles per cell and axis, every run to t = 200. The quantity is the vertical displacement of "
          "the top right particle at t = 200; the kinetic share of the energy then says whether the run "
          "has come to rest (the current version's rule stops a run below 0.005 after t = 100). The public decks of the current version are the h = 1 bimp and sgmp cases: the "
          "original gives 0.2620 (B-spline) and 0.2678 (smoothed gradient) for them "
          "(its own results, published with the public decks, not in the repository)." % when, "",
          "| method | h | particles | tip vertical displacement | against the reference %.4f | "
          "kinetic share at t = 200 | run time (s) |" % REF_TIP,
          "|---|---|---|---|---|---|---|"]
    for r in rows:
        L.append("| %s | %s | %s | %.4f | %+.1f %% | %.4f | %.1f |" % (
            r["method"], r["h"], r["particles"], float(r["tip"]), 100 * (float(r["tip"]) / REF_TIP - 1),
            float(r["kinetic_share"]), float(r["wall_seconds"])))
    L += ["", "Linear MPM locks at nu 0.499: its tip moves about 20 % less than the remedies' and hardly "
          "more under refinement, and it does not come to rest (pressure ringing keeps the kinetic share "
          "near 0.1). GIMP locks on the coarse grids and approaches the remedies only at h = 1. The "
          "smoothed-gradient (sgmp) and B-spline (bimp) runs come to rest (kinetic share below 0.008); bimp "
          "converges from below onto the reference below, while sgmp, closer on the coarse grids, rises "
          "through it and ends 2 % above at h = 1 (the original's SG deck too, 1.3 % above).", "",
          "The reference, %.4f: the tip moves 0.26 on a membrane 48 long, small strains where the "
          "neo-Hookean solid is linear, so the converged linear plane-strain answer applies: 16.4326 for a unit load at G = 0.375, "
          "lambda = 7500 (nu 0.49998), at the right edge's midpoint (P. Krysl's FinEALE examples: NICE-T6 "
          "elements with Richardson extrapolation), scaled by 1 / G to E 70, nu 0.499, and by (1 - nu) / "
          "(1 - 0.49998) for the slightly larger compressibility (plane-strain bending: +0.2 %%); the corner "
          "and the mid-edge move alike to 0.05 %% (the plane-stress benchmark's 23.96 and 23.97). At h = 1 "
          "the B-spline run is %+.1f %% from it and the smoothed gradient %+.1f %% (the original, on its "
          "decks: 0.2620 and 0.2678, %+.1f %% and %+.1f %%); GIMP %+.1f %%, linear MPM %+.0f %% (locked). "
          "The run times were taken on a loaded, noisy machine: read them as orders of magnitude." % (
              REF_TIP, 100 * (tip_of(rows, "bimp") / REF_TIP - 1), 100 * (tip_of(rows, "sgmp") / REF_TIP - 1),
              100 * (0.2620 / REF_TIP - 1), 100 * (0.2678 / REF_TIP - 1), 100 * (tip_of(rows, "gimp") / REF_TIP - 1),
              100 * (tip_of(rows, "mpm") / REF_TIP - 1)), ""]
    return L


def write_table(rows, path):
    with open(path, "w") as f:
        f.write("| method | h | particles | tip vertical displacement | settled at t | run time s |\n"
                "|---|---|---|---|---|---|\n")
        for r in rows:
            settled = "%.1f" % r[5] if r[5] < 199.0 else "no (t = 200)"
            f.write("| %s | %g | %d | %.4f | %s | %.1f |\n" % (r[0], r[1], r[4], r[2], settled, r[3]))


if __name__ == "__main__":
    if len(sys.argv) == 5 and sys.argv[1] == "deck":
        print(write_deck(sys.argv[2], float(sys.argv[3]), sys.argv[4]))
    elif len(sys.argv) == 4 and sys.argv[1] == "study":
        write_table(study(sys.argv[2], sys.argv[3]), os.path.join(sys.argv[3], "cook.md"))
    else:
        sys.exit(__doc__)
