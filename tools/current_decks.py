#!/usr/bin/env python3
"""The current MPM3D-F90's public example decks against the current program's own results.

usage: tools/current_decks.py BUILD_DIR [--threads N] [--speed-runs R] [--out docs/CURRENT_DECKS.md]

Runs every deck of ../shared/decks/current (the decks are not ours to publish: they are read
from there and never copied into the repository) with BUILD_DIR/cxx/mpm3d to its end time,
compares the energy and curve files with ../shared/reference/current/<deck>/ (the current
program's run of the same deck) and writes one table per deck to docs/CURRENT_DECKS.md:
our value, the original's, the difference, and the note that explains a difference. A deck
mpm3d refuses is listed with the refusal. Exits 0 with a note when ../shared is absent.
"""
import argparse
import datetime
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(os.path.dirname(ROOT), "shared")
DECKS = os.path.join(SHARED, "decks", "current")
REFS = os.path.join(SHARED, "reference", "current")

# Why our figures differ from the original's, per deck (what we know; docs/DECK_FORMAT.md
# lists the keywords).
NOTES = {
    "SoftBeam_SBTL_0p1mesh_SBTL": (
        "Total Lagrangian MPM (TLmp) with a nearly incompressible neo-Hookean beam (nu 0.499). "
        "The total energy agrees within 0.2 %, the kinetic and internal energies and the tip's "
        "displacement differ by up to half their largest values: the current program's "
        "trilinear TLmp never computes the particles' natural coordinates in their reference "
        "cells (only its sgmp branch does), so every particle takes the shape functions and "
        "gradients of its cell's centre, where we take them at the particle's reference "
        "position, and it weighs the work of P on dF by the current volume where we use V0 (P is "
        "per reference volume): the rule `tl_shape`. With the original's rules (`tl_shape=centre`, "
        "and `deck_reals=single`, to which nu = 0.499 makes 1 - 2 nu sensitive) the run agrees "
        "with the current program's (second column). We keep the shape functions at the "
        "particles' positions."),
    "Cook_membrane_BSMPM5776p_Cookmo_Bimp": (
        "B-spline MPM (bimp) on the nearly incompressible neo-Hookean Cook membrane (nu 0.499), "
        "loaded quasi-statically (QuLo 15, Damp 0.3) and run on until the kinetic share of the "
        "energy is below 0.005 after t = 100, as the original. The same number of steps as the "
        "original, the energies and the tip displacement equal to its four printed digits at "
        "the end; over the whole run every column of the energy and curve files within 0.08 % "
        "of its largest value. The agreement rests on mpm3d using the original's basis (node i "
        "carries the quadratic "
        "B-spline centred at the centre of cell i) and its two fixed node layers with 27-node "
        "stencils (docs/DECK_FORMAT.md)."),
    "Cook_membrane_SG5776p_Cookmo_SG": (
        "Smoothed-gradient MPM (sgmp) on the same membrane, one cell thick (the particles at the "
        "cell centres). The same number of steps, the energies and the tip displacement equal "
        "to the original's four printed digits over the first 2000 steps (test "
        "current_reference.cook_sg) and at the end. The agreement rests on mpm3d using the "
        "original's exchanges "
        "through the cell centres, its rules at held faces (the auxiliary coordinate pushed "
        "to the nearer centre; G2P between the face and the cell centre) and its two fixed node "
        "layers (docs/DECK_FORMAT.md)."),
    "DamBreak_SGMPM_Dam_SGR2": (
        "The dam break: the current version's null water (density, bulk modulus, viscosity), "
        "its weakly compressible EOS (seos type 4), bulk viscosity 1.5/1.0, sgmp, gravity. The "
        "same number of steps; kinetic energy and the tracked particles' displacements (the "
        "surge front, disx, and the column's top, disy) equal to the original's four printed "
        "digits to the end. The internal energy, 0.2 % of the energy, differs by up to 4 % of its "
        "value by our rules: we switch the bulk viscosity on where the volume shrinks, the "
        "original where the previous mean stress is compressive, and it counts q's work with "
        "the new q (rules `bulk_switch`, `bulk_work`); our viscous stress is the deviator "
        "2 mu dev(D), where the original's 1/3 in integer arithmetic makes its trace term zero "
        "(rule `fluid_viscous`). With the original's rules the internal energy agrees too."),
    "SGDeto1k": (
        "The one-dimensional TNT detonation with sgmp: a grid one cell thick in y and z. Here "
        "the original reads beyond its auxiliary grid: in G2P a particle next to a held face "
        "weighs the cell centres beyond the grid's single layer, which the original skips, so "
        "every particle receives only a quarter of the grid's velocity and acceleration. We "
        "give such weights to the nearest centre (the weights sum to one). Our kinetic energy "
        "is therefore about 17 times the original's after 2000 steps (2.5 against 0.14), and "
        "the step, which shrinks with the particle velocity, is shorter. The rule `sg_beyond=drop` "
        "drops those weights as the original does: with the original's rules the run agrees "
        "with the original's (second column). The standard MPM run of the same charge "
        "(book deck Deto1k) has a kinetic energy of 12 at t = 0.005, where the original's "
        "SGDeto1k has 0.5: the original's figure is the artefact, not the physics."),
    "FreeSoftBeam_MPM_v0p3_FreeSB_MPM": (
        "The energies agree with the original's to its four printed digits to t = 1.9 and within "
        "0.2 % of the initial energy to the end (the internal energy after 5 steps agrees to 8 "
        "digits with the original program rebuilt here). Both runs gain energy slowly (+4.6 % at "
        "t = 3: MUSL with linear shape functions on a freely vibrating beam). The agreement "
        "rests on the current program's default artificial bulk viscosity (1.5, 0.06, "
        "applied to the stress), which current decks get (docs/DECK_FORMAT.md); without it "
        "our energy grows by 12 % instead of 4.6 % (2026-11-25)."),
}


