#!/usr/bin/env python3
"""Every public MPM3D-F90 deck against the original program that reads it, side by side.

usage: tools/public_decks.py BUILD_DIR --repo MPM3D_F90 --book EXE --current EXE --runs DIR
                             [--threads 2] [--only NAME[,NAME...]] [--out docs/CURRENT_DECKS.md]

MPM3D_F90 is a checkout of the public repository github.com/xzhang66/MPM3D-F90 (its `Data/`
and `VolumetricLockingEx/` decks, commit 4a6275f); --book and --current are the original
programs built from it at commits 2284feb and 4a6275f (the latter with its one-line gfortran
fix, `if (p_type(i) /= 0)` in `AuxiliaryGridSHP`). None of them is part of this repository:
build them outside it. The 26 readable decks of the current version run against the current
program, the five book decks (`Taylor`, `TNT3D`, `Deto1k`, `LeadHypervelocityImpact` cut at
0.006 ms, `Slopefail`) also against the book program: 31 runs. Each deck runs to its end in
DIR/NAME/original (kept: a finished original run is reused, the originals take hours) and
DIR/NAME/mpm3d, and both files are compared as `mpm3d-compare` does (tools/mpm3d_compare.py):
every column of EnergyPlot.dat and of the curve file, the largest difference over the run in
% of the column's largest magnitude in the original's run. mpm3d runs twice: by our rules
(DIR/NAME/mpm3d) and by the original program's (DIR/NAME/mpm3d_rules: `--rules original`,
or `--rules current` for a book deck run against the current program; mpm3d --help lists
the rules). The table replaces the block
between the PUBLIC_DECKS markers of --out; NOTES below says why a deck differs, each cause
found by experiment.

With --newest EXE (the newest program, commit 17fd4ee, built outside the repository from the
shared folder's sources), the six decks that program added run against it too (by our rules
and by `--rules original`): the three R1 dam breaks of --newest-decks (default: the shared
folder's decks/newest) and the three 3D landslides, written there by its
make_landslide_decks.py and cut at t = 0.03 (the newest program takes 0.3-0.6 s a step on them;
their whole runs are in docs/PERFORMANCE.md). Their table replaces the block between the
NEWEST_DECKS markers. `--only newest` runs those alone.
"""
import argparse
import datetime
import importlib.util
import json
import os
import platform
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BEGIN, END = "<!-- PUBLIC_DECKS begin -->", "<!-- PUBLIC_DECKS end -->"

_spec = importlib.util.spec_from_file_location("mpm3d_compare", os.path.join(HERE, "mpm3d_compare.py"))
compare = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(compare)

