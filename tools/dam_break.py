#!/usr/bin/env python3
"""The dam break against Martin & Moyce's experiment (1952): the surge front under refinement.

A water column a = 1 m wide and 2a high (their n^2 = 2) stands in the corner of a free-slip
floor and wall and collapses under gravity: the current MPM3D-F90's null water (rho 997.5,
K 2e9, viscosity 0.001) with its weakly compressible EOS (c0 1415 m/s), bulk viscosity
1.5 / 1.0, sgmp and smoo, MUSL, one particle layer in plane strain, four particles per cell
and axis, as in the public dam-break deck of the current version but at three cell sizes
(0.25, 0.125, 0.0625 m), run to t = 0.68 s. The front is the bottom-right particle's x plus
half a particle spacing (`curv disx`: the current version numbers a block x fastest, so that
particle is the block's nx-th); it is compared in Martin & Moyce's variables Z = x / a
against T = t sqrt(2 g / a).

  dam_break.py deck DCELL OUT.mpm     write one deck
  dam_break.py study MPM3D OUTDIR     run the three resolutions, print the table
"""
import csv
import json
import math
import os
import subprocess
import sys

from study import section_start

A, G = 1.0, 9.81
CELLS = (0.25, 0.125, 0.0625)
END = 0.68
# Martin & Moyce (1952), n^2 = 2, surge front: (T = t sqrt(2g/a), Z = x/a), read from their
# figure for the columns of a = 2.25 in and a = 1.125 in (published values, up to T = 3).
MM_225 = [(0.832, 1.217), (1.219, 1.474), (1.997, 2.292), (2.547, 2.995)]
MM_1125 = [(0.849, 1.245), (1.212, 1.443), (1.602, 1.884), (2.283, 2.689), (2.950, 3.728)]

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CSV = os.path.join(ROOT, "docs", "verification", "dam_break.csv")
PNG = os.path.join(ROOT, "docs", "verification", "dam_break.png")


def write_deck(dcell, path):
    dp = dcell / 4.0
    nx, ny = int(round(A / dp)), int(round(2 * A / dp))
    lines = [
        "mpm3d dam break, cell %g m (our deck, tools/dam_break.py)" % dcell,
        "! Martin & Moyce's column (a = 1 m, height 2a), null water with the weakly compressible",
        "! EOS, sgmp and smoo; free-slip floor and wall. Units m kg N s Pa.",
        "nbco 1", "nbbo 1", "nbmp %d" % (nx * ny), "nmat 1", "",
        "spx %r %r" % (-dcell, 4.25),
        "spy %r %r" % (-dcell, 2.25),
        "spz 0 %r" % dcell,
        "dcell %r" % dcell, "",
        "dtscale 0.8", "endtime %r" % END, "outtime 0.1", "rpttime 0.01", "",
        "musl on", "sgmp", "smoo", "bulk 1.5 1.0",
        "curv disx %d" % nx, "",
        "fixed 2 0 2 0 2 2", "",
        "material", "  1  null  997.5  2.0e9  0.001", "seos 1 4 1415", "",
        "part bloc 1 1 997.5 %r 0 0 %r %d %d 1" % (dp, dcell / 2.0 - dp / 2.0, nx, ny),
        "load", "grav 1 0 -9.81 0", "endl", "", "endi"]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return nx, dp


def front(curve_file, x0):
    """(t, x_front) from the curve file (time, engk1, engi1, disx)."""
    out = []
    with open(curve_file) as f:
        for line in f.readlines()[1:]:
            w = line.split()
            if w:
                out.append((float(w[0]), x0 + float(w[-1])))
    return out


def interp(series, t):
    for (t0, x0), (t1, x1) in zip(series, series[1:]):
        if t0 <= t <= t1:
            return x0 + (x1 - x0) * (t - t0) / (t1 - t0) if t1 > t0 else x0
    return float("nan")


def study(mpm3d, outdir, threads=2):
    """Per resolution: particles, steps, wall time and the front at the experiment's times."""
    os.makedirs(outdir, exist_ok=True)
    runs = []
    for dcell in CELLS:
        name = "dam_n%d" % round(A / dcell)  # cells per metre (the output names stop at a dot)
        deck = os.path.join(outdir, name + ".mpm")
        nx, dp = write_deck(dcell, deck)
        summary = os.path.join(outdir, name + ".json")
        p = subprocess.run([mpm3d, "--threads", str(threads), "--quiet", "--summary", summary, "--out-dir", outdir,
                            deck], capture_output=True, text=True)
        if p.returncode != 0:
            runs.append(dict(dcell=dcell, status="failed: " + p.stderr.strip()[-200:]))
            continue
        with open(summary) as f:
            s = json.load(f)
        # The front particle's centre is half a spacing inside the column's edge.
        x0 = (nx - 0.5) * dp
        series = front(os.path.join(outdir, name + "_curv.dat"), x0 + dp / 2.0)
        runs.append(dict(dcell=dcell, status="ok", particles=s["particles"], steps=s["steps"],
                         wall_seconds=s.get("wall_seconds", float("nan")), series=series))
    return runs


