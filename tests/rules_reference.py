#!/usr/bin/env python3
"""A deck of ours against the original program's own output for it, kept as data in
tests/reference/rules/STEM/ (EnergyPlot.dat and STEM_curv.dat, written once by the public
program built outside this repository; its README says which program).

usage: rules_reference.py MPM3D DECK REFDIR [--beyond] [MPM3D OPTIONS...]

Runs `mpm3d OPTIONS DECK` (e.g. --rules original) in a temporary directory and compares its
energy and curve files with REFDIR's, as mpm3d-compare does (tools/mpm3d_compare.py): the
largest difference over the run in % of the column's largest magnitude in the original's
run. Within: kinetic and total energy and every curve within 1 %, internal energy (and
the internal-energy curves engi*) within 5 %. Exit 0 when every column is within; with
--beyond, exit 0 when some column is beyond instead (the run under our own rules, to show
that the rule is what brings the agreement). Exit 2 on a missing or empty file or a failed run.
"""
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
import mpm3d_compare as compare  # noqa: E402


def bound(column):
    return 5.0 if column == "internal" or column.startswith("engi") else 1.0


def main(argv):
    if len(argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    mpm3d, deck, ref = os.path.abspath(argv[1]), argv[2], argv[3]
    rest = argv[4:]
    beyond_wanted = bool(rest) and rest[0] == "--beyond"
    if beyond_wanted:
        rest = rest[1:]
    stem = os.path.splitext(os.path.basename(deck))[0]
    for path in (mpm3d, deck, os.path.join(ref, compare.ENERGY_FILE)):
        if not os.path.exists(path):
            print("rules_reference: %s: no such file" % path, file=sys.stderr)
            return 2
    with open(os.path.join(ref, compare.ENERGY_FILE)) as f:
        if sum(1 for line in f if line.strip()) < 2:  # an original that crashed writes nothing
            print("rules_reference: %s holds no run" % os.path.join(ref, compare.ENERGY_FILE), file=sys.stderr)
            return 2
    work = tempfile.mkdtemp(prefix="rules-reference-%s-" % stem)
    try:
        shutil.copy(deck, os.path.join(work, os.path.basename(deck)))
        argv_run = [mpm3d, "--threads", "2", "--quiet", "--out-dir", work] + rest + [os.path.basename(deck)]
        print("+ " + " ".join(argv_run))
        if subprocess.run(argv_run, cwd=work).returncode != 0:
            print("rules_reference: mpm3d failed", file=sys.stderr)
            return 2
        rows, _ = compare.compare_runs(stem, ref, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    beyond = []
    for r in rows:
        if r.max_diff is None:
            print("  %-24s %-10s %s" % (r.file, r.column, r.note))
            continue
        out = r.max_diff > bound(r.column)
        if out:
            beyond.append(r.column)
        print("  %-24s %-10s %9.3f %%  (bound %g %%)%s" % (r.file, r.column, r.max_diff, bound(r.column),
                                                        "  BEYOND" if out else ""))
    if beyond_wanted:
        print("beyond the bounds: %s" % (", ".join(beyond) if beyond else "none (expected some)"))
        return 0 if beyond else 1
    print("every column within its bound" if not beyond else "beyond the bounds: " + ", ".join(beyond))
    return 1 if beyond else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