def load_rows(path, skip_header=False):
    rows = []
    with open(path) as f:
        for i, line in enumerate(f):
            if skip_header and i == 0:
                continue
            try:
                rows.append([float(v) for v in line.split()])
            except ValueError:
                pass
    return rows


def at_time(rows, t, col):
    """Linear interpolation of column col at time t (column 0)."""
    for a, b in zip(rows, rows[1:]):
        if a[0] <= t <= b[0]:
            w = 0.0 if b[0] == a[0] else (t - a[0]) / (b[0] - a[0])
            return a[col] + w * (b[col] - a[col])
    return rows[-1][col] if rows and t >= rows[-1][0] else float("nan")


def original_ns(ref_dir):
    try:
        with open(os.path.join(ref_dir, "timing.txt")) as f:
            for line in f:
                if "particle cycle" in line:
                    return float(line.split(":")[1].split()[0])
    except OSError:
        pass
    return None


def run_deck(mpm3d, deck, threads, work):
    os.makedirs(work, exist_ok=True)
    summary = os.path.join(work, "summary.json")
    p = subprocess.run([mpm3d, "--threads", str(threads), "--quiet", "--out-dir", work, "--summary", summary, deck],
                       capture_output=True, text=True)
    info = {}
    if os.path.exists(summary):
        with open(summary) as f:
            info = json.load(f)
    return p.returncode, p.stderr.strip(), info


def median_ns(mpm3d, deck, threads, first_ns, runs):
    """The median time per particle-step of the run already made (first_ns) and runs - 1
    more without output: one run on a machine whose cores come and go is not a figure."""
    times = [first_ns]
    with tempfile.TemporaryDirectory() as work:
        summary = os.path.join(work, "s.json")
        for _ in range(runs - 1):
            subprocess.run([mpm3d, "--threads", str(threads), "--quiet", "--no-output", "--summary", summary, deck],
                           check=True, capture_output=True)
            with open(summary) as f:
                times.append(json.load(f)["ns_per_particle_step"])
    return statistics.median(times)