VL = "VolumetricLockingEx/"
# (name, deck in the public repository, which original, end time override)
DECKS = [
    ("Taylor", "Data/Taylor.mpm", "book", None),
    ("TNT3D", "Data/TNT3D.mpm", "book", None),
    ("Deto1k", "Data/Deto1k.mpm", "book", None),
    ("LeadHypervelocityImpact", "Data/LeadHypervelocityImpact.mpm", "book", "0.006"),
    ("Slopefail", "Data/Slopefail.mpm", "book", None),
    ("Taylor (current program)", "Data/Taylor.mpm", "current", None),
    ("TNT3D (current program)", "Data/TNT3D.mpm", "current", None),
    ("Deto1k (current program)", "Data/Deto1k.mpm", "current", None),
    ("LeadHypervelocityImpact (current program)", "Data/LeadHypervelocityImpact.mpm", "current", "0.006"),
    ("Slopefail (current program)", "Data/Slopefail.mpm", "current", None),
    ("BSMPMDeto1k", "Data/BSMPMDeto1k.mpm", "current", None),
    ("SGDeto1k", "Data/SGDeto1k.mpm", "current", None),
] + [(p[len(VL):-4].replace("/", "_"), p, "current", None) for p in (
    VL + "Cook_membrane/MPM5776p/Cookmo_MPM.mpm",
    VL + "Cook_membrane/GIMP5776p/Cookmo_Gimp.mpm",
    VL + "Cook_membrane/BSMPM5776p/Cookmo_Bimp.mpm",
    VL + "Cook_membrane/SG5776p/Cookmo_SG.mpm",
    VL + "Cook_membrane/MPM23072p/Cookmo_0p5m.mpm",
    VL + "Cook_membrane/GIMP23072p/Cookmo_GIMP0p5m.mpm",
    VL + "Cook_membrane/BSMPM23072p/Cookmo_BS0p5m.mpm",
    VL + "Cook_membrane/SG23072p/Cookmo_SG0p5m.mpm",
    VL + "DamBreak/MPM/Dam_R2.mpm",
    VL + "DamBreak/SGMPM/Dam_SGR2.mpm",
    VL + "DamBreak/SGMPMvsPressure/Dam_SGR2.mpm",
    VL + "FreeSoftBeam/MPM_v0p3/FreeSB_MPM.mpm",
    VL + "FreeSoftBeam/MPM_v0p499/FreeSB_MPM.mpm",
    VL + "FreeSoftBeam/SGMPM_v0p3/FreeSB_SGMPM.mpm",
    VL + "FreeSoftBeam/SGMPM_v0p499/FreeSB_SGMPM.mpm",
    VL + "SoftBeam/SBTL_0p1mesh/SBTL.mpm",
    VL + "SoftBeam/SBTL_0p05mesh/SBTL.mpm",
    VL + "SoftBeam/SBSGTL_0p1mesh/SBSGTL.mpm",
    VL + "SoftBeam/SBSGTL_0p05mesh/SBSGTL.mpm")]

# The newest program's decks (--newest): (name, deck in --newest-decks, end time override).
NEWEST_DECKS = [
    ("DamBreak_MPM_R1_Dam_R1 (newest)", "DamBreak_MPM_R1_Dam_R1.mpm", None),
    ("DamBreak_SGMPM_R1_Dam_SGR1 (newest)", "DamBreak_SGMPM_R1_Dam_SGR1.mpm", None),
    ("DamBreak_SGMPMvsPressureR1_Dam_SGR1 (newest)", "DamBreak_SGMPMvsPressureR1_Dam_SGR1.mpm", None),
    ("3DProgressiveLandslide_BS (newest, to t = 0.03)", "BS.mpm", "0.03"),
    ("3DProgressiveLandslide_GIMP (newest, to t = 0.03)", "GIMP.mpm", "0.03"),
    ("3DProgressiveLandslide_SG (newest, to t = 0.03)", "SG.mpm", "0.03"),
]
LANDSLIDES = ("BS.mpm", "GIMP.mpm", "SG.mpm")
NEWEST_BEGIN, NEWEST_END = "<!-- NEWEST_DECKS begin -->", "<!-- NEWEST_DECKS end -->"

