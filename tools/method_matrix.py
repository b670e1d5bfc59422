#!/usr/bin/env python3
"""Every transfer method x material family, against the current MPM3D-F90.

usage:
  tools/method_matrix.py write [--dir DIR]
  tools/method_matrix.py run BUILD_DIR --original EXE [--only NAME ...] [--set CARD ...]
                         [--variant flush|tl-coarse] [--mpm3d EXE] [--keep DIR] [--no-doc]

write: one small deck per runnable pair, DIR/<material>_<method>.mpm (default
inputs/methods/). The decks are ours: a small scene per material family, the same scene for
every method of that family (only the method's keyword differs; the TLmp column has its cell
halved, see scene_neoh), each a current-version deck (it holds `smoo`, which only adds an
output, or the method's own current keyword), so that mpm3d applies the current program's
rules.

run: writes the decks, runs BUILD_DIR/cxx/mpm3d-compare --original EXE --threads 2 on each,
judges each deck by the criterion below, checks that mpm3d refuses the pairs it does not run
with a message naming both keywords, and writes the table and its notes into
docs/DECK_FORMAT.md between the METHOD_MATRIX markers. --only restricts the run to some
decks (names as <material>_<method>); --set CARD adds a header card to every deck, or
replaces the card of the same keyword (an experiment: e.g. --set 'bulk 0 0'); --variant
writes another layout (flush: the walls touch the bodies; tl-coarse: the TLmp column in the
other neoh decks' cells); --mpm3d runs another mpm3d (a test build). These print the
verdicts and leave the document alone, as does --no-doc.

Criterion: the kinetic and total energy and every curve within 1 % of the column's largest
magnitude over the original's run (largest and final difference), the internal energy
within 5 %.
"""
import argparse
import datetime
import os
import re
import subprocess
import sys
import tempfile
import textwrap

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK_DIR = os.path.join(ROOT, "inputs", "methods")
DOC = os.path.join(ROOT, "docs", "DECK_FORMAT.md")
BEGIN, END = "<!-- METHOD_MATRIX begin -->", "<!-- METHOD_MATRIX end -->"
METHODS = ["linear", "gimp", "bimp", "sgmp", "TLmp"]
KEYWORD = {"linear": None, "gimp": "gimp", "bimp": "bimp", "sgmp": "sgmp", "TLmp": "TLmp"}
TOLERANCE = 1.0          # % of a column's largest magnitude
INTERNAL_TOLERANCE = 5.0  # the internal energy's


def bloc_index(i, j, k, nx, ny):
    """1-based number of the particle (i, j, k) of a `part bloc` card in a current-version
    deck (x fastest, then y, then z)."""
    return 1 + i + nx * (j + ny * k)


# ---------------------------------------------------------------------------- the scenes
# Each scene: a title, comment lines, header cards (box, cell, times, faces, curves), the
# material cards and the body cards. With sgmp the current program mishandles particles
# in the outer half of a boundary cell (next to a lower face: docs/DECK_FORMAT.md, sgmp;
# next to an upper face its auxiliary-cell number overflows: note of the table), so every
# body starts half a cell off the walls, which are upper faces (gravity points at them),
# with empty cells between it and the lower faces.

def scene_j2eos(method):
    nx, ny, nz = 6, 6, 8
    corner = bloc_index(nx - 1, ny - 1, nz - 1, nx, ny)
    return dict(
        title="copper block striking a rigid wall (sjc + Mie-Gruneisen)",
        comments=["Units mm g N ms MPa. A copper block 3 x 3 x 4 mm (6 x 6 x 8 particles, dp 0.5,",
                  "cell 1) moving at 200 m/s along +z strikes the symmetric face z = 5 (0.5 mm",
                  "= half a cell away): simplified Johnson-Cook with the Mie-Gruneisen EOS (the copper of the",
                  "public Taylor bar). Two empty cells below and beside the block."],
        box=((-2.0, 5.0), (-2.0, 5.0), (-2.0, 5.0)), h=1.0, dtscale=0.5, endtime=0.03,
        fixed="0 0 0 0 0 2",
        curves=["disx %d" % corner, "disz %d" % corner],
        material=["   1   sjc   8.93d-3  117.0d3  0.35  157.0  425.0  1.0  0.0  1d-3",
                  "seos 1 2 3940 1.49 1.96 0"],
        bodies=["part bloc 1 1 8.93d-3 0.5  0.0 0.0 0.5  %d %d %d" % (nx, ny, nz)],
        after=["velo", "body 1 0.0 0.0 200.0", "endv"])