def run(build, threads=2):
    """make report: the study in a scratch folder; docs/verification/dam_break.csv and .png."""
    import tempfile
    mpm3d = os.path.join(os.path.abspath(build), "cxx", "mpm3d")
    with tempfile.TemporaryDirectory() as work:
        runs = study(mpm3d, work, threads)
    os.makedirs(os.path.dirname(CSV), exist_ok=True)
    with open(CSV, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["dcell", "particles", "steps", "wall_seconds", "experiment", "T", "Z_experiment", "Z_mpm3d"])
        for r in runs:
            if r["status"] != "ok":
                w.writerow([r["dcell"], "", "", "", r["status"], "", "", ""])
                continue
            for label, data in (("a=2.25in", MM_225), ("a=1.125in", MM_1125)):
                for T, Z in data:
                    t = T / math.sqrt(2 * G / A)
                    w.writerow([r["dcell"], r["particles"], r["steps"], "%.3f" % r["wall_seconds"], label, T, Z,
                                "%.4f" % (interp(r["series"], t) / A)])
    plot(runs)
    return runs


def plot(runs):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for r in runs:
        if r["status"] != "ok":
            continue
        T = [t * math.sqrt(2 * G / A) for t, _ in r["series"]]
        ax.plot(T, [x / A for _, x in r["series"]], label="mpm3d sgmp, cell %g m (%d particles)"
                % (r["dcell"], r["particles"]))
    ax.plot(*zip(*MM_225), "ko", mfc="none", label="Martin & Moyce, a = 2.25 in")
    ax.plot(*zip(*MM_1125), "ks", mfc="none", label="Martin & Moyce, a = 1.125 in")
    ax.set(xlabel="T = t sqrt(2g/a)", ylabel="Z = surge front x / a", title="dam break, n^2 = 2")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(PNG, dpi=90)
    plt.close(fig)


def section_lines():
    """The report's section (docs/VERIFICATION.md) from docs/verification/dam_break.csv."""
    L, rows, when = section_start("## Dam break: the surge front against Martin & Moyce",
                                  CSV, "`make report`")
    if rows is None:
        return L
    cells = sorted({float(r["dcell"]) for r in rows}, reverse=True)
    ok = [r for r in rows if r["T"]]
    info = {float(r["dcell"]): r for r in ok}
    L += ["`tools/dam_break.py` (run %s, 2 threads): a water column a = 1 m wide and 2a high (Martin & "
          "Moyce's n^2 = 2) on a free-slip floor against a free-slip wall, the current version's null water "
          "(rho 997.5, K 2e9, viscosity 0.001) with its weakly compressible EOS (c0 1415 m/s), bulk viscosity "
          "1.5 / 1.0, sgmp and smoo, MUSL, four particles per cell and axis in one layer, to t = 0.68 s "
          "(T = 3.0). The surge front is the bottom-right particle's x plus half a spacing; Z = x / a, "
          "T = t sqrt(2 g / a). The experiment's points are read from their figure, for their columns of "
          "a = 2.25 in and 1.125 in." % when, "",
          "| T | Z, experiment (column) | " + " | ".join("Z, cell %g m" % c for c in cells) + " |",
          "|---|---|" + "---|" * len(cells)]
    points = []
    for r in ok:
        key = (float(r["T"]), r["experiment"])
        if key not in points:
            points.append(key)
    points.sort()
    mean = {c: [] for c in cells}
    for T, exp in points:
        z = [r for r in ok if float(r["T"]) == T and r["experiment"] == exp]
        ze = float(z[0]["Z_experiment"])
        cols = []
        for c in cells:
            m = [r for r in z if float(r["dcell"]) == c]
            if m:
                d = float(m[0]["Z_mpm3d"]) - ze
                mean[c].append(d / ze)
                cols.append("%.3f (%+.3f)" % (float(m[0]["Z_mpm3d"]), d))
            else:
                cols.append("-")
        L.append("| %.3f | %.3f (%s) | %s |" % (T, ze, exp.replace("a=", "a = ").replace("in", " in"),
                                                " | ".join(cols)))
    L += ["", "Runs: " + "; ".join("cell %g m: %s particles, %s steps, %.1f s" % (
        c, info[c]["particles"], info[c]["steps"], float(info[c]["wall_seconds"])) for c in cells if c in info) + "."]
    rel = {c: sum(v) / len(v) for c, v in mean.items() if v}
    if rel:
        L += ["", "Mean difference from the experiment, relative to its Z: " + ", ".join(
            "%+.1f %% at cell %g m" % (100 * rel[c], c) for c in cells if c in rel) + ". "
              "The coarsest grid follows the experiment closest and each refinement moves the front further "
              "ahead: the coarse grid's smoothing slows the thin leading tongue, and the refined answer is "
              "that of an inviscid, free-slip model. A computed front ahead of Martin & Moyce's is commonly "
              "reported for this case by particle methods (SPH, MPS, MPM): the experiment's gate was not "
              "removed instantly, and the floor's friction and the water's surface tension, absent from "
              "the model, slow the real front. The public deck of the current version (cell 0.125 m, five "
              "particles per cell and axis) ends at T = 3.01 with its front at x = 4.127 m (its disx 3.127, "
              "docs/CURRENT_DECKS.md, on which mpm3d agrees with it); ours at cell 0.125 m, four particles "
              "per cell and axis, reaches 4.003 at T = 2.95."]
    L += ["", "![dam break surge front](verification/dam_break.png)", ""]
    return L


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "deck":
        print(write_deck(float(sys.argv[2]), sys.argv[3]))
    elif len(sys.argv) == 4 and sys.argv[1] == "study":
        for r in study(sys.argv[2], sys.argv[3]):
            if r["status"] != "ok":
                print(r["dcell"], r["status"])
                continue
            print(r["dcell"], r["particles"], r["steps"], "%.2f s" % r["wall_seconds"],
                  " ".join("T %.2f Z %.3f" % (T, interp(r["series"], T / math.sqrt(2 * G / A)) / A)
                           for T, _ in MM_225 + MM_1125))
    else:
        sys.exit(__doc__)