# Why a deck differs by more than the criterion (kinetic, total and curves 1 %, internal 5 % of
# the column's largest magnitude), each cause shown by experiment: the rule switched, the
# difference gone.
_spec = importlib.util.spec_from_file_location("current_decks", os.path.join(HERE, "current_decks.py"))
_current = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_current)
NOTES = dict(_current.NOTES)  # the six decks of shared/decks/current, studied step by step
NOTES.update({
    "DamBreak_MPM_R1_Dam_R1 (newest)": (
        "Linear MPM dam break at the coarser resolution R1. The newest program (as the 2025 one) "
        "replaces the first EOS coefficient of every `null` material by the null's wave speed "
        "sqrt(K/rho0) when it sets up the particles: c0 1416.0 instead of the deck's 1415, so its "
        "internal energy is 0.14 % above ours from the first step and the runs drift apart after "
        "t = 0.06 (rule `null_eos`). With that rule among the original's, every row of both energy "
        "files agrees to the printed digits until t = 0.80; the surge then hits the far wall and "
        "splashes, and the runs end 1.4 % (kinetic) and 6.5 % (internal) apart. Our own run under the "
        "same rules with one deck real moved by one unit in its last single-precision digit (the "
        "water's density 997.5 -> 997.50006, its bulk modulus 2.0e9 -> 2.00000013e9, the particle "
        "spacing 0.025 -> 0.025000002, gravity 9.81 -> 9.8100014; 2026-12-05) differs from the "
        "unperturbed run by 2.4-5.0 % (kinetic) and 8.1-26.6 % (internal), and those runs from each "
        "other by up to 6.5 % and 27.8 %: the original lies inside the spread of our own rounding. The newest "
        "program built with `-fcheck=bounds` runs the deck without a read outside its arrays and writes the "
        "same energy file."),
    "DamBreak_SGMPM_R1_Dam_SGR1 (newest)": (
        "The sgmp dam break at R1: 3.2 % apart in kinetic energy until the rule `null_eos` (the "
        "null's wave speed in place of the deck's c0, as the note above); with the original's rules "
        "every column agrees to the printed digits."),
    "DamBreak_SGMPMvsPressureR1_Dam_SGR1 (newest)": (
        "The small sgmp dam break (14,400 particles, cells of 1.9 mm) with `bulk 1.5 0.5`, a linear "
        "coefficient eight times the default. By our rules the water's internal energy (0.1 % of its energy "
        "in the original's run) ends 12 times the original's and a front particle's disx differs by up to "
        "80 %: our bulk viscosity acts wherever the volume shrinks, the original's only where the mean "
        "stress is compressive (rule `bulk_switch`: restored alone to ours under the original's other rules "
        "it takes the internal energy to 214 times the original's; `bulk_work` alone 1.4 %, `null_eos` alone "
        "0.19 %; 2026-12-05). With the original's rules every column agrees within 0.04 %."),
    "3DProgressiveLandslide_BS (newest, to t = 0.03)": (
        "The three landslides (clay, MUSL, `smoo`, `bulk`): by our rules within 0.24 % (kinetic) and 0.39 % "
        "(internal) over the first 0.03 s; with the original's rules (`clay_return`, `bulk_switch`, "
        "`bulk_linear`, `bulk_work` among them) every column to the printed digits. Their whole runs to "
        "t = 5.5 s (the newest program would take 2-6 hours for each): docs/VERIFICATION.md and "
        "docs/PERFORMANCE.md."),
    "DamBreak_MPM_Dam_R2": (
        "Linear MPM dam break, the current version's null water. By our rules the internal energy "
        "(a tenth of the kinetic at the end) drifts apart by up to 7 % of its largest value after "
        "t = 0.05: the bulk viscosity's switch and work and the single-precision deck reals "
        "(rules `bulk_switch`, `bulk_work`, `deck_reals`); with the original's rules it stays "
        "within 4 %. The splashing surge amplifies any last-digit difference: our own run with the "
        "water's density moved by 6e-8 (997.5 -> 997.50006) moves its internal energy by up to "
        "5.7 %."),
    "FreeSoftBeam_MPM_v0p499_FreeSB_MPM": (
        "The free soft beam at nu 0.499 (linear MPM). The original reads deck reals in single "
        "precision; near incompressibility (1 - 2 nu = 0.002) that moves lambda and the wave "
        "speed by 1e-5 relative, and over the run's 53,604 steps the beam's phase drifts (rule "
        "`deck_reals`): by the original's rules the run agrees."),
    "SoftBeam_SBTL_0p05mesh_SBTL": (
        "The same beam on the finer grid: kinetic and internal energy up to 12.5 % and 14 % apart "
        "by our rules, the current program's TLmp taking every particle's shape functions at its "
        "cell's centre (rule `tl_shape`, the 0.1 mesh's note)."),
    "Slopefail": (
        "Drucker-Prager slope under gravity. The book program reads `bulk 1.5 0.06` but does not "
        "apply it (rule `bulk_book`: 15,888 steps against our 16,870), and its Drucker-Prager "
        "return takes the shear branch wherever the trial stress is above the corner line, "
        "leaving mean stresses beyond its tension cut-off, and its tension return keeps the "
        "deviator (rule `dp_return`; docs/DECK_FORMAT.md, the method table's note 5). With the "
        "original's rules the run agrees to the printed digits. We keep our returns, which end "
        "on the yield surface."),
    "Deto1k (current program)": (
        "A book deck read by the current program, which recomputes the time step every step "
        "(28,852 steps), gives `hiex` no bulk viscosity and burns by a step. With its rules "
        "(`--rules current`) the energies agree within 0.1 % (total), 0.6 % (internal) and 4.9 % "
        "(kinetic); the pressure curves behind the fronts differ by up to 101 %: the products' "
        "oscillations behind the front amplify rounding, as the book deck's note shows. Our own "
        "run under the same rules with one deck real moved by one unit in its last "
        "single-precision digit (the TNT's density, detonation velocity, or JWL A, B or R2: five "
        "runs, 2026-11-28) differs from the unperturbed one by 2.8-4.1 % (kinetic) and 71-139 % "
        "(pressure curves), and three of them from each other by up to 4.8 %; the original lies "
        "3.4-4.9 % (kinetic) from the unperturbed run and those three: inside the spread of our "
        "own rounding."),
    "TNT3D (current program)": (
        "The current program on the book deck: its step burn, its time step every step (237 steps "
        "against the book's 208) and its default bulk viscosity on the copper plates (none on the "
        "explosive). With its rules (`--rules current`: `program`, `time_step`, `burn`, "
        "`bulk_linear`, `bulk_switch`, `bulk_work`) every column agrees within 0.02 %."),
    "LeadHypervelocityImpact (current program)": (
        "The lead sphere at 6.58 km/s read by the current program. That program computes its "
        "time step every step from the wave speed plus the fastest particle (26,975 steps against "
        "the book's fixed 6,353) and gives `sjcf` its default bulk viscosity without the linear "
        "term, switched by the mean stress. We read the deck as the book does: kinetic energy up "
        "to 8.2 % apart and internal energy up to 42 %, where the current program damps the "
        "book's sloshing of energy between the sphere and the plate (2026-11-27). The rules "
        "`program`, `time_step`, `bulk_switch`, `bulk_linear` and `bulk_work` (`--rules "
        "current`) are that program's choices: over the first 1,848 steps of the current "
        "program's run (t up to 4.6e-4, 2026-11-28; its whole run did not finish in that "
        "session) our run differs by 8.1 % (kinetic) and 74 % (internal) by our rules, and by "
        "0.000 % in every column with `--rules current`."),
    "Slopefail (current program)": (
        "The current program on the book deck: its time step every step (16,016 steps against "
        "our book-mode 16,870), its Drucker-Prager branches (the book deck's note) and its bulk "
        "viscosity without the linear term for `dpm`. With its rules (`--rules current`) the run "
        "agrees to the printed digits."),
    "TNT3D": (
        "Kinetic energy up to 3.9 % apart (internal 1.5 %) by our rules: the original's burn "
        "fraction is a step (the whole pressure at the lighting time), ours a ramp over 1.5 "
        "cells (rule `burn`; docs/EXPLOSIVES.md, 'What remains'). With the original's rules "
        "every energy agrees within 0.05 %. Refining the cell, the two burns converge to each "
        "other."),
    "Deto1k": (
        "The book program reads `bulk 1.5 0.06` but does not apply it (rule `bulk_book`: 20,790 "
        "steps against our 22,075) and burns by a step (rule `burn`). With its rules the energies "
        "agree within 0.1 % (total), 0.5 % (internal) and 3.9 % (kinetic); the pressure curves "
        "behind the fronts differ by up to 71 %: there the products' oscillations amplify "
        "rounding, and the original compiled with fused multiply-adds differs from itself "
        "(docs/EXPLOSIVES.md, 'What remains'). Our own run under the same rules with the TNT's "
        "density or detonation velocity moved by one unit in its last single-precision digit "
        "(1.63e-3 -> 1.6300001e-3, 6930 -> 6930.0005; 2026-11-28) moves by 4.8-4.9 % (kinetic) "
        "and 75-143 % (pressure curves): the original lies inside that spread."),
})