def scene_neoh(method):
    nx, ny, nz = 4, 4, 20
    tip = bloc_index(2, 2, 0, nx, ny)
    if method == "TLmp":
        # The current program's trilinear TLmp never computes the particles' natural
        # coordinates in their cells (they stay zero): every particle takes its cell
        # centre's shape functions. One particle per cell, at its centre, is where that
        # is right (note of the table).
        s = scene_neoh("linear")
        s.update(comments=["Units m kg N s Pa. A soft column 0.2 x 0.2 x 1 m (4 x 4 x 20 particles, dp 0.05)",
                           "in cells of 0.05, one particle per cell at its centre, hangs under gravity",
                           "from the fixed face z = 1 (its top), started sideways at 1 m/s. neoh E 1 MPa,",
                           "nu 0.3. The column of the other neoh decks, with the cell halved (see",
                           "tools/method_matrix.py: the current program's TLmp)."],
                 box=((-0.5, 0.7), (-0.3, 0.5), (-0.35, 1.0)), h=0.05)
        return s
    return dict(
        title="neo-Hookean column hanging from the ceiling, swinging",
        comments=["Units m kg N s Pa. A soft column 0.2 x 0.2 x 1 m (4 x 4 x 20 particles, dp 0.05,",
                  "cell 0.1) hangs under gravity from the fixed face z = 1.05 (half a cell above",
                  "its top), started sideways at 1 m/s: it swings about a tenth of its length.",
                  "neoh E 1 MPa, nu 0.3."],
        box=((-0.5, 0.7), (-0.3, 0.5), (-0.35, 1.05)), h=0.1, dtscale=0.8, endtime=1.0,
        fixed="0 0 0 0 0 1",
        curves=["disx %d" % tip, "disz %d" % tip],
        material=["   1   neoh  1000  1.0e6  0.3"],
        bodies=["part bloc 1 1 1000 0.05  0.0 0.0 0.0  %d %d %d" % (nx, ny, nz)],
        after=["velo", "body 1 1.0 0.0 0.0", "endv", "load", "grav 1 0.0 0.0 -9.81", "endl"])


def scene_null(method):
    nx, ny, nz = 6, 6, 12
    front = bloc_index(0, ny - 1, nz - 1, nx, ny)
    top = bloc_index(nx - 1, ny - 1, 0, nx, ny)
    return dict(
        title="water column collapsing in a corner (null + weakly compressible EOS)",
        comments=["Units m kg N s Pa. A water column 0.3 x 0.3 x 0.6 m (6 x 6 x 12 particles, dp",
                  "0.05, cell 0.1) in the corner of the walls x = 0.35 and y = 0.35 collapses onto",
                  "the floor z = 0.65 (all three symmetric faces, each half a cell off the water).",
                  "The scene is upside down (gravity",
                  "along +z) so that the water reaches no lower box face. The current version's",
                  "fluid: density, bulk modulus 2e6 Pa (c = 44.7 m/s), viscosity 1e-3 Pa s."],
        box=((-1.05, 0.35), (-1.05, 0.35), (-0.25, 0.65)), h=0.1, dtscale=0.8, endtime=0.3,
        fixed="0 2 0 2 0 2",
        curves=["disx %d" % front, "disz %d" % top],
        material=["   1   null  1000  2.0e6  0.001", "seos 1 4 44.72"],
        bodies=["part bloc 1 1 1000 0.05  0.0 0.0 0.0  %d %d %d" % (nx, ny, nz)],
        after=["load", "grav 1 0.0 0.0 9.81", "endl"])


