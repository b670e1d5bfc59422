#!/usr/bin/env python3
"""The free soft beam (the current MPM3D-F90's volumetric-locking example): its vibration
period against beam theory, at Poisson's ratio 0.3 and 0.499.

usage: tools/soft_beam.py BUILD_DIR [--threads N]   (make report calls run() and section_lines())

A neo-Hookean beam 1 x 6 (x, y), one particle layer in plane strain (z faces fixed), free at
both ends, started with v_x = v0 sin(pi y / 6) (the deck card 'vsin'), particle spacing
0.05, cells 0.1, standard MPM (trilinear, MUSL). The period is measured from the tip's x
velocity relative to the centre of mass (the field has a net momentum): the mean spacing
of its upward zero crossings over the run. Theory: the first free-free mode of an
Euler-Bernoulli beam, omega = (beta L)^2 sqrt(E' I / (rho A L^4)), beta L = 4.7300,
E' = E / (1 - nu^2) (plane strain), I / A = h^2 / 12. Shear deformation (h / L = 1/6) makes
the real beam somewhat softer than that (Timoshenko: a few per cent longer period).
Writes docs/verification/soft_beam.csv; section_lines() turns it into the report's section.
"""
import argparse
import math
import os
import sys

from study import deck_run, section_start, write_dicts

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CSV = os.path.join(ROOT, "docs", "verification", "soft_beam.csv")
E, RHO, H, L = 17.0e6, 1100.0, 1.0, 6.0
NP = 20 * 120  # particles
END_TIME = 1.5


def deck(nu, method="MPM"):
    # sgmp keeps the one cell across z (the particles at its centre); bimp needs two cells
    # per axis (the particles on the middle node layer's cells, z symmetric on both faces).
    spz = "-0.1 0.1" if method == "bimp" else "0 0.1"
    keyword = {"MPM": "", "sgmp": "sgmp\n", "bimp": "bimp\n"}[method]
    return f"""mpm3d *** free soft beam, nu {nu}, {method} (tools/soft_beam.py)
nbco 1
nbbo 1
nbmp {NP}
nmat 1
spx -1.5 2.1
spy -0.1 6.2
spz {spz}
dcell 0.1
dtscale 0.9
endtime {END_TIME}
outtime {END_TIME}
rpttime 0.1
musl on
{keyword}curv disx {NP}
fixed 0 0 0 0 2 2
material
 1 neoh {RHO} {E} {nu}
part bloc 1 1 {RHO} 0.05 -1 0 0.025 20 120 1
velo
vsin 1
endv
endi
"""


def theory_period(nu):
    e_plane = E / (1.0 - nu * nu)
    omega = 4.7300 ** 2 * math.sqrt(e_plane * H * H / 12.0 / (RHO * L ** 4))
    return 2.0 * math.pi / omega


def upward_crossings(rows, band):
    """Times where the signal crosses zero upward, with hysteresis: a crossing counts only
    once the signal has been below -band since the last one, so the small high-frequency
    ringing around zero (pressure waves) does not add spurious crossings."""
    ups, armed = [], False
    for a, b in zip(rows, rows[1:]):
        if a[1] < -band:
            armed = True
        if armed and a[1] <= 0.0 < b[1]:
            ups.append(a[0] - a[1] * (b[0] - a[0]) / (b[1] - a[1]))
            armed = False
    return ups


def measured_period(work):
    """The tip's x displacement relative to the centre of mass (disx minus the centre of mass
    velocity, MomentumPlot.dat over the total mass, times t): the mean spacing of its upward
    zero crossings (with a hysteresis band of a quarter of the first swing's amplitude)
    when they are regular (spacings within 5 % of their mean), the number of crossings, and
    the amplitude of the last expected period over that of the first."""
    mass = RHO * 0.05 ** 3 * NP
    v_cm = {}
    with open(os.path.join(work, "MomentumPlot.dat")) as f:
        for line in f:
            t, px = line.split()[:2]
            v_cm[t] = float(px) / mass
    rows = []
    with open(os.path.join(work, "beam_curv.dat")) as f:
        next(f)
        for line in f:
            c = line.split()
            t = float(c[0])
            rows.append((t, float(c[3]) - v_cm[c[0]] * t))
    th = theory_period(0.3)
    first = max(abs(u) for t, u in rows if t <= th)
    last = max(abs(u) for t, u in rows if t >= rows[-1][0] - th)
    ups = upward_crossings(rows, 0.25 * first)
    gaps = [b - a for a, b in zip(ups, ups[1:])]
    period = float("nan")
    if gaps:
        mean = sum(gaps) / len(gaps)
        if all(abs(g - mean) <= 0.05 * mean for g in gaps):
            period = mean
    return period, len(ups), last / first