def slug(name):
    name = name.replace(" (current program)", "@current")
    return name.split(" (newest")[0] + "@newest" if " (newest" in name else name


def prepare(deck_src, end, path):
    """The deck as the user has it, or with its end time cut (LeadHypervelocityImpact)."""
    with open(deck_src, errors="replace") as f:
        lines = f.readlines()
    with open(path, "w") as f:
        for line in lines:
            if end is not None and line.split()[:1] and line.split()[0].lower()[:4] == "endt":
                line = "endtime %s\n" % end
            f.write(line)


def run(cmd, cwd):
    """(exit status, wall seconds) of cmd run in cwd, its output in cwd/run.log."""
    t0 = time.time()
    with open(os.path.join(cwd, "run.log"), "w") as log:
        rc = subprocess.run(cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT).returncode
    return rc, time.time() - t0


def run_original(exe, deck, work):
    """The original's run, reused when a finished one is there (the file 'done')."""
    done = os.path.join(work, "done")
    if os.path.exists(done):
        with open(done) as f:
            return json.load(f)
    os.makedirs(work, exist_ok=True)
    shutil.copy(deck, work)
    rc, wall = run([exe, os.path.basename(deck)], work)
    for name in os.listdir(work):  # the animation frames are not compared: keep the disk free
        if name.endswith(".vtu") or "_anim" in name:
            os.remove(os.path.join(work, name))
    info = {"rc": rc, "wall": wall}
    with open(done, "w") as f:
        json.dump(info, f)
    return info


