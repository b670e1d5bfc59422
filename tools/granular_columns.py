#!/usr/bin/env python3
"""Granular column collapse against the experiments of Lube et al. (2005, two-dimensional columns).

Plane-strain sand columns, a = H0/L0 = 0.5 to 4, under three rule sets (the method: section_lines).
usage: tools/granular_columns.py BUILD_DIR [--threads N]: decks, runs, CSV and PNG (as make report does)
"""
import glob
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np

from study import section_start, write_dicts

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CSV = os.path.join(ROOT, "docs", "verification", "granular_columns.csv")
PNG = os.path.join(ROOT, "docs", "verification", "granular_columns.png")
CASES = ((0.5, 80.0, 400), (1, 40.0, 400), (2, 40.0, 550), (4, 32.0, 700))  # a, L0 (mm), 6 sqrt(H0/g) (ms)
DCELL = 2.0  # mm
DECK = os.path.join(ROOT, "inputs", "granular", "column_a%g.mpm")  # % a
RULES = (("ours", []), ("ours, dp_return=original", ["--rule", "dp_return=original"]),
         ("original", ["--rules", "original"]))


def lube(a):
    """Lube et al.'s fits for two-dimensional columns: ((L - L0)/L0, H/L0)."""
    return (1.2 * a if a < 2.3 else 1.9 * a ** (2.0 / 3.0)), (a if a < 1.15 else a ** 0.4)


def deck_text(a, L0, end):
    H0, dp = a * L0, DCELL / 2
    nx, nz = int(round(L0 / dp)), int(round(H0 / dp))
    spx = DCELL * round(1.6 * L0 * (1 + lube(a)[0]) / DCELL)  # 1.6 times Lube's deposit
    return "\n".join([
        "mpm3d *** granular column collapse, aspect ratio %g (cohesionless sand, plane strain)" % a,
        "! Our own deck (MPM3D-CXX), written by tools/granular_columns.py. Unit: mm g N ms MPa.",
        "! A column L0 = %g mm wide, H0 = %g mm high (a = %g) against a smooth wall (x0) on a rough" % (L0, H0, a),
        "! floor (z0 fixed), plane strain (symmetric y faces, one cell thick), 2 x 2 x 2 particles per",
        "! cell, released at t = 0 (Lube et al. 2005). Cohesionless sand, phi = 30 degrees, no dilatancy:",
        "!   q_phi = 3 tan(phi) / sqrt(9 + 12 tan^2(phi)) = 0.48038, k_phi = 0, q_psi = 0, sigma_t = 0.",
        "nbco 1", "nbbo 1", "nbmp %d" % (nx * 2 * nz), "nmat 1", "spx 0.0 %g" % spx, "spy 0.0 %g" % DCELL,
        "spz 0.0 %g" % (DCELL * round(H0 / DCELL + 2)), "dcell %g" % DCELL, "dtscale 0.5",
        "endtime %g" % end, "outtime 25.0", "rpttime 25.0", "musl on", "jaum on",
        "!      x0  xn  y0  yn  z0  zn", "fixed  2   0   2   2   1   0", "material",
        "!  num type density  E     nu   q_phi    k_phi q_psi sigma_t",
        "   1   dpm  2.0d-3   10.0  0.3  0.48038  0.0   0.0   0.0",
        "part bloc 1 1 2.0d-3 %g  0.0 0.0 0.0  %d 2 %d" % (dp, nx, nz),
        "load", " grav 1 0.0 0.0 -9.81d-3", "endl", "curv velx 1", "endi", ""])


def shape(pos, L0, dp):
    """(front, height) of a deposit from the particles' positions (N, 3)."""
    x, z = pos[:, 0], pos[:, 2]
    return float(np.percentile(x, 99)) + dp / 2, float(z[x < L0 / 4].max()) + dp / 2


