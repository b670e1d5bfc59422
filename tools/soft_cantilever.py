#!/usr/bin/env python3
"""The soft cantilever (the current MPM3D-F90's SoftBeam decks, after Kadapa 2019): total
Lagrangian MPM with and without the smoothed gradient at nu 0.3 and 0.499.

A neo-Hookean beam 1 x 6 (x, y) in plane strain (E 17 MPa, rho 1100), clamped at y = 0,
started with v_x = 10 m/s everywhere, particle spacing 0.05, cells 0.1, MUSL, `smoo`, `UVFp`,
`TLmp`, to t = 1.2 s: the tip's x displacement (`curv disx`), its largest swing either way
and the time of its first return through zero. With `sgmp` the grid starts one cell below
the clamp (sgmp holds two node layers on a fixed face).

usage: tools/soft_cantilever.py BUILD_DIR [--threads N]   (make report calls run() and
section_lines(); writes docs/verification/soft_cantilever.csv)
"""
import argparse
import os

from study import deck_run, section_start, write_dicts

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CSV = os.path.join(ROOT, "docs", "verification", "soft_cantilever.csv")
NP = 20 * 120


def deck(nu, sg):
    return f"""mpm3d *** soft cantilever, nu {nu}, TLmp{' + sgmp' if sg else ''} (tools/soft_cantilever.py)
nbco 1
nbbo 1
nbmp {NP}
nmat 1
spx {'-1.1 0.1' if sg else '-1.0 0'}
spy {'-0.1 6.1' if sg else '0 6.0'}
spz 0 0.1
dcell 0.1
dtscale 0.9
endtime 1.2
outtime 1.2
rpttime 0.1
musl on
{'sgmp' if sg else ''}
smoo
UVFp
TLmp
curv disx {NP}
fixed 0 0 1 0 2 2
material
 1 neoh 1100 17e6 {nu}
part bloc 1 1 1100 0.05 -1 0 0.025 20 120 1
velo
body 1 10 0 0
endv
endi
"""


def measures(curve):
    rows = []
    with open(curve) as f:
        next(f)
        for line in f:
            c = line.split()
            if c:
                rows.append((float(c[0]), float(c[3])))
    peak = max(rows, key=lambda r: r[1])
    back = next(((a[0] - a[1] * (b[0] - a[0]) / (b[1] - a[1])) for a, b in zip(rows, rows[1:])
                 if a[0] > peak[0] and a[1] > 0.0 >= b[1]), float("nan"))
    return max(r[1] for r in rows), min(r[1] for r in rows), peak[0], back


def run(build, threads=2):
    mpm3d = os.path.join(os.path.abspath(build), "cxx", "mpm3d")
    out = []
    for nu in (0.3, 0.499):
        for sg in (False, True):
            with deck_run(mpm3d, deck(nu, sg), threads, f"soft_cantilever: nu {nu} sg {sg}") as work:
                hi, lo, t_peak, t_back = measures(os.path.join(work, "beam_curv.dat"))
            out.append({"nu": nu, "method": "TLmp + sgmp" if sg else "TLmp", "tip_max": hi, "tip_min": lo,
                        "t_peak": t_peak, "t_back": t_back})
            print(f"soft_cantilever: nu {nu} {out[-1]['method']}: tip {lo:.3f} .. {hi:.3f}, peak at {t_peak:.3f} s, "
                  f"back through zero at {t_back:.3f} s")
    write_dicts(CSV, out)
    return out


def section_lines():
    L, rows, when = section_start("## Soft cantilever: total Lagrangian MPM with and without the smoothed gradient",
                                  CSV, "`python3 tools/soft_cantilever.py build`")
    if rows is None:
        return L
    L += ["`tools/soft_cantilever.py` (run %s, 2 threads): the current MPM3D-F90's soft beam (after Kadapa "
          "2019): a neo-Hookean beam 1 x 6 in plane strain, E 17 MPa, rho 1100, clamped at y = 0 and started "
          "with v_x = 10 m/s everywhere; 2,400 particles (spacing 0.05, cells 0.1), MUSL, `smoo`, `UVFp`, "
          "`TLmp`, with and without `sgmp`, to t = 1.2 s. The tip's x displacement: its largest swing each "
          "way, when it peaks and when it comes back through zero. The published response (Kadapa 2019, "
          "implicit and explicit finite elements) is a figure whose values are not in the repository's "
          "reach: the comparison here is between the methods, and the public SBSGTL deck's run against "
          "the original program is in docs/DECK_FORMAT.md (`sgmp`)." % when, "",
          "| nu | method | tip max (m) | tip min (m) | peak at (s) | back through zero at (s) |",
          "|---|---|---|---|---|---|"]
    for r in rows:
        L.append("| %s | %s | %.3f | %.3f | %.3f | %.3f |" % (r["nu"], r["method"], float(r["tip_max"]),
                                                             float(r["tip_min"]), float(r["t_peak"]),
                                                             float(r["t_back"])))
    by = {(r["nu"], r["method"]): r for r in rows}
    a, b = by.get(("0.3", "TLmp")), by.get(("0.3", "TLmp + sgmp"))
    c, d = by.get(("0.499", "TLmp")), by.get(("0.499", "TLmp + sgmp"))
    if a and b and c and d:
        L += ["", "At nu 0.3 the two methods swing alike (peak %.3f and %.3f m). At nu 0.499 the total "
              "Lagrangian beam without smoothing peaks at %.3f m, %.0f %% below the smoothed one's %.3f m "
              "(%.0f %% below its own nu 0.3 swing, the smoothed one %.0f %%), and comes back through zero at "
              "%.3f s against %.3f s: the trilinear cells lock volumetrically and stiffen the beam, the "
              "smoothed gradient (one volumetric strain rate per cell) relieves most of it." % (
                  float(a["tip_max"]), float(b["tip_max"]), float(c["tip_max"]),
                  100 * (1 - float(c["tip_max"]) / float(d["tip_max"])), float(d["tip_max"]),
                  100 * (1 - float(c["tip_max"]) / float(a["tip_max"])),
                  100 * (1 - float(d["tip_max"]) / float(b["tip_max"])), float(c["t_back"]), float(d["t_back"]))]
    return L + [""]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    run(a.build, a.threads)
    print("\n".join(section_lines()))


if __name__ == "__main__":
    main()