def rules_preset(name):
    """The --rules that makes mpm3d follow the program a row compares with."""
    return "current" if name.endswith("(current program)") else "original"


def run_mpm3d(exe, deck, threads, work, reuse=False, rule_args=()):
    summary = os.path.join(work, "summary.json")
    if reuse and os.path.exists(summary):
        with open(summary) as f:
            return dict(json.load(f), rc=0, wall=0.0)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    shutil.copy(deck, work)
    summary = os.path.join(work, "summary.json")
    rc, wall = run([exe, "--threads", str(threads), "--quiet", "--out-dir", ".", "--summary", summary]
                   + list(rule_args) + [os.path.basename(deck)], work)
    info = {"rc": rc, "wall": wall}
    if os.path.exists(summary):
        with open(summary) as f:
            info.update(json.load(f))
    return info


def rows_of(stem, orig_dir, our_dir):
    """The compared columns of both runs: energies and curves."""
    rows, _ = compare.compare_file("energy", os.path.join(orig_dir, compare.ENERGY_FILE),
                                   os.path.join(our_dir, compare.ENERGY_FILE), compare.ENERGY_COLUMNS)
    curves = compare.curve_file(orig_dir, stem)
    if curves:
        more, _ = compare.compare_file("curves", curves, compare.curve_file(our_dir, stem))
        rows += more
    return rows


def verdict(rows):
    """(worst kinetic/total/curve difference, worst internal, within the criterion)."""
    def is_internal(r):  # the energy file's column and the curves of a body's internal energy
        return r.column == "internal" or r.column.startswith("engi")
    other = [r.max_diff for r in rows if r.max_diff is not None and not is_internal(r)]
    internal = [r.max_diff for r in rows if r.max_diff is not None and is_internal(r)]
    worst_o, worst_i = max(other, default=0.0), max(internal, default=0.0)
    return worst_o, worst_i, worst_o <= 1.0 and worst_i <= 5.0


def pct(v):
    return "-" if v is None else ("%.2f" % v if v < 100 else "%.0f" % v)


def newest_table(results, when, threads):
    """The newest program's decks: the same columns under their own heading and markers."""
    rows = table(results, when, threads)[5:-1]  # the header lines, the rows and the notes
    return [NEWEST_BEGIN, "## The newest program's decks (commit 17fd4ee), side by side", "",
            f"`tools/public_decks.py --newest` on {when}, {platform.machine()}, {os.cpu_count()} cores: the "
            "six decks the newest MPM3D-F90 added, run by that program (serial, gfortran 12 `-O2`, built "
            f"here from its sources) and by `mpm3d --threads {threads}`, by our rules and by the original "
            "program's (`--rules original`), compared as the table above. The landslides are cut at "
            "t = 0.03 (140-190 steps; their whole runs: docs/PERFORMANCE.md and docs/VERIFICATION.md).",
            ""] + rows + [NEWEST_END]