def scene_hiex(method):
    nx, ny, nz = 16, 4, 4
    mid = bloc_index(nx // 2, 1, 1, nx, ny)
    side = bloc_index(nx // 2, 0, 0, nx, ny)
    return dict(
        title="TNT column lit at one end against a rigid wall (hiex + JWL)",
        comments=["Units mm g N ms MPa. A TNT column 4 x 1 x 1 mm (16 x 4 x 4 particles, dp 0.25,",
                  "cell 0.5) lit at the centre of its end x = 0 (programmed burn, JWL with the",
                  "parameters of the public one-dimensional TNT deck); its other end against the",
                  "symmetric face x = 4.25 (half a cell on). The products expand freely sideways and backwards into",
                  "four empty millimetres."],
        box=((-3.75, 4.25), (-4.0, 5.0), (-4.0, 5.0)), h=0.5, dtscale=0.1, endtime=1.2e-3,
        fixed="0 2 0 0 0 0",
        curves=["pres %d" % mid, "disy %d" % side],
        material=["   1   hiex  1.63d-3  6930",
                  "seos 1 3 3.712d5 3.21d3 4.15 0.95 0.3 6993",
                  "deto 0.0 0.5 0.5"],
        bodies=["part bloc 1 1 1.63d-3 0.25  0.0 0.0 0.0  %d %d %d" % (nx, ny, nz)],
        after=[])


def scene_dpm(method):
    nx, ny, nz = 6, 6, 12
    toe = bloc_index(0, ny - 1, nz - 1, nx, ny)
    top = bloc_index(nx - 1, ny - 1, 0, nx, ny)
    return dict(
        title="soil column collapsing in a corner (Drucker-Prager)",
        comments=["Units m kg N s Pa. A soil column 3 x 3 x 6 m (6 x 6 x 12 particles, dp 0.5,",
                  "cell 1) in the corner of the smooth walls x = 3.5 and y = 3.5 slumps onto the",
                  "rough floor z = 6.5 (fixed), each half a cell off the soil; upside down (gravity along +z) so that the soil reaches no",
                  "lower box face. dpm: E 10 MPa, nu 0.3, friction angle 30 degrees (q_phi",
                  "0.48038), cohesion 2 kPa (k_phi 1664), no dilatancy, tension cut-off 1 kPa."],
        box=((-9.5, 3.5), (-9.5, 3.5), (-1.5, 6.5)), h=1.0, dtscale=0.5, endtime=1.5,
        fixed="0 2 0 2 0 1",
        curves=["disx %d" % toe, "disz %d" % top],
        material=["   1   dpm  2000  1.0e7  0.3  0.48038  1664.0  0.0  1000.0"],
        bodies=["part bloc 1 1 2000 0.5  0.0 0.0 0.0  %d %d %d" % (nx, ny, nz)],
        after=["load", "grav 1 0.0 0.0 9.81", "endl"])


SCENES = {"j2eos": (scene_j2eos, "sjc"), "neoh": (scene_neoh, "neoh"),
          "null": (scene_null, "null"), "hiex": (scene_hiex, "hiex"),
          "dpm": (scene_dpm, "dpm")}
MATERIAL_LABEL = {"j2eos": "J2 / Johnson-Cook + EOS (`sjc`, `seos 2`)",
                  "neoh": "neo-Hookean (`neoh`)",
                  "null": "fluid (`null rho K mu`, `seos 4`)",
                  "hiex": "explosive (`hiex`, `seos 3`, `deto`)",
                  "dpm": "Drucker-Prager (`dpm`)"}


def runnable(material, method):
    """TLmp runs with neoh materials only (mpm3d refuses the rest, naming both)."""
    return method != "TLmp" or material == "neoh"


def particle_count(scene):
    n = 0
    for card in scene["bodies"]:
        w = card.split()
        n += int(w[-1]) * int(w[-2]) * int(w[-3])
    return n


VARIANTS = ("flush", "tl-coarse")


def deck_text(material, method, cards=(), variant=None):
    """The deck of one pair; cards: extra header cards (each replaces a card of the same
    keyword, else joins the header). Variants (experiments): 'flush' moves the box half a
    cell down along every axis with a wall at its upper face, so that the wall touches the
    body; 'tl-coarse' gives the TLmp deck the other neoh decks' layout."""
    s = SCENES[material][0]("linear" if variant == "tl-coarse" else method)
    if variant == "flush" and not (material == "neoh" and method == "TLmp"):
        codes = s["fixed"].split()
        s["box"] = tuple((lo - s["h"] / 2, hi - s["h"] / 2) if codes[2 * a + 1] != "0" else (lo, hi)
                         for a, (lo, hi) in enumerate(s["box"]))
    (x0, x1), (y0, y1), (z0, z1) = s["box"]
    kw = KEYWORD[method]
    head = ["mpm3d *** %s, %s" % (s["title"], kw or "linear MPM"),
            "! Our own deck (MPM3D-CXX), written by tools/method_matrix.py: material family %s," % material,
            "! transfer method %s; `smoo` (an output only) makes it a current-version deck." % (kw or "linear")]
    head += ["! " + c for c in textwrap.wrap(" ".join(s["comments"]), 88)]
    cards_out = ["nbco 1", "nbbo %d" % len(s["bodies"]), "nbmp %d" % particle_count(s), "nmat 1",
                 "spx %g %g" % (x0, x1), "spy %g %g" % (y0, y1), "spz %g %g" % (z0, z1),
                 "dcell %g" % s["h"], "dtscale %g" % s["dtscale"], "endtime %g" % s["endtime"],
                 "outtime %g" % (s["endtime"] / 5), "rpttime %g" % (s["endtime"] / 10),
                 "musl on", "jaum on", "smoo"]
    if kw:
        cards_out.append(kw)
    cards_out += ["curv " + c for c in s["curves"]]
    for extra in cards:
        key = extra.split()[0][:4].lower()
        at = [k for k, c in enumerate(cards_out) if c.split()[0][:4].lower() == key]
        if at:
            cards_out[at[0]] = extra
        else:
            cards_out.append(extra)
    body = ["!     x0 xn y0 yn z0 zn", "fixed " + s["fixed"], "material"] + s["material"]
    body += s["bodies"] + s["after"] + ["endi"]
    return "\n".join(head + cards_out + body) + "\n"


def pairs():
    """(material, method) of every pair, runnable or not, in table order."""
    return [(m, k) for m in SCENES for k in METHODS]


def write_decks(directory, cards=(), only=None, variant=None):
    """Write the runnable pairs' decks; their paths."""
    os.makedirs(directory, exist_ok=True)
    paths = []
    for material, method in pairs():
        name = "%s_%s" % (material, method)
        if not runnable(material, method) or (only and name not in only):
            continue
        path = os.path.join(directory, name + ".mpm")
        with open(path, "w") as f:
            f.write(deck_text(material, method, cards, variant))
        paths.append(path)
    return paths


# ---------------------------------------------------------------------------- judging

ROW = re.compile(r"^  (\S+)\s{2,}(\S+)\s{2,}(\S+)\s{2,}(\S+)\s{2,}(.*)$")


def parse_compare(text):
    """[(file, column, max diff, final diff)] of mpm3d-compare's table (compared rows only)."""
    rows = []
    for line in text.splitlines():
        m = ROW.match(line)
        if not m or m.group(1) == "file":
            continue
        try:
            rows.append((m.group(1), m.group(2), float(m.group(3)), float(m.group(4))))
        except ValueError:
            continue  # a column not compared ('-')
    return rows


def limit(column):
    """The internal energy (EnergyPlot's column, the curve file's engi1) gets 5 %."""
    return INTERNAL_TOLERANCE if column.startswith(("internal", "engi")) else TOLERANCE


def judge(rows):
    """(agrees, worst (column, %) relative to its limit, [(column, %) beyond their limits])."""
    beyond, worst, worst_ratio = [], None, -1.0
    for _, column, mx, final in rows:
        d = max(mx, final)
        if d > limit(column):
            beyond.append((column, d))
        if d / limit(column) > worst_ratio:
            worst, worst_ratio = (column, d), d / limit(column)
    return not beyond and bool(rows), worst, beyond


def compare(build, original, deck, keep, mpm3d=None, rule_args=()):
    """mpm3d-compare's exit status and output for one deck (rule_args: mpm3d's --rules)."""
    argv = [os.path.join(build, "cxx", "mpm3d-compare"), "--original", original,
            "--mpm3d", mpm3d or os.path.join(build, "cxx", "mpm3d"), "--threads", "2"] + list(rule_args) + [deck]
    if keep:
        argv[1:1] = ["--keep", keep]
    # Passive OpenMP waits: the figures are the same bits, and a busy machine does not make
    # two spinning threads crawl.
    env = dict(os.environ, OMP_WAIT_POLICY=os.environ.get("OMP_WAIT_POLICY", "PASSIVE"))
    p = subprocess.run(argv, capture_output=True, text=True, stdin=subprocess.DEVNULL, env=env)
    return p.returncode, p.stdout + p.stderr


def refusal(build, original, material, work):
    """mpm3d's exit status and one-line error on the TLmp deck of a material it refuses
    with TLmp, and the line of the current program's 'Stop' on the same deck."""
    name = "%s_TLmp.mpm" % material
    here = os.path.join(work, "refused_" + material)
    os.makedirs(here)
    with open(os.path.join(here, name), "w") as f:
        f.write(deck_text(material, "TLmp"))
    p = subprocess.run([os.path.join(build, "cxx", "mpm3d"), "--quiet", "--no-output", name],
                       capture_output=True, text=True, stdin=subprocess.DEVNULL, cwd=here)
    line = (p.stderr.strip().splitlines() or ["(no message, exit status %d)" % p.returncode])[0]
    try:
        o = subprocess.run([original, name], capture_output=True, text=True,
                           stdin=subprocess.DEVNULL, cwd=here, timeout=120)
        stops = [l.strip() for l in (o.stdout + o.stderr).splitlines() if "Stop" in l]
        theirs = stops[0] if stops else "(runs: exit status %d)" % o.returncode
    except subprocess.TimeoutExpired:
        theirs = "(runs)"
    return p.returncode, line, theirs


# ---------------------------------------------------------------------------- the document

# Why a pair differs, or what its layout avoids, with the experiments that show it (the
# figures of the runs made when the notes were written; 'run' prints them again, the test
# builds excepted).
NOTES = {
    "layout": (
        "Layout. Every body starts half a cell off its walls (upper box faces; gravity points "
        "at them) and at least one empty cell off the lower faces, because the current "
        "program's sgmp mishandles particles in the outer half of a boundary cell. Next to a "
        "lower face it truncates toward the wrong auxiliary cell (the sgmp row above). Next "
        "to an upper face the number of the auxiliary cell, `int((x - x0 - h/2)/h) + 1`, is "
        "one past the last one: along x or y it names a cell of the next row (the particle's "
        "mass, momentum and stress go to the other side of the grid), along z it is out of "
        "range and the particle is skipped (no mass, no force, it never moves). With the "
        "walls moved half a cell onto the bodies (`run --variant flush`) the current "
        "program's sgmp runs of the fluid, explosive and Drucker-Prager decks end in a "
        "segmentation fault (the fluid after negative volumes from about step 40), and the "
        "copper block's, with `bulk 0 0` in both programs, differs by 29 % in kinetic and "
        "44 % in internal energy (its corner particle at the wall never moves there); the "
        "hanging neo-Hookean column agrees all the same (the particles skipped are the "
        "clamped ones). The other methods are not affected (copper, flush, `bulk 0 0`: "
        "worst column 0.07 %)."),
    "bulk": (
        "Artificial bulk viscosity. These decks have no `bulk` card: both programs apply "
        "their default 1.5, 0.06, by different rules. With `bulk 0 0` in both (`run --set "
        "'bulk 0 0'`) every copper pair and the linear fluid pair agree (worst columns "
        "0.011-0.024 % and 0.068 %). The current program switches q on where the particle's "
        "mean stress is compressive (for `sjc` and `null` the previous step's, read before "
        "the EOS; for `dpm` the updated one), we where the volume shrinks; and its linear "
        "term takes the "
        "particle's sound speed, which it sets for `elas`, `neoh` and `null` only, so that "
        "the term vanishes for `sjc` and `dpm`; it also counts q's work with the new q over "
        "the step, we with the mean of the old and new q. These are the rules `bulk_switch`, "
        "`bulk_linear` and `bulk_work` (docs/FROM_MPM3D_F90.md, \"The rules\"); under "
        "`--rules original` every pair agrees."),
    "burn": (
        "Programmed burn. We ramp the burn fraction `F = (t - t_l) D / (1.5 h)` over one and "
        "a half cells (docs/EXPLOSIVES.md); the current program switches the whole EOS "
        "pressure on at once when `t > t_l` (F is 0 or 1), and gives `hiex` no bulk "
        "viscosity (its JWL adds the particle's q, which only the other materials' branches "
        "compute). `bulk 0 0` "
        "alone changes little (kinetic energy still 10-11.5 % apart; the pressure curve at "
        "mid-column, which the ramp delays, 97-99 %). Cause: the rules `burn` and "
        "`bulk_linear`; under `--rules original` every method agrees to the printed digits."),
    "dp": (
        "Drucker-Prager near the tension cut-off. The current program picks the shear "
        "return whenever the trial stress lies above the corner line `h > 0`, and leaves the "
        "mean stress where that return puts it, above the cut-off too (with `q_psi = 0` at "
        "its trial value); we take the tension return there. And its tension return sets "
        "`sm = sigma_t` and keeps the deviator, where ours caps `tau` at `tau_P` "
        "(Model notes, `dpm`, above). `bulk 0 0` alone changes little (kinetic energy "
        "24-52 % apart). Cause: the two branches, the rule `dp_return` (with the bulk "
        "viscosity's rules: under `--rules original` every method agrees to the printed "
        "digits). The current program's first branch leaves stresses outside its own tension "
        "cut-off, so we keep our returns, which end on the yield surface."),
    "tl": (
        "TLmp. The current program's trilinear TLmp never computes the particles' natural "
        "coordinates in their reference cells (only its sgmp branch does; they stay zero, as "
        "a print in a copy of its source built here shows): every particle takes the shape "
        "functions and gradients of its cell's centre. We take them at the reference "
        "positions. This deck therefore has one particle per cell, at its centre, where "
        "the two agree (kinetic energy and the tip's displacement within 0.003 %; "
        "the internal energy within 0.8 %, the current program weighing the work of P on "
        "dF by the current volume, we by V0). The column of the other neoh decks, two "
        "particles per cell (`run --variant tl-coarse`): kinetic energy 32 %, internal "
        "energy 42 %, the tip's vertical displacement 44 % apart. The rule `tl_shape` "
        "(`centre`: the cell's centre and the current volume) gives the current program's "
        "numbers; we keep the shape functions at the particles' own reference positions."),
}
# The notes of each deck, in order.
NOTE_OF = {"j2eos_linear": ["bulk"], "j2eos_gimp": ["bulk"], "j2eos_bimp": ["bulk"],
           "j2eos_sgmp": ["layout", "bulk"], "neoh_sgmp": ["layout"], "neoh_TLmp": ["tl"],
           "null_linear": ["bulk"], "null_sgmp": ["layout"],
           "hiex_linear": ["burn"], "hiex_gimp": ["burn"], "hiex_bimp": ["burn"],
           "hiex_sgmp": ["layout", "burn"],
           "dpm_linear": ["dp"], "dpm_gimp": ["dp"], "dpm_bimp": ["dp"], "dpm_sgmp": ["layout", "dp"]}
REFUSED_NOTE = ("The refused pairs: the current program reads these decks and stops at its "
                "first step (%s).")


def wrap(text, indent=""):
    """A paragraph of at most 92 columns; a number keeps its ' %'."""
    return textwrap.fill(text.replace(" %", "\0%"), 92, subsequent_indent=indent).replace("\0", " ")


def cell(result, by_rules=None):
    """The table's cell: the verdict by our rules, then by the original's (--rules original)."""
    text = verdict_text(result)
    if by_rules is not None and result[0] in ("agrees", "differs"):
        kind = by_rules[0]
        if kind == "agrees":
            text += "; original's rules: agrees (worst column %s %.2f %%)" % by_rules[1]
        elif kind == "differs":
            worst = max(by_rules[1], key=lambda b: b[1] / limit(b[0]))
            text += "; original's rules: differs (worst %s %.1f %%)" % worst
    return text


def verdict_text(result):
    kind = result[0]
    if kind in ("agrees", "differs"):
        notes = result[2]
        ref = "note%s %s" % ("s" if len(notes) > 1 else "", ", ".join(map(str, notes))) if notes else ""
    if kind == "agrees":
        column, d = result[1]
        return "agrees (worst column %s %.2f %%)%s" % (column, d, "; " + ref if ref else "")
    if kind == "differs":
        worst = max(result[1], key=lambda b: b[1] / limit(b[0]))
        return "differs: %s (worst %s %.1f %%)" % (ref, worst[0], worst[1])
    if kind == "refused":
        return "refused: `%s`" % result[1]
    return "does not run: note %d" % result[2][0]


def document(results, notes, results_rules=None):
    when = datetime.datetime.utcnow().strftime("%Y-%m-%d")
    intro = ("Generated by `tools/method_matrix.py run BUILD_DIR --original PATH` on %s (mpm3d "
             "on 2 threads, the current MPM3D-F90 serial, both on this machine). Criterion: the "
             "kinetic and total energy and every curve within %g %% of the column's largest "
             "magnitude over the current program's run (largest and final difference), the "
             "internal energy within %g %%; the worst column named is the one nearest its "
             "limit (curves: `curv` variable and particle number). Each cell gives the verdict by "
             "our rules, then by the original's (`mpm3d --rules original`, docs/FROM_MPM3D_F90.md "
             "\"The rules\")."
             % (when, TOLERANCE, INTERNAL_TOLERANCE))
    out = [BEGIN, "", wrap(intro), "",
           "| material | " + " | ".join(METHODS) + " |",
           "|---" * (len(METHODS) + 1) + "|"]
    for material in SCENES:
        out.append("| %s | " % MATERIAL_LABEL[material] +
                   " | ".join(cell(results[(material, m)], (results_rules or {}).get((material, m)))
                              for m in METHODS) + " |")
    out.append("")
    for k, text in enumerate(notes, start=1):
        out.append(wrap("%d. %s" % (k, text), "   "))
    out += ["", END]
    return "\n".join(out)


def write_doc(block):
    with open(DOC) as f:
        text = f.read()
    if BEGIN not in text or END not in text:
        raise SystemExit("method_matrix: %s lacks the METHOD_MATRIX markers" % DOC)
    head, rest = text.split(BEGIN, 1)
    tail = rest.split(END, 1)[1]
    with open(DOC, "w") as f:
        f.write(head + block + tail)


# ---------------------------------------------------------------------------- main

def run(args):
    build = os.path.abspath(args.build)
    original = os.path.abspath(args.original)
    experiment = bool(args.set or args.only or args.mpm3d or args.variant)
    results, notes, refused_by_original, note_number = {}, [NOTES["layout"]], [], {"layout": 1}
    results_rules = {}
    with tempfile.TemporaryDirectory() as work:
        directory = work if (args.set or args.variant) else DECK_DIR
        decks = write_decks(directory, args.set, args.only, args.variant)
        for deck in decks:
            name = os.path.basename(deck)[:-4]
            material, method = name.split("_", 1)
            rc, text = compare(build, original, deck, args.keep, args.mpm3d)
            print(text, end="")
            rows = parse_compare(text)
            if rc == 2 or not rows:
                why = [l for l in text.splitlines() if l.startswith("mpm3d-compare:")]
                notes.append("%s does not run: %s" % (name, why[0].split(" its last")[0] if why
                                                         else "exit status %d" % rc))
                print("%s: DOES NOT RUN (%s)\n" % (name, notes[-1].split(": ", 1)[1]))
                results[(material, method)] = ("error", None, [len(notes)])
                continue
            agrees, worst, beyond = judge(rows)
            print("%s: %s (worst %s %.3f %%)%s\n" % (name, "agrees" if agrees else "DIFFERS",
                                                   worst[0], worst[1], "" if agrees else
                                                   ", beyond: " + ", ".join("%s %.2f %%" % b for b in beyond)))
            for key in NOTE_OF.get(name, []):
                if key not in note_number:
                    notes.append(NOTES[key])
                    note_number[key] = len(notes)
            numbers = [note_number[k] for k in NOTE_OF.get(name, [])]
            if not agrees and not numbers:
                notes.append("%s: not explained." % name)
                numbers = [len(notes)]
            results[(material, method)] = ("agrees" if agrees else "differs", worst if agrees
                                           else beyond, numbers)
            # The same deck by the original program's rules (mpm3d --rules original).
            rc, text = compare(build, original, deck, None, args.mpm3d, ["--rules", "original"])
            rows = parse_compare(text)
            if rows:
                agrees, worst, beyond = judge(rows)
                results_rules[(material, method)] = ("agrees" if agrees else "differs",
                                                     worst if agrees else beyond, [])
                print("%s by the original's rules: %s (worst %s %.3f %%)\n"
                      % (name, "agrees" if agrees else "DIFFERS", worst[0], worst[1]))
        for material, method in pairs():
            if runnable(material, method):
                continue
            rc, line, theirs = refusal(build, original, material, work)
            named = rc == 1 and "TLmp" in line and SCENES[material][1] in line
            print("%s_%s: exit status %d, %s%s\n  the current program: %s"
                  % (material, method, rc, line, "" if named else "  <- NOT A REFUSAL NAMING BOTH",
                     theirs))
            refused_by_original.append(theirs)
            results[(material, method)] = ("refused", line if named else
                                           "(not a refusal naming both) " + line)
        if refused_by_original:
            # One message with the material's type number in it: show it once, with N.
            types = [m.group(1) for m in (re.search(r"material type +(\d+)", t) for t in refused_by_original) if m]
            shown = sorted(set(re.sub(r"material type +\d+", "material type N", t) for t in refused_by_original))
            notes.append(REFUSED_NOTE % ("; ".join("`%s`" % t for t in shown) +
                                         (" with N = %s" % ", ".join(types) if types else "")))
    if experiment or args.no_doc:
        return 0
    write_doc(document(results, notes, results_rules))
    print("method_matrix: wrote the table into %s" % DOC)
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="mode", required=True)
    w = sub.add_parser("write", help="write the decks")
    w.add_argument("--dir", default=DECK_DIR)
    r = sub.add_parser("run", help="write, compare with the original, update the document")
    r.add_argument("build", help="the build directory (holds cxx/mpm3d and cxx/mpm3d-compare)")
    r.add_argument("--original", required=True, help="the current MPM3D-F90 program")
    r.add_argument("--only", nargs="+", metavar="NAME", help="only these decks (<material>_<method>)")
    r.add_argument("--set", nargs="+", metavar="CARD", default=[],
                   help="add or replace a header card in every deck (an experiment)")
    r.add_argument("--mpm3d", metavar="EXE", help="another mpm3d (a test build; an experiment)")
    r.add_argument("--variant", choices=VARIANTS, help="another deck layout (an experiment)")
    r.add_argument("--keep", metavar="DIR", help="keep both programs' runs (mpm3d-compare --keep)")
    r.add_argument("--no-doc", action="store_true", help="leave docs/DECK_FORMAT.md alone")
    a = ap.parse_args()
    if a.mode == "write":
        for p in write_decks(a.dir):
            print(os.path.relpath(p))
        return 0
    return run(a)


if __name__ == "__main__":
    sys.exit(main())
