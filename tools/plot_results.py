#!/usr/bin/env python3
"""plot_results.py: the energies and curves of mpm3d runs (or of the original MPM3D-F90's) in one PNG.

    tools/plot_results.py RUN_DIR_OR_FILES... [-o out.png] [--momentum]

A RUN_DIR is the folder a run wrote into (`mpm3d --out-dir RUN_DIR DECK`): its
EnergyPlot.dat (time, total, kinetic, internal energy), its NAME_curv.dat (the deck's `curv`
and `curx` columns under their header names) and, for decks with `cont`, ContforcPlot.dat
(time, contact force x, y, z); MomentumPlot.dat too with --momentum. Files may also be named
one by one. Each column gets a panel against time; several runs are drawn in the same
panels, labelled by their folder. The curve file's first two columns (engk1, engi1: the
total kinetic and internal energies again) are left out when the energy file is drawn.

The files are read with the parser of tools/mpm3d_compare.py (installed as mpm3d-compare),
which this script imports from its own folder: Fortran E12.4 numbers, an optional header
line, the rows of one printed time averaged. Needs python3 and matplotlib (imported only
when drawing).

Exit status: 0 written; 1 matplotlib missing; 2 bad input (a missing file or folder, a
folder without result files, a file without rows).
"""
import argparse
import importlib.machinery
import importlib.util
import os
import sys

PROG = "plot_results.py"
EXIT_OK, EXIT_NO_MATPLOTLIB, EXIT_BAD = 0, 1, 2

ENERGY_FILE = "EnergyPlot.dat"
MOMENTUM_FILE = "MomentumPlot.dat"
CONTACT_FILE = "ContforcPlot.dat"
# Headerless files: their columns by position (the energy columns as mpm3d_compare names them).
DEFAULT_NAMES = {
    MOMENTUM_FILE: ["Time", "momentum x", "momentum y", "momentum z"],
    CONTACT_FILE: ["Time", "contact force x", "contact force y", "contact force z"],
}
PANEL_TITLES = {ENERGY_FILE: "energy", MOMENTUM_FILE: "momentum", CONTACT_FILE: "contact force"}
TOTALS_IN_CURVES = ("engk1", "engi1")


class BadInput(Exception):
    """A path we cannot plot; the message names it (exit status 2)."""


def load_compare_module():
    """tools/mpm3d_compare.py, or the installed copy `mpm3d-compare`, from this script's folder."""
    here = os.path.dirname(os.path.abspath(__file__))
    for name in ("mpm3d_compare.py", "mpm3d-compare"):
        path = os.path.join(here, name)
        if os.path.isfile(path):
            loader = importlib.machinery.SourceFileLoader("mpm3d_compare", path)
            spec = importlib.util.spec_from_loader("mpm3d_compare", loader)
            module = importlib.util.module_from_spec(spec)
            loader.exec_module(module)
            return module
    raise BadInput("cannot find mpm3d_compare.py (or mpm3d-compare) beside %s: its file "
                   "parser is needed" % os.path.abspath(__file__))


def kind_of(path):
    """Which result file a path is, by its name: the energy, momentum or contact file, a
    curve file (*_curv.dat), or any other time-history table (first column the time)."""
    base = os.path.basename(path)
    if base in (ENERGY_FILE, MOMENTUM_FILE, CONTACT_FILE):
        return base
    return "curves" if base.endswith("_curv.dat") else "table"


def files_of_dir(run_dir, momentum):
    """The result files of one run folder, in plotting order."""
    found = []
    for name in (ENERGY_FILE, MOMENTUM_FILE if momentum else None, CONTACT_FILE):
        if name and os.path.isfile(os.path.join(run_dir, name)):
            found.append(os.path.join(run_dir, name))
    found += sorted(os.path.join(run_dir, f) for f in os.listdir(run_dir) if f.endswith("_curv.dat"))
    if not found:
        raise BadInput("%s: no %s and no *_curv.dat in this folder (is it a run's --out-dir?)"
                       % (run_dir, ENERGY_FILE))
    return found