def g(v):
    return "-" if v is None or v != v else f"{v:.4g}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--speed-runs", type=int, default=3, help="runs whose median time the speed column takes")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "CURRENT_DECKS.md"))
    a = ap.parse_args()
    if not os.path.isdir(DECKS):
        print(f"current_decks: {DECKS} absent: nothing to compare")
        return 0
    mpm3d = os.path.join(os.path.abspath(a.build), "cxx", "mpm3d")
    when = datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M UTC")
    out = ["# The current MPM3D-F90's public decks", "",
           f"Generated by `tools/current_decks.py` (`make report`) on {when}, {platform.machine()}, "
           f"{os.cpu_count()} cores, `mpm3d --threads {a.threads}`, the time per particle-step the median of "
           f"{a.speed_runs} runs. Each deck of the public decks folder beside the checkout "
           "(`shared/decks/current`, not in the repository) run to its end against the current program's "
           "run of the same deck (from the reference folder beside it, `shared/reference/current`: its own "
           "energies, curves and time per particle-step, serial, "
           "on its machine). Energies in the deck's units; 'difference' is ours minus the original's "
           "relative to the largest total energy of the original's run (for a curve: to its largest magnitude there). "
           "The speed-up column divides by the original's time from its own run (another day; the side-by-side "
           "figures, both programs on this machine alternately, are in docs/PERFORMANCE.md).", ""]
    summary_rows = []
    for name in sorted(f[:-4] for f in os.listdir(DECKS) if f.endswith(".mpm")):
        deck = os.path.join(DECKS, name + ".mpm")
        ref = os.path.join(REFS, name)
        with tempfile.TemporaryDirectory() as work:
            rc, err, info = run_deck(mpm3d, deck, a.threads, work)
            out += [f"## {name}", ""]
            ons = original_ns(ref)
            if rc != 0:
                first = err.splitlines()[0] if err else f"exit status {rc}"
                first = first.replace(DECKS + os.sep, "")  # no machine paths in the docs
                out += [f"Refused: `{first}`", ""]
                summary_rows.append((name, "refused", "-", g(ons), "-"))
                continue
            ours = load_rows(os.path.join(work, "EnergyPlot.dat"))
            orig = load_rows(os.path.join(ref, "EnergyPlot.dat")) if os.path.isdir(ref) else []
            ns = info.get("ns_per_particle_step")
            if ns and a.speed_runs > 1:
                ns = median_ns(mpm3d, deck, a.threads, ns, a.speed_runs)
            out += [f"{info.get('particles')} particles, {info.get('steps')} steps to t = {g(info.get('time'))}; "
                    f"dt {g(info.get('dt_min'))} .. {g(info.get('dt_max'))}.", ""]
            if orig:
                # Relative to the largest total energy of the original's run (a deck that starts
                # at rest has an initial total of nearly zero).
                e0 = max(abs(r[1]) for r in orig) or 1.0
                tend = min(ours[-1][0], orig[-1][0])
                out += ["| t | quantity | mpm3d | original | difference |", "|---|---|---|---|---|"]
                for k in range(1, 6):
                    t = tend * k / 5.0
                    for col, q in ((1, "total"), (2, "kinetic"), (3, "internal")):
                        x, y = at_time(ours, t, col), at_time(orig, t, col)
                        out.append(f"| {t:.4g} | {q} | {g(x)} | {g(y)} | {100.0 * (x - y) / e0:+.2f} % |")
                out.append("")
                # The deck's curve variables (the curve file's columns after time, named in
                # its header): 'difference' relative to the original's largest magnitude.
                cname = name + "_curv.dat"
                if os.path.exists(os.path.join(ref, cname)) and os.path.exists(os.path.join(work, cname)):
                    with open(os.path.join(ref, cname)) as f:
                        heads = f.readline().split()
                    cours = load_rows(os.path.join(work, cname), True)
                    corig = load_rows(os.path.join(ref, cname), True)
                    out += ["| t | curve | mpm3d | original | difference |", "|---|---|---|---|---|"]
                    for col in range(1, len(heads)):
                        scale = max(abs(r[col]) for r in corig) or 1.0
                        for k in range(1, 6):
                            t = tend * k / 5.0
                            x, y = at_time(cours, t, col), at_time(corig, t, col)
                            out.append(f"| {t:.4g} | {heads[col]} | {g(x)} | {g(y)} | "
                                       f"{100.0 * (x - y) / scale:+.2f} % |")
                    out.append("")
            speed = f"{ons / ns:.2f}" if ns and ons else "-"
            out += [f"Speed: mpm3d {g(ns)} ns per particle-step ({a.threads} threads, this machine), the "
                    f"original {g(ons)} (serial, its machine): {speed}x.", ""]
            if name in NOTES:
                out += [NOTES[name], ""]
            summary_rows.append((name, "runs", g(ns), g(ons), speed))
    head_len = 5  # title, blank, the paragraph, blank: the summary table goes after them
    out[head_len - 1:head_len - 1] = \
        ["| deck | mpm3d | ns per particle-step | original ns | speed-up |", "|---|---|---|---|---|"] + \
        [f"| {r[0]} | {r[1]} | {r[2]} | {r[3]} | {r[4]} |" for r in summary_rows] + [""]
    # Keep the side-by-side table of every public deck (tools/public_decks.py) in its place.
    begin, end = "<!-- PUBLIC_DECKS begin -->", "<!-- PUBLIC_DECKS end -->"
    if os.path.exists(a.out):
        old = open(a.out).read()
        if begin in old and end in old:
            out[1:1] = ["", begin + old.split(begin, 1)[1].split(end, 1)[0] + end]
    with open(a.out, "w") as f:
        f.write("\n".join(out))
    print(f"current_decks: wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
