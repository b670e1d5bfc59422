#!/usr/bin/env python3
"""Two equal elastic spheres colliding head-on through the multi-velocity contact, against
what physics requires, by our contact and by the original programs' (rule contact).

inputs/contact/spheres.mpm (radius 2 mm, E 1000 MPa, nu 0.3, +-20 m/s, frictionless, MUSL)
at three time-step scales. Exact: the total momentum stays zero, the total energy stays E0
(no friction, elastic bodies), and equal spheres exchange their velocities (each sphere's
mean x velocity goes from +-v0 to -+v0). Each run: the total energy at the end and its peak
over the run (E/E0, EnergyPlot.dat), the spheres' mean x velocities at the end over v0 and
the total momentum over M v0 (the state file).
usage: tools/contact_spheres.py BUILD_DIR [--threads N]: runs, CSV and PNG (as make report does)
"""
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np

from study import section_start, write_dicts

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CSV = os.path.join(ROOT, "docs", "verification", "contact_spheres.csv")
PNG = os.path.join(ROOT, "docs", "verification", "contact_spheres.png")
DECK = os.path.join(ROOT, "inputs", "contact", "spheres.mpm")
V0 = 20.0
DTSCALES = (0.1, 0.2, 0.5)
RULES = (("ours", []), ("original", ["--rule", "contact=original"]))


def run_one(mpm3d, dtscale, label, args, threads, work):
    import h5py
    deck = os.path.join(work, "spheres_%s_%g.mpm" % (label, dtscale))
    text = open(DECK).read().replace("dtscale 0.2", "dtscale %g" % dtscale)
    open(deck, "w").write(text)
    out = os.path.join(work, "%s_%g" % (label, dtscale))
    t0 = time.time()
    subprocess.run([mpm3d, "--threads", str(threads), "--quiet", "--out-dir", out, "--state",
                    os.path.join(out, "state.h5")] + args + [deck], cwd=work, check=True)
    wall = time.time() - t0
    e = np.loadtxt(os.path.join(out, "EnergyPlot.dat"))  # time, total, kinetic, internal
    with h5py.File(os.path.join(out, "state.h5"), "r") as f:
        v = f["/particles/velocity"][:]
        m = f["/particles/mass"][:]
        body = f["/particles/body"][:]
    v = v.reshape(-1, 3) if v.shape[-1] == 3 else v.T
    mine = [body == b for b in sorted(set(body.tolist()))]
    M = m[mine[0]].sum()
    vx = [float((m[s] * v[s, 0]).sum() / m[s].sum()) for s in mine]
    E0 = M * V0 ** 2  # two spheres of M v0^2 / 2
    row = dict(rules=label, dtscale=dtscale, steps=len(e), energy_end=e[-1, 1] / E0, energy_peak=e[:, 1].max() / E0,
               v1_end=vx[0] / V0, v2_end=vx[1] / V0, momentum=abs(float((m * v[:, 0]).sum())) / (M * V0),
               wall_s=wall, threads=threads, run=time.strftime("%Y-%m-%d"), machine=platform.machine())
    return row, (e[:, 0], e[:, 1] / E0)


def run(build, threads=2):
    """make report: the six runs, docs/verification/contact_spheres.csv and .png."""
    mpm3d = os.path.join(os.path.abspath(build), "cxx", "mpm3d")
    rows, curves = [], {}
    with tempfile.TemporaryDirectory() as work:
        for label, args in RULES:
            for s in DTSCALES:
                row, curve = run_one(mpm3d, s, label, args, threads, work)
                rows.append(row)
                curves[(label, s)] = curve
    write_dicts(CSV, rows)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    for (label, s), (t, e) in sorted(curves.items()):
        ax.plot(t, e, ("-" if label == "ours" else "--"), label="%s, dtscale %g" % (
            "ours" if label == "ours" else "the originals' (contact=original)", s))
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xlabel("t (ms)")
    ax.set_ylabel("total energy / E0")
    ax.set_title("Two elastic spheres, frictionless contact: exact E = E0")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(PNG, dpi=110)


def section_lines():
    """The report's section (docs/VERIFICATION.md) from docs/verification/contact_spheres.csv."""
    L, rows, _ = section_start("## Colliding spheres: contact against the exact answer",
                               CSV, "`make report`, or `tools/contact_spheres.py BUILD_DIR`")
    if rows is None:
        return L
    L += ["`tools/contact_spheres.py` (run %s, `--threads %s`): `inputs/contact/spheres.mpm`, two equal elastic "
          "spheres (radius 2 mm, E 1000 MPa, nu 0.3, 280 particles each, cells of 1 mm) at +-20 m/s, frictionless "
          "multi-velocity contact, MUSL, to t = 0.12 ms (the spheres have separated), by our contact and by the "
          "original programs' (`--rule contact=original`: one correction a step, forces by the full dt; docs/"
          "FROM_MPM3D_F90.md row 16). Exact: the total energy stays E0, the total momentum zero, and the spheres "
          "exchange their velocities (mean x velocity of sphere 1 from +v0 to -v0, sphere 2 the reverse)." % (
              rows[0]["run"], rows[0]["threads"]), "",
          "| contact | dtscale | steps | E/E0 at the end (peak) | sphere 1, 2: v_x/v0 at the end (exact -1, +1) | "
          "momentum / (M v0) | run (s) |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        f = {k: float(v) for k, v in r.items() if k not in ("rules", "run", "machine")}
        L.append("| %s | %g | %d | %.3f (%.3f) | %.3f, %.3f | %.1e | %.2f |" % (
            "ours" if r["rules"] == "ours" else "the originals'", f["dtscale"], f["steps"], f["energy_end"],
            f["energy_peak"], f["v1_end"], f["v2_end"], f["momentum"], f["wall_s"]))
    return L + [""] + NARRATIVE + ["", "![colliding spheres](verification/contact_spheres.png)", ""]


# What the runs show (written once the runs were read, 2026-12-05).
NARRATIVE = [
    "Momentum is conserved to rounding by both: each correction moves momentum between the two grids. Energy is "
    "not: the originals' contact gains energy in every impact, in proportion to the step, because the strain rates "
    "read velocities of the two spheres that separate at the contact nodes where the velocities that moved the "
    "particles did not (the released elastic energy exceeds the work done on them). Ours reads the corrected "
    "velocities and stays below E0, with the loss of a grid contact (an inelastic collision of the nodal masses "
    "at each node in contact), so its spheres rebound below v0; its peak passes E0 only at dtscale 0.5, by 0.5 %, "
    "the scheme's own error at that step (one velocity field without contact peaks higher). Neither is exact at this "
    "resolution (four particles per radius); ours does not create energy in the impact, which a contact must not.",
]


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    threads = int(sys.argv[sys.argv.index("--threads") + 1]) if "--threads" in sys.argv else 2
    run(sys.argv[1], threads)
    print("\n".join(section_lines()))