def collect(paths, momentum):
    """[(label, [file, ...])]: one entry per run folder, or per folder of the files named."""
    runs, by_dir = [], {}
    for path in paths:
        if os.path.isdir(path):
            runs.append((path.rstrip("/") or path, files_of_dir(path, momentum)))
        elif os.path.isfile(path):
            folder = os.path.dirname(path) or "."
            if folder not in by_dir:
                by_dir[folder] = (folder, [])
                runs.append(by_dir[folder])
            by_dir[folder][1].append(path)
        else:
            raise BadInput("%s: no such file or folder" % path)
    return runs


def read_run(compare, files):
    """[(panel key, panel title, times, values)] of one run's files."""
    series = []
    has_energy = any(kind_of(f) == ENERGY_FILE for f in files)
    for path in files:
        kind = kind_of(path)
        default = compare.ENERGY_COLUMNS if kind == ENERGY_FILE else DEFAULT_NAMES.get(kind)
        try:
            names, times, columns = compare.read_series(path, default)
        except OSError as e:
            raise BadInput("%s: %s" % (path, e.strerror or e))
        if not times:
            raise BadInput("%s: no rows to plot" % path)
        skip = set(TOTALS_IN_CURVES) if kind == "curves" and has_energy else set()
        for k, name in enumerate(names[1:], start=1):
            if k <= 2 and name in skip:
                continue
            if kind in PANEL_TITLES:  # all columns of the file in one panel
                key, title = kind, PANEL_TITLES[kind]
            else:  # a panel per curve column: each has its own units
                key, title = "column " + name, name
            series.append((key, title, name, times, columns[name]))
    return series


def plot(runs, out_path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("%s: drawing needs matplotlib, which %s cannot import (Debian: apt-get install "
              "python3-matplotlib; or run this script with a python3 that has it)"
              % (PROG, sys.executable), file=sys.stderr)
        return EXIT_NO_MATPLOTLIB
    panels = {}  # key -> (title, [(label, times, values)])
    for label, series in runs:
        for key, title, name, times, values in series:
            line_label = name if key in PANEL_TITLES else None
            if len(runs) > 1:
                line_label = label if line_label is None else "%s: %s" % (label, name)
            panels.setdefault(key, (title, []))[1].append((line_label, times, values))
    ncol = min(3, len(panels))
    nrow = (len(panels) + ncol - 1) // ncol
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.8 * ncol, 3.4 * nrow), squeeze=False)
    for ax, (title, lines) in zip(axes.flat, panels.values()):
        for line_label, times, values in lines:
            ax.plot(times, values, label=line_label, linewidth=1.2)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("time")
        ax.grid(True, alpha=0.3)
        ax.ticklabel_format(axis="both", style="sci", scilimits=(-3, 4))
        if any(l[0] for l in lines):
            ax.legend(fontsize=7)
    for ax in list(axes.flat)[len(panels):]:
        ax.axis("off")
    fig.suptitle(", ".join(label for label, _ in runs), fontsize=10)
    fig.tight_layout()
    fig.savefig(out_path, dpi=100)
    plt.close(fig)
    print("%s: wrote %s (%d panels)" % (PROG, out_path, len(panels)))
    return EXIT_OK


def main(argv=None):
    p = argparse.ArgumentParser(
        prog=PROG, description=__doc__.split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("paths", nargs="+", metavar="RUN_DIR_OR_FILE")
    p.add_argument("-o", "--output", default="results.png",
                   help="the PNG to write (default: results.png in the current folder)")
    p.add_argument("--momentum", action="store_true",
                   help="also draw MomentumPlot.dat of each run folder")
    args = p.parse_args(argv)
    try:
        compare = load_compare_module()
        runs = [(label, read_run(compare, files)) for label, files in collect(args.paths, args.momentum)]
        out_dir = os.path.dirname(os.path.abspath(args.output))
        if not os.path.isdir(out_dir):
            raise BadInput("%s: the folder %s does not exist" % (args.output, out_dir))
    except BadInput as e:
        print("%s: %s" % (PROG, e), file=sys.stderr)
        return EXIT_BAD
    return plot(runs, args.output)


if __name__ == "__main__":
    sys.exit(main())