def run_one(mpm3d, a, L0, end, label, args, threads):
    """One run: a CSV row (a failed run: its status and stop time, no figures)."""
    import h5py
    nan, dp = float("nan"), DCELL / 2
    row = dict(a=a, L0_mm=L0, end_ms=end, rules=label, status="ok", stop_ms="", runout=nan,
               runout_lube=lube(a)[0], runout_ratio=nan, height=nan, height_lube=lube(a)[1], height_ratio=nan,
               ke_end_pct=nan, front_moved_mm=nan, wall_s=nan, threads=threads)
    with tempfile.TemporaryDirectory() as work:
        t0 = time.time()
        p = subprocess.run([mpm3d, "--threads", str(threads), "--quiet", "--hdf5", "--out-dir", work, "--state",
                            os.path.join(work, "state.h5")] + args + [DECK % a],
                           cwd=work, capture_output=True, text=True)
        row["wall_s"] = time.time() - t0
        if p.returncode != 0:  # "mpm3d: numerical instability at step N (t = T): ..."
            msg = (p.stderr.strip().splitlines() or ["exit status %d" % p.returncode])[-1]
            row["status"] = "stopped: " + msg.split(": ")[1 if msg.startswith("mpm3d:") else 0].split(" at step")[0]
            row["stop_ms"] = float(msg.split("(t = ")[1].split(")")[0]) if "(t = " in msg else ""
            return row
        e = np.loadtxt(os.path.join(work, "EnergyPlot.dat"))  # time, total, kinetic, internal
        row["ke_end_pct"] = 100 * e[-1, 2] / e[:, 2].max()
        with h5py.File(os.path.join(work, "state.h5"), "r") as f:
            front, height = shape(f["/particles/position"][:], L0, dp)
        with h5py.File(glob.glob(os.path.join(work, "*_anim.h5"))[0], "r") as f:
            frames = sorted(f["frames"].values(), key=lambda g: g.attrs["time"])
            before = [g for g in frames if g.attrs["time"] <= frames[-1].attrs["time"] - 100 + 1e-6][-1]
            row["front_moved_mm"] = front - shape(before["position"][:], L0, dp)[0]
    row.update(runout=(front - L0) / L0, height=height / L0)
    row.update(runout_ratio=row["runout"] / row["runout_lube"], height_ratio=row["height"] / row["height_lube"])
    return row


def run(build, threads=2):
    """make report: the decks, the 12 runs, docs/verification/granular_columns.csv and .png."""
    mpm3d = os.path.join(os.path.abspath(build), "cxx", "mpm3d")
    for a, L0, end in CASES:
        open(DECK % a, "w").write(deck_text(a, L0, end))
    rows = []
    for label, args in RULES:
        for a, L0, end in CASES:
            rows.append(run_one(mpm3d, a, L0, end, label, args, threads))
            print("granular column a = %(a)g, %(rules)s: %(status)s, run-out %(runout).2f (Lube %(runout_lube).2f), "
                  "H/L0 %(height).2f (Lube %(height_lube).2f), %(wall_s).0f s" % rows[-1], flush=True)
    when = "%s, %s, %d cores" % (time.strftime("%Y-%m-%d"), platform.machine(), os.cpu_count())
    write_dicts(CSV, [dict(r, run=when, **{k: "%.4g" % v for k, v in r.items() if isinstance(v, float)})
                      for r in rows])
    plot(rows)