def table(results, when, threads):
    out = [BEGIN, "## Every public deck against the original program, side by side", "",
           f"`tools/public_decks.py` on {when}, {platform.machine()}, {os.cpu_count()} cores: each public "
           f"deck run to its end by the original program (serial, gfortran 12 `-O2`, built here from the "
           f"public repository) and by `mpm3d --threads {threads}` on this machine, by our rules and by "
           "the original program's (`--rules original`; `--rules current` for the book decks run against the "
           "current program). Columns: the largest difference over the run, in % of the column's largest "
           "magnitude in the original's run, on the original's times (as `mpm3d-compare`); 'curves' is the "
           "worst curve column. Criterion: kinetic, total and curves within 1 %, internal energy within 5 %, "
           "or the cause shown by experiment (notes below the table). Speed side by side: "
           "docs/PERFORMANCE.md.", "",
           "| deck | program | particles | steps ours / original's rules / original | total | kinetic | internal "
           "| curves | with the original's rules: total | kinetic | internal | curves | within |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        if r.get("pending"):
            out.append(f"| {r['name']} | {r['program']} |" + " - |" * 10 + " the original's run not finished |")
            continue
        if r.get("refused"):
            out.append(f"| {r['name']} | {r['program']} |" + " - |" * 10 + f" refused: {r['refused']} |")
            continue

        def cells(rows):
            by = {row.column: row.max_diff for row in rows}
            curves = [row.max_diff for row in rows if row.file == "curves" and row.max_diff is not None]
            return (f"{pct(by.get('total'))} | {pct(by.get('kinetic'))} | {pct(by.get('internal'))} | "
                    f"{pct(max(curves) if curves else None)}")
        ok = verdict(r["rules_rows"])[2]
        out.append(f"| {r['name']} | {r['program']} | {r['particles']} | {r['steps']} / {r['rules_steps']} / "
                   f"{r['orig_steps']} | {cells(r['rows'])} | {cells(r['rules_rows'])} | "
                   f"{'yes' if ok else 'no: note'} |")
    out.append("")
    for r in results:
        if r["name"] in NOTES:
            out += [f"**{r['name']}.** " + NOTES[r["name"]], ""]
    out.append(END)
    return out


def write(out_path, block, begin=BEGIN, end=END):
    """block (lines, from its begin marker to its end marker) in place of the one between the
    markers in out_path, or after the file's title line when it has none."""
    text = open(out_path).read() if os.path.exists(out_path) else "# The current MPM3D-F90's public decks\n"
    if begin in text and end in text:
        head, rest = text.split(begin, 1)
        text = head + "\n".join(block) + rest.split(end, 1)[1]
    else:
        title, _, body = text.partition("\n")
        text = title + "\n\n" + "\n".join(block) + "\n" + body
    with open(out_path, "w") as f:
        f.write(text)


def add_program_args(ap):
    """The arguments both comparison tools take: the build and the original programs."""
    ap.add_argument("build")
    ap.add_argument("--repo", required=True, help="checkout of the public MPM3D-F90 (its decks)")
    ap.add_argument("--book", required=True, help="the book program (commit 2284feb)")
    ap.add_argument("--current", required=True, help="the current program (commit 4a6275f)")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_program_args(ap)
    ap.add_argument("--runs", required=True, help="where both programs run (outside the repository)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--only", default="", help="only the decks whose names contain one of these")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "CURRENT_DECKS.md"))
    ap.add_argument("--reuse", action="store_true",
                    help="keep mpm3d's finished runs too (a rerun of the table with the same build)")
    ap.add_argument("--finished-only", action="store_true",
                    help="leave out the decks whose original run is not finished (start none)")
    ap.add_argument("--newest", help="the newest program (commit 17fd4ee): also its six decks")
    ap.add_argument("--newest-decks", default=os.path.join(ROOT, "..", "shared", "decks", "newest"),
                    help="the newest decks (the R1 dam breaks and make_landslide_decks.py)")
    a = ap.parse_args()
    mpm3d = os.path.join(os.path.abspath(a.build), "cxx", "mpm3d")
    wanted = [w for w in a.only.split(",") if w]
    results, newest = [], []
    todo = list(DECKS)
    if a.newest:
        todo += [(name, rel, "newest", end) for name, rel, end in NEWEST_DECKS]
        landslide_dir = os.path.join(os.path.abspath(a.runs), "_landslide_decks")
        if not all(os.path.exists(os.path.join(landslide_dir, d)) for d in LANDSLIDES):
            os.makedirs(landslide_dir, exist_ok=True)
            subprocess.run([sys.executable, os.path.join(a.newest_decks, "make_landslide_decks.py"), landslide_dir],
                           check=True, stdout=subprocess.DEVNULL)
    for name, rel, which, end in todo:
        if wanted and not any(w in name for w in wanted):
            continue
        if which == "newest":
            src = os.path.join(landslide_dir if rel in LANDSLIDES else a.newest_decks, rel)
        else:
            src = os.path.join(a.repo, rel)
        if not os.path.exists(src):
            print(f"public_decks: {rel} not in {a.repo}: skipped", file=sys.stderr)
            continue
        base = os.path.join(os.path.abspath(a.runs), slug(name))
        deck = os.path.join(base, os.path.basename(rel))
        os.makedirs(base, exist_ok=True)
        prepare(src, end, deck)
        if a.finished_only and not os.path.exists(os.path.join(base, "original", "done")):
            results.append({"name": name, "program": which, "pending": True})
            continue
        exe = os.path.abspath({"book": a.book, "current": a.current, "newest": a.newest}[which])
        orig = run_original(exe, deck, os.path.join(base, "original"))
        ours = run_mpm3d(mpm3d, deck, a.threads, os.path.join(base, "mpm3d"), a.reuse)
        by_rules = run_mpm3d(mpm3d, deck, a.threads, os.path.join(base, "mpm3d_rules"), a.reuse,
                             ["--rules", rules_preset(name)])
        r = {"name": name, "program": which}
        if ours["rc"] != 0 or orig["rc"] != 0 or by_rules["rc"] != 0:
            who = "the original" if orig["rc"] != 0 else "mpm3d"
            sub = "original" if orig["rc"] != 0 else "mpm3d" if ours["rc"] != 0 else "mpm3d_rules"
            log = os.path.join(base, sub, "run.log")
            last = open(log, errors="replace").read().strip().splitlines()[-1:] or [""]
            r["refused"] = f"{who}: {last[0].replace(base + os.sep, '')}"
        else:
            stem = os.path.basename(rel)[:-4]
            r["rows"] = rows_of(stem, os.path.join(base, "original"), os.path.join(base, "mpm3d"))
            r["rules_rows"] = rows_of(stem, os.path.join(base, "original"), os.path.join(base, "mpm3d_rules"))
            r["rules_steps"] = by_rules.get("steps")
            orig_rows = compare.read_table(os.path.join(base, "original", compare.ENERGY_FILE))[1]
            r.update(particles=ours.get("particles"), steps=ours.get("steps"), orig_steps=len(orig_rows),
                     wall=ours["wall"], orig_wall=orig["wall"])
        (newest if which == "newest" else results).append(r)
        print(f"public_decks: {name}: " + (r.get("refused") or "max %.3f %%, internal %.3f %%; by the original's "
                                            "rules %.3f %%, %.3f %%" % (verdict(r["rows"])[:2] + verdict(r["rules_rows"])[:2])),
              flush=True)
    when = datetime.datetime.utcnow().strftime("%Y-%m-%d")
    if newest:
        write(a.out, newest_table(newest, when, a.threads), NEWEST_BEGIN, NEWEST_END)
    if results:
        write(a.out, table(results, when, a.threads))
    print(f"public_decks: wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