def run(build, threads=2):
    mpm3d = os.path.join(os.path.abspath(build), "cxx", "mpm3d")
    rows = []
    for nu, method in ((0.3, "MPM"), (0.499, "MPM"), (0.3, "sgmp"), (0.499, "sgmp"), (0.3, "bimp"),
                       (0.499, "bimp")):
        with deck_run(mpm3d, deck(nu, method), threads, f"soft_beam: nu {nu} {method}") as work:
            t, n, amp = measured_period(work)
        rows.append({"nu": nu, "method": method, "period": t, "crossings": n, "amplitude_ratio": amp,
                     "theory": theory_period(nu)})
        print(f"soft_beam: nu {nu} {method}: period {t:.4f} s ({n} crossings), amplitude last/first {amp:.3f}, "
              f"Euler-Bernoulli {theory_period(nu):.4f} s")
    write_dicts(CSV, rows)
    return rows


def section_lines():
    L_, rows, when = section_start("## Free soft beam: vibration period and volumetric locking",
                                   CSV, "`python3 tools/soft_beam.py build`")
    if rows is None:
        return L_
    L_ += ["The current MPM3D-F90's free soft beam (`tools/soft_beam.py`): a neo-Hookean beam 1 x 6 in "
           "plane strain, E 17 MPa, rho 1100, free at both ends, started with `vsin 1`; 2,400 particles "
           "(spacing 0.05, cells 0.1), MUSL: standard MPM (trilinear), the smoothed-gradient MPM (`sgmp`) and "
           "the current version's B-splines (`bimp`, two cells across z), run to "
           f"{END_TIME} s (run {when}). Period from the tip's displacement relative to the centre of mass (the "
           "mean spacing of its upward zero crossings, each counted once the signal has been below a quarter "
           "of the first swing's amplitude, so that the pressure ringing's small wiggles around zero add "
           "none; regular when every spacing is within 5 % of the mean); theory: the "
           "first free-free mode of an Euler-Bernoulli beam with E / (1 - nu^2) (shear makes the real "
           "beam a few per cent softer).", "",
           "| nu | method | period (s) | Euler-Bernoulli (s) | ratio | amplitude, last period / first |",
           "|---|---|---|---|---|---|"]
    for r in rows:
        t, th, amp = float(r["period"]), float(r["theory"]), float(r["amplitude_ratio"])
        n = int(r["crossings"])
        shown = f"{t:.4f}" if t == t else (f"none ({n} upward crossing{'' if n == 1 else 's'}"
                                           f"{', irregular' if n > 2 else ''})")
        ratio = f"{t / th:.3f}" if t == t else "-"
        L_.append(f"| {r['nu']} | {r['method']} | {shown} | {th:.4f} | {ratio} | {amp:.2f} |")
    r03 = next((r for r in rows if float(r["nu"]) == 0.3 and r["method"] == "MPM"), None)
    r05 = next((r for r in rows if float(r["nu"]) == 0.499 and r["method"] == "MPM"), None)
    fixes = [r for r in rows if float(r["nu"]) == 0.499 and r["method"] != "MPM"]
    if r03 and r05:
        q03 = float(r03["period"]) / float(r03["theory"])
        L_ += ["", f"At nu 0.3 the beam vibrates in its first mode with a period {q03:.3f} times the "
               "Euler-Bernoulli one (softer: Timoshenko's shear correction at h/L = 1/6 accounts for a few "
               f"per cent, the coarse discretisation for the rest) and keeps its amplitude ({float(r03['amplitude_ratio']):.2f}). At nu 0.499 linear MPM locks: the "
               "constant-strain cells cannot bend without changing volume; the tip does not swing through "
               f"its first mode ({r05['crossings']} upward crossing{'' if int(r05['crossings']) == 1 else 's'} in {END_TIME} s where the free beam gives "
               f"{int(END_TIME / float(r05['theory']))}, its amplitude down to {float(r05['amplitude_ratio']):.2f} "
               "of the first swing) and high-frequency pressure ringing dominates."]
        for r in fixes:
            t, th = float(r["period"]), float(r["theory"])
            if t == t:
                L_ += [f"With `{r['method']}` at nu 0.499 the beam swings regularly again: period {t / th:.3f} "
                       f"times Euler-Bernoulli (at nu 0.3: {q03:.3f}), amplitude {float(r['amplitude_ratio']):.2f} "
                       "of the first swing: the locking is gone."]
            else:
                clean = int(END_TIME / th)
                L_ += [f"With `{r['method']}` at nu 0.499 the beam keeps its swing (amplitude "
                       f"{float(r['amplitude_ratio']):.2f} of the first, against {float(r05['amplitude_ratio']):.2f} "
                       f"without) and the spurious zero crossings drop from {r05['crossings']} to {r['crossings']} "
                       f"(a clean first mode gives {clean}), but the swing is not yet regular on this coarse beam "
                       "(ten cells across): the locking is relieved, not removed, at this resolution."]
    return L_ + [""]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    run(a.build, a.threads)
    print("\n".join(section_lines()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