def plot(rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    aa = np.geomspace(0.4, 5, 200)
    fig, axs = plt.subplots(1, 2, figsize=(10, 4.4))
    for i, (ax, key, name, ticks) in enumerate(((axs[0], "runout", "(L - L0) / L0", [0.5, 1, 2, 4]),
                                                (axs[1], "height", "H / L0", [0.5, 1, 1.5, 2]))):
        fit = np.array([lube(a)[i] for a in aa])
        ax.fill_between(aa, 0.8 * fit, 1.2 * fit, color="0.85", label="Lube et al. 2005 fit +- 20 %")
        ax.plot(aa, fit, "k-", lw=1)
        for (label, _), m in zip(RULES, "os^"):
            ok = [r for r in rows if r["rules"] == label and r["status"] == "ok"]
            if ok:
                ax.plot([r["a"] for r in ok], [r[key] for r in ok], m + "-", mfc="none", label="mpm3d, " + label)
        ax.set(xscale="log", yscale="log", xlabel="aspect ratio a = H0 / L0", ylabel=name)
        ax.grid(alpha=0.3, which="both")
        ax.set_xticks([0.5, 1, 2, 4], ["0.5", "1", "2", "4"])
        ax.set_yticks(ticks, ["%g" % t for t in ticks])
        ax.minorticks_off()
    axs[0].legend(fontsize=8)
    fig.suptitle("granular column collapse, plane strain, phi = 30 deg (runs that stopped are not drawn)", fontsize=9)
    fig.tight_layout()
    fig.savefig(PNG, dpi=90)
    plt.close(fig)


def section_lines():
    """The report's section (docs/VERIFICATION.md) from docs/verification/granular_columns.csv."""
    L, rows, _ = section_start("## Granular columns: collapse run-out and final height against Lube et al. (2005)",
                               CSV, "`make report`, or `tools/granular_columns.py BUILD_DIR`")
    if rows is None:
        return L
    L += ["`tools/granular_columns.py` (run %s, `--threads %s`; decks `inputs/granular/column_a{0.5,1,2,4}.mpm`): "
          "plane-strain columns of cohesionless sand (`dpm`, rho 2.0e-3 g/mm^3, E 10 MPa, nu 0.3, phi = 30 degrees, "
          "no dilatancy, no tension) L0 wide and a L0 high (L0 = %s mm), against a smooth wall on a rough (fixed) "
          "floor, cells of 2 mm with 2 x 2 particles per cell in x-z (one cell thick, symmetric faces), MUSL, "
          "Jaumann rate, released at t = 0 and run for 6 sqrt(H0/g) (%s ms). The front L is the 99th percentile of "
          "the particles' x plus half a spacing; the final height H the highest particle within L0/4 of the wall "
          "(the deposit's surface is rough at the scale of a cell). Lube et al.'s fits for their two-dimensional "
          "columns: (L - L0)/L0 = 1.2 a for a < 2.3, 1.9 a^(2/3) above; H/L0 = a for a < 1.15, a^(2/5) above "
          "(ratio: ours / fit). Rest: the kinetic energy at the end as %% of its peak, and the front's move over "
          "the last 100 ms. Run times are noisy (a shared machine)." % (
              rows[0]["run"], rows[0]["threads"], ", ".join("%s (a = %s)" % (r["L0_mm"], r["a"]) for r in rows[:4]),
              ", ".join(r["end_ms"] for r in rows[:4])), "",
          "| rules | a | (L - L0)/L0 (fit, ratio) | H/L0 (fit, ratio) | within 20 % | KE at end, % of peak | "
          "front moved, last 100 ms (mm) | run (s) |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        f = {k: float(v) for k, v in r.items() if k not in ("rules", "status", "stop_ms", "run")}
        if r["status"] != "ok":
            L.append("| %s | %s | %s at t = %s ms | | no result | | | %.1f |" % (
                r["rules"], r["a"], r["status"], r["stop_ms"], f["wall_s"]))
            continue
        ok = [w for w in ("runout", "height") if abs(f[w + "_ratio"] - 1) <= 0.2]
        L.append("| %s | %s | %.2f (%.2f, %.2f) | %.2f (%.2f, %.2f) | %s | %.1f | %.2f | %.1f |" % (
            r["rules"], r["a"], f["runout"], f["runout_lube"], f["runout_ratio"], f["height"], f["height_lube"],
            f["height_ratio"], " and ".join(ok).replace("runout", "run-out") or "neither", f["ke_end_pct"],
            abs(f["front_moved_mm"]) if abs(f["front_moved_mm"]) < 0.005 else f["front_moved_mm"], f["wall_s"]))
    return L + [""] + NARRATIVE + ["", "![granular column collapse](verification/granular_columns.png)", ""]


# What the runs show (written once the runs were read, 2026-12-05; ours again after the opening change).
NARRATIVE = [
    "Under our rules every column comes to rest with every particle at its density: beyond the tension cut-off "
    "the return's volumetric opening is space between particles, left out of their volumes (docs/FROM_MPM3D_F90.md, "
    "row 6; before that change the front thinned to 1-2 % of rho0 and every column stopped with numerical "
    "instability at t = 121-211 ms). The final height is within 10 % of Lube et al.'s fit for a <= 2 and 28 % low "
    "at a = 4, as with the original's return. The run-out is 22-61 % longer than the fit, not within 20 %: the "
    "deposit follows the original's return's to within a few mm up to that one's front, and beyond it ours carries "
    "a thin tail (at a = 2, 6 % of the particles lie beyond x = 140 mm, the tail at most 4 cells thick; none in the "
    "original's). "
    "Why, shown at a = 2 (frames at t = 100, 150, 200 ms, `docs/bench/granular_front.csv`; the front is the "
    "particles within 10 mm of the 99th percentile): under our return 74-90 % of the front's particles are "
    "stress-free (the front dilates, and a cohesionless material has no strength in extension), so nothing brakes"
    " it and it slides on at 0.66-0.73 mm/ms; under the original's return none is, and 57-62 % of them carry a "
    "shear stress beyond the yield cone (tau > q_phi p), a strength that cohesionless sand does not have, which "
    "holds the front together (its front 0.29-0.48 mm/ms, 111 mm at t = 200 against our 136). Not the cells: with"
    " GIMP on a grid two cells thick the front is the same (136.3 mm). Not the floor alone: the fixed floor holds"
    " its nodes but, with FLIP, not the velocities of the particles in the first cell above it (0.55-0.70 mm/ms "
    "there); a build whose held nodes brake the particles' velocities as well (an experiment, not a rule) stops "
    "that cell, and the stress-free layer above it slides over it (126.8 mm at t = 200). What keeps the separated"
    " front moving is FLIP: a stress-free particle keeps its velocity, whatever its neighbours do. An experiment "
    "build in which a stress-free particle takes the grid's velocity in G2P (PIC, the local mean: separated grains"
    " that share their momentum as in a perfectly inelastic collision) and every other particle keeps FLIP "
    "overshoots the other way: the run-out is 0.34, 0.38, 0.56 and 0.53 of the fit at a = 0.5, 1, 2, 4 "
    "(`docs/bench/dropped.csv`). The right answer lies between the two, and a blend would be a fitted parameter, "
    "not a law. A run-out within 20 % under our rules therefore needs a mechanism that neither program has (a "
    "collisional dissipation law for separated grains, a base friction acting on a particle's weight, or a "
    "dense-flow law for a dilating front), not a different return. "
    "With the original's return (`--rule dp_return=original`) every column comes to rest with the figures of "
    "`--rules original` to 1.5 %. "
    "Against Lube et al.: the run-out is within 20 % of the fit for a = 1, 2, 4 (0.82-0.92 of it) and 26-27 % "
    "short at a = 0.5, short at every a; the final height is within 5 % for a <= 2 (at a = 0.5 and 1 the column's "
    "top stays, as in the experiments) and 28-29 % low at a = 4. The run-out is not converged in the cell size: "
    "with 10 cells across the column (20 at a = 0.5; the first try) `--rules original` gave 0.28, 0.61, 2.01, "
    "3.74, and at a = 1 with 40 (cells of 1 mm) 1.07, not 0.99. The thin front lies in the first cell above the "
    "fixed floor, whose nodes hold it back: the short run-out at small a is largely the resolution's. At the end "
    "the kinetic energy is steady and the front still; the residue is a few particles at the floor (in the first "
    "try 1 % of the particles held 14-60 % of it).",
    "",
    "The fits are quoted, not read in the original (Lube, Huppert, Sparks & Freundt, Phys. Rev. E 72, 041301, "
    "2005): the run-out's as by Lagree, Staron & Popinet (J. Fluid Mech. 686, 378, 2011, Eq. 3.1) and other "
    "secondary sources alike; for the height one quotes H/L0 = 1.0 a^0.4; the switch at a = 1.15 is unconfirmed."]


def main(argv):
    if len(argv) not in (2, 4) or argv[1].startswith("-") or (len(argv) == 4 and argv[2] != "--threads"):
        sys.exit(__doc__)
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")  # as make report: 2 threads on a shared machine
    run(argv[1], int(argv[3]) if len(argv) == 4 else 2)
    print("\n".join(section_lines()))


if __name__ == "__main__":
    main(sys.argv)
