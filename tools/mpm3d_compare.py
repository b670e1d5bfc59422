#!/usr/bin/env python3
"""mpm3d-compare: run decks through the original MPM3D-F90 and through mpm3d, and compare.

Installed as `mpm3d-compare` beside `mpm3d`. Plain Python 3 (no numpy), so that it runs with
whatever python3 the user has; matplotlib is imported only for --plot.
"""
import argparse
import importlib.util
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

EXIT_OK, EXIT_DIFFER, EXIT_BAD = 0, 1, 2
ENERGY_FILE = "EnergyPlot.dat"
ENERGY_COLUMNS = ["Time", "total", "kinetic", "internal"]
LOG_NAME = "run.log"  # both output streams of each program, in its run directory
SUMMARY_NAME = "summary.json"
TAIL_LINES = 10

DESCRIPTION = """\
Run each DECK through the original MPM3D-F90 program and through mpm3d, each in a fresh
directory, and compare what both write: every column of EnergyPlot.dat (total, kinetic,
internal energy) and of NAME_curv.dat (curve columns matched by name, else by position),
interpolated linearly on the original's times where both runs cover them.

For each column: the largest |mpm3d - original| over the run and the difference at the
last compared time, both in % of the column's largest magnitude in the original's run,
and whether both are within --tolerance. Particle fields: when the deck asks for the
TecPlot animation (tecp), both programs write NAME_anim.dat, and the original's last frame
is compared with mpm3d's frame at the same time (columns by name, particles in deck
order). For decks without tecp no particle fields are compared (neither the ParaView .vtu
series nor mpm3d's HDF5 files are read). Columns only one program writes are listed,
marked, and not compared.

Where particles leave the grid, the original's results are undefined from then on (it
indexes its cell list with -1). mpm3d counts them at its reports (rpttime): from the first
report that counts any, a line says how many left and when, a column 'before exit %' gives
each column's largest difference up to the report before it (in % of the original's largest
magnitude up to then; particle fields: the original's last frame up to then), and that
column alone decides the result. Without particles leaving, the output is as above.

Also printed: both wall times, mpm3d's ns per particle-step (its --summary) and the
original's 'Time per particle cycle' (its output or NAME.out).

--rules and --rule are passed to mpm3d (mpm3d --help lists the rules: the places where
mpm3d deliberately differs from the original programs). --rules original means the rules of
the original program given: the book version or the current one (2025 and newer), as
--original-program says, or by default (auto) as its executable tells: the current
program's holds its version's deck keywords (bimp, sgmp, TLmp, UVFp, QuLo, neoh) as text,
the book program's none of them; a script tells it in a line
'# mpm3d-compare: program=book' (or current). --explain answers why a column is beyond the
tolerance: mpm3d runs again with each rule in turn set to that program's value (to the
value under --rules book or current where given), then with all of them, and a table gives
each column's largest difference under each. It also prints what mpm3d knows it does
differently on the deck with no rule to copy the original (mpm3d's summary, not_copied),
and where the original's own results turn on the last digits (sensitive).

Exit status: 0 every compared column within tolerance; 1 some column beyond it;
2 bad input (a program missing or not executable, a missing deck, a deck either
program rejects, an original program that auto cannot tell where it must)."""


class BadInput(Exception):
    """A program or deck we cannot compare with; the message names it (exit status 2)."""


# Reading and comparing the two programs' files (tools/compare_files.py, installed beside);
# read_series and read_table for the tools that load this script as their file parser (from
# any folder: hence this script's own folder on the path).
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_files import (compare_file, compare_particles, curve_file, has_data, largest,  # noqa: E402,F401
                           parse_number, read_series, read_table, relative)


# ---------------------------------------------------------------------------- which original

# Deck keywords of the current version that the book version lacks; gfortran keeps them as
# text in the executable (the keyword tables of its DataIn.f90).
CURRENT_KEYWORDS = ("bimp", "sgmp", "TLmp", "UVFp", "QuLo", "neoh")
PROGRAM_LINE = re.compile(rb"^# mpm3d-compare: program=(book|current)[ \t]*$", re.M)


def which_program(exe):
    """('book' or 'current', how that was told) of the original's executable, or (None, why
    not): a compiled program by CURRENT_KEYWORDS (all: current, none: book), a script by
    its line '# mpm3d-compare: program=...'."""
    with open(exe, "rb") as f:
        data = f.read()
    if data.startswith(b"#!"):
        m = PROGRAM_LINE.search(data)
        if m:
            return m.group(1).decode(), "its line '%s'" % m.group(0).decode().strip()
        return None, "a script without a line '# mpm3d-compare: program=book' (or current)"
    found = [k for k in CURRENT_KEYWORDS if k.encode() in data]
    names = ", ".join(CURRENT_KEYWORDS)
    if len(found) == len(CURRENT_KEYWORDS):
        return "current", "its executable holds the current version's keywords " + names
    if not found:
        return "book", "its executable holds none of the current version's keywords " + names
    return None, "its executable holds only %s of the keywords %s" % (", ".join(found), names)


def settle_program(args, original):
    """args.program: 'book' or 'current', the original program whose rules --rules original
    and --explain take (printed with how it was told; BadInput where it cannot be told). A
    --rules book or current that names the other program gets a warning."""
    args.program = None
    given = args.rules in ("book", "current")
    needed = args.rules == "original" or (args.explain and not given)
    if not (needed or given):
        return
    program, how = ((args.original_program, "as --original-program says")
                    if args.original_program != "auto" else which_program(original))
    if program is None and needed:
        raise BadInput("cannot tell which original program %s is (%s): give "
                       "--original-program book or current" % (args.original, how))
    if needed:
        args.program = program
        print("mpm3d-compare: the original program is taken to be the %s program (%s)"
              % (program, how))
    elif program not in (None, args.rules):
        print("mpm3d-compare: warning: --rules %s, but the original program is the %s "
              "program (%s)" % (args.rules, program, how), file=sys.stderr)


# ---------------------------------------------------------------------------- running

def resolve_program(path, what):
    """The absolute path of an executable given as a path or a name on PATH (both runs
    change directory, so a relative path must be made absolute first)."""
    found = shutil.which(path) if os.sep not in path else path
    if not found or not os.path.isfile(found):
        raise BadInput("%s %s: no such file" % (what, path))
    if not os.access(found, os.X_OK):
        raise BadInput("%s %s: not executable" % (what, path))
    return os.path.abspath(found)


def default_mpm3d():
    """The mpm3d beside this script (installed in one bin/, or both in the build tree's
    cxx/), following a link to the script too; else mpm3d on PATH."""
    for here in (os.path.abspath(__file__), os.path.realpath(__file__)):
        beside = os.path.join(os.path.dirname(here), "mpm3d")
        if os.path.isfile(beside) and os.access(beside, os.X_OK):
            return beside
    return shutil.which("mpm3d") or "mpm3d"


def run(argv, cwd):
    """Run with empty stdin and both output streams to cwd/run.log (a long run prints
    more than is worth holding in memory); (exit status, wall seconds)."""
    with open(os.path.join(cwd, LOG_NAME), "wb") as log:
        start = time.perf_counter()
        try:
            proc = subprocess.run(argv, cwd=cwd, input=b"", stdout=log, stderr=subprocess.STDOUT)
        except OSError as e:
            raise BadInput("cannot run %s: %s" % (argv[0], e.strerror))
        return proc.returncode, time.perf_counter() - start


def log_tail(run_dir, n=TAIL_LINES):
    """The last n non-empty lines a program printed, indented for stderr."""
    with open(os.path.join(run_dir, LOG_NAME), errors="replace") as f:
        lines = [l.rstrip() for l in f if l.strip()]
    return "\n".join("    " + l for l in lines[-n:])


def original_ns(run_dir, stem):
    """The original's own 'Time per particle cycle: X nanoseconds', from its output or
    NAME.out; None when absent (older versions do not print it)."""
    pattern = re.compile(r"Time per particle cycle:\s*([-+0-9.EeDd]+)")
    for name in (LOG_NAME, stem + ".out"):
        path = os.path.join(run_dir, name)
        if os.path.isfile(path):
            with open(path, errors="replace") as f:
                found = pattern.findall(f.read())
            if found:
                return parse_number(found[-1].replace("D", "E").replace("d", "e"))
    return None


PROGRESS = re.compile(r"^step +\d+ +t +(\S+) .* outside +(\d+)", re.M)


def grid_exit(run_dir, stem):
    """(particles, time) at the first of mpm3d's reports (its progress lines in NAME.out,
    the last one at the end) that counts particles outside the grid, and the time of the
    report before it (0 if none); None where none left the grid."""
    reports = [(0.0, 0)]
    try:
        with open(os.path.join(run_dir, stem + ".out"), errors="replace") as f:
            reports += [(float(t), int(n)) for t, n in PROGRESS.findall(f.read())]
    except OSError:  # an mpm3d that writes no log (not ours): nothing to tell
        pass
    k = next((k for k, (_, n) in enumerate(reports) if n > 0), None)
    return None if k is None else (reports[k][1], reports[k][0], reports[k - 1][0])


def run_original(exe, deck_name, run_dir):
    """Run the original as `exe deck.mpm`; (wall s, its ns per particle cycle). A deck it
    rejects: a non-zero exit, or no EnergyPlot.dat rows (its 'stop' exits with 0)."""
    rc, wall = run([exe, deck_name], run_dir)
    if rc != 0 or not has_data(os.path.join(run_dir, ENERGY_FILE)):
        why = "exit status %d" % rc if rc != 0 else "no %s written" % ENERGY_FILE
        raise BadInput("%s: the original rejected the deck (%s); its last lines:\n%s"
                       % (deck_name, why, log_tail(run_dir)))
    return wall, original_ns(run_dir, os.path.splitext(deck_name)[0])


def run_mpm3d(exe, deck_name, run_dir, threads, rule_args=()):
    """Run mpm3d with its outputs in run_dir; (wall s, its ns per particle-step).
    rule_args: mpm3d's --rules/--rule options."""
    summary = os.path.join(run_dir, SUMMARY_NAME)
    argv = [exe, "--threads", str(threads), "--quiet", "--out-dir", run_dir,
            "--summary", summary] + list(rule_args) + [deck_name]
    rc, wall = run(argv, run_dir)
    if rc != 0 or not has_data(os.path.join(run_dir, ENERGY_FILE)):
        why = "exit status %d" % rc if rc != 0 else "no %s written" % ENERGY_FILE
        raise BadInput("%s: mpm3d rejected the deck (%s):\n%s"
                       % (deck_name, why, log_tail(run_dir, 3)))
    try:
        with open(summary) as f:
            return wall, json.load(f).get("ns_per_particle_step")
    except (OSError, ValueError):
        return wall, None


# ---------------------------------------------------------------------------- reporting

def fmt(value, spec):
    """A figure, or '-' where there is none."""
    return "-" if value is None else spec % value


def print_table(deck, rows, tolerance, timing, left=None):
    """The per-deck table: one line per column, then the two programs' speeds. left:
    grid_exit's (particles, time, report before), adding the column 'before exit %'."""
    header = ("file", "column", "max diff %", "final diff %") + \
        (("before exit %",) if left else ()) + ("result",)
    lines = []
    for r in rows:
        verdict = r.note or ("FAIL" if r.failed(tolerance) else "not judged (after the exit)"
                             if r.cut and r.exit_diff is None else "ok")
        figures = [r.max_diff, r.final_diff] + ([r.exit_diff] if left else [])
        lines.append((r.file, r.column) + tuple(fmt(v, "%.3f") for v in figures) + (verdict,))
    w = [max(len(x[k]) for x in lines + [header]) for k in range(len(header) - 1)]
    print("== %s (tolerance %g %%)" % (deck, tolerance))
    if left:
        print("  %d particles left the grid by t = %.4e (mpm3d counts them at its reports, none "
              "at t = %.4e);\n  the original's results after that are undefined (it indexes "
              "its cell list with -1 there),\n  so 'before exit %%' compares up to t = %.4e, "
              "and it alone decides the result:" % (left[:3] + left[2:]))
    for x in [header] + lines:
        print("  " + "  ".join([x[0].ljust(w[0]), x[1].ljust(w[1])] +
                               [v.rjust(n) for v, n in zip(x[2:-1], w[2:])] + [x[-1]]))
    (o_wall, o_ns), (c_wall, c_ns) = timing
    print("  %-24s %12s %12s" % ("", "original", "mpm3d"))
    print("  %-24s %12.2f %12.2f" % ("wall time (s)", o_wall, c_wall))
    print("  %-24s %12s %12s" % ("ns per particle-step", fmt(o_ns, "%.1f"), fmt(c_ns, "%.1f")))
    failed = [r.column for r in rows if r.failed(tolerance)]
    before = " before particles left the grid" if left else ""
    print("  %s\n" % ("beyond %g %%%s: %s" % (tolerance, before, ", ".join(failed)) if failed
                      else "all compared columns within %g %%%s" % (tolerance, before)))
    sys.stdout.flush()
    return failed


def plot_deck(path, deck, plots):
    """One PNG: a panel per compared column, both programs against time."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ncol = min(3, max(1, len(plots)))
    nrow = max(1, (len(plots) + ncol - 1) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.5 * ncol, 3.2 * nrow), squeeze=False)
    for ax, (label, column, o_t, o_y, c_t, c_y) in zip(axes.flat, plots):
        ax.plot(o_t, o_y, label="original")
        ax.plot(c_t, c_y, "--", label="mpm3d")
        ax.set_title("%s: %s" % (label, column), fontsize=9)
        ax.set_xlabel("time")
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[len(plots):]:
        ax.axis("off")
    fig.suptitle(deck)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def keep_runs(keep_dir, stem, tmp):
    """Move both run directories to keep_dir/stem/{original,mpm3d}, replacing earlier ones."""
    target = os.path.join(keep_dir, stem)
    os.makedirs(target, exist_ok=True)
    for sub in ("original", "mpm3d"):
        dest = os.path.join(target, sub)
        if os.path.isdir(dest):
            shutil.rmtree(dest)
        shutil.move(os.path.join(tmp, sub), dest)


# ---------------------------------------------------------------------------- one deck, all

def compare_deck(deck, args, original, mpm3d):
    """Run and compare one deck; EXIT_OK or EXIT_DIFFER (BadInput for a rejected deck)."""
    if not os.path.isfile(deck):
        raise BadInput("%s: no such deck" % deck)
    deck_name = os.path.basename(deck)
    stem = os.path.splitext(deck_name)[0]
    tmp = tempfile.mkdtemp(prefix="mpm3d-compare-%s-" % stem)
    try:
        dirs = {}
        for sub in ("original", "mpm3d"):
            dirs[sub] = os.path.join(tmp, sub)
            os.mkdir(dirs[sub])
            shutil.copy(deck, os.path.join(dirs[sub], deck_name))
        rule_args = user_rule_args(args)
        timing = (run_original(original, deck_name, dirs["original"]),
                  run_mpm3d(mpm3d, deck_name, dirs["mpm3d"], args.threads, rule_args))
        left = grid_exit(dirs["mpm3d"], stem)
        until = left[2] if left else None
        rows, plots = compare_runs(stem, dirs["original"], dirs["mpm3d"], until)
        rows += compare_particles(stem, dirs["original"], dirs["mpm3d"], until)
        if rule_args:
            print("  (mpm3d run with %s)" % " ".join(rule_args))
        failed = print_table(deck_name, rows, args.tolerance, timing, left)
        if failed and args.explain:
            explain(deck_name, stem, dirs, args, mpm3d, rows, failed, until)
        if args.plot:
            os.makedirs(args.plot, exist_ok=True)
            plot_deck(os.path.join(args.plot, stem + ".png"), deck_name, plots)
        return EXIT_DIFFER if failed else EXIT_OK
    finally:
        if args.keep:
            keep_runs(args.keep, stem, tmp)
        shutil.rmtree(tmp, ignore_errors=True)


def compare_runs(stem, orig_dir, our_dir, until=None):
    """Rows and plot series of the energy file and the curve file of two run directories
    (until: see compare_file)."""
    rows, plots = compare_file(ENERGY_FILE, os.path.join(orig_dir, ENERGY_FILE),
                               os.path.join(our_dir, ENERGY_FILE), ENERGY_COLUMNS, until)
    orig_curves = curve_file(orig_dir, stem)
    if orig_curves:
        more, more_plots = compare_file(os.path.basename(orig_curves), orig_curves,
                                        curve_file(our_dir, stem), None, until)
        rows, plots = rows + more, plots + more_plots
    return rows, plots


# ---------------------------------------------------------------------------- --explain

def user_rule_args(args):
    """mpm3d's rule options as given: --rules PRESET (original: the original program's,
    book or current), then each --rule NAME=VALUE."""
    rules = args.program if args.rules == "original" else args.rules
    out = ["--rules", rules] if rules else []
    for r in args.rule or []:
        out += ["--rule", r]
    return out


# The summary's notes on the original programs that --explain prints: key, heading.
SUMMARY_NOTES = (
    ("not_copied", "not copied (mpm3d differs from the original here by design, and no rule takes the "
                   "original's way)"),
    ("sensitive", "sensitive (the original's own results here turn on the last digits, so mpm3d's differ "
                  "within that spread)"),
)


def rules_in_force(mpm3d, deck_name, run_dir, rule_args, notes=None):
    """{rule: value} that mpm3d resolves for the deck under rule_args (a run of 0 steps,
    from its summary); where notes (a dict) is given, the summary's lists of SUMMARY_NOTES
    by key."""
    summary = os.path.join(run_dir, "rules.json")
    argv = [mpm3d, "--threads", "1", "--quiet", "--no-output", "--steps", "0", "--summary",
            summary] + list(rule_args) + [deck_name]
    rc, _ = run(argv, run_dir)
    try:
        with open(summary) as f:
            js = json.load(f)
        rules = js.get("rules")
        if notes is not None:
            for key, _ in SUMMARY_NOTES:
                notes[key] = js.get(key) or []
    except (OSError, ValueError):
        rules = None
    if rc != 0 or not isinstance(rules, dict):
        raise BadInput("%s: mpm3d did not report its rules (exit status %d):\n%s"
                       % (deck_name, rc, log_tail(run_dir, 3)))
    return rules


def explain(deck_name, stem, dirs, args, mpm3d, rows, failed, until=None):
    """Rerun mpm3d with each rule that differs from the original program's value set to it,
    then with all of them; print each failing column's largest difference under each."""
    base_args = user_rule_args(args)
    preset = args.rules if args.rules in ("book", "current") else args.program
    work = os.path.join(os.path.dirname(dirs["mpm3d"]), "explain")
    os.makedirs(work, exist_ok=True)
    shutil.copy(os.path.join(dirs["mpm3d"], deck_name), os.path.join(work, deck_name))
    ours = rules_in_force(mpm3d, deck_name, work, base_args)
    notes = {}
    target = rules_in_force(mpm3d, deck_name, work, ["--rules", preset], notes)
    for key, heading in SUMMARY_NOTES:
        if notes.get(key):
            print("  %s:" % heading)
            for text in notes[key]:
                print("    - " + text)
    if ours == target:
        print("  why: mpm3d already ran with the original program's rules (--rules %s): the "
              "difference is not one of mpm3d's rules\n" % preset)
        return
    trials = [("%s=%s" % (r, target[r]), base_args + ["--rule", "%s=%s" % (r, target[r])])
              for r in target if ours.get(r) != target[r]]
    if len(trials) > 1:
        trials.append(("all (--rules %s)" % preset, ["--rules", preset]))
    as_compared = {r.column: r.decisive() for r in rows if r.column in failed}
    table = [("(as compared)", as_compared)]
    for label, rule_args in trials:
        run_dir = os.path.join(work, "run%d" % len(table))
        os.mkdir(run_dir)
        shutil.copy(os.path.join(work, deck_name), os.path.join(run_dir, deck_name))
        rc, _ = run([mpm3d, "--threads", str(args.threads), "--quiet", "--out-dir", run_dir]
                    + rule_args + [deck_name], run_dir)
        if rc != 0 or not has_data(os.path.join(run_dir, ENERGY_FILE)):
            table.append((label, None))
            continue
        trial_rows, _ = compare_runs(stem, dirs["original"], run_dir, until)
        table.append((label, {r.column: r.decisive() for r in trial_rows if r.column in failed}))
    print("  why: the columns beyond %g %% (largest difference %%) with each rule set to the "
          "original program's value" % args.tolerance)
    w = max(len(label) for label, _ in table)
    print("  %-*s  %s" % (w, "rule", "  ".join("%10s" % c for c in failed)))
    for label, diffs in table:
        cells = ("%10s" % ("mpm3d fails" if diffs is None else fmt(diffs.get(c), "%.3f"))
                 for c in failed)
        print("  %-*s  %s" % (w, label, "  ".join(cells)))
    print()
    sys.stdout.flush()


def parse_args(argv):
    p = argparse.ArgumentParser(prog="mpm3d-compare", description=DESCRIPTION,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--original", required=True, metavar="PATH",
                   help="the original MPM3D-F90 program, run as 'PATH deck.mpm'")
    p.add_argument("--mpm3d", metavar="PATH",
                   help="mpm3d (default: the mpm3d beside this script, else on PATH)")
    p.add_argument("--threads", type=int, default=os.cpu_count() or 1, metavar="N",
                   help="mpm3d's OpenMP threads (default: all cores; the original is serial)")
    p.add_argument("--tolerance", type=float, default=1.0, metavar="T",
                   help="largest allowed difference, in %% of a column's largest "
                        "magnitude (default 1)")
    p.add_argument("--plot", metavar="DIR", help="write DIR/DECKNAME.png (needs matplotlib)")
    p.add_argument("--rules", metavar="PRESET", choices=["ours", "original", "book", "current"],
                   help="mpm3d's rules: ours (default), original (the original "
                        "program's: book or current), book or current")
    p.add_argument("--original-program", choices=["book", "current", "auto"], default="auto",
                   help="which program --original is, for --rules original and --explain: "
                        "book, current (2025 and newer), auto (default: told by its "
                        "executable)")
    p.add_argument("--rule", action="append", metavar="NAME=VALUE",
                   help="set one of mpm3d's rules (repeatable; mpm3d --help lists them)")
    p.add_argument("--explain", action="store_true",
                   help="for the columns beyond the tolerance, rerun mpm3d with each rule set "
                        "to the original program's value, then all, and print a table")
    p.add_argument("--keep", metavar="DIR",
                   help="keep both runs in DIR/DECKNAME/{original,mpm3d} (replacing those)")
    p.add_argument("decks", nargs="+", metavar="DECK")
    args = p.parse_args(argv)
    if args.threads < 1 or args.tolerance < 0:
        p.error("--threads must be at least 1 and --tolerance not negative")
    return args


def main(argv=None):
    args = parse_args(argv)
    try:
        original = resolve_program(args.original, "the original program")
        mpm3d = resolve_program(args.mpm3d or default_mpm3d(), "mpm3d")
        settle_program(args, original)
        if args.plot and importlib.util.find_spec("matplotlib") is None:
            raise BadInput("--plot needs matplotlib, which %s cannot import (run "
                           "'PYTHON3 mpm3d-compare ...' with one that can)" % sys.executable)
    except BadInput as e:
        print("mpm3d-compare: %s" % e, file=sys.stderr)
        return EXIT_BAD
    status = EXIT_OK
    for deck in args.decks:
        try:
            status = max(status, compare_deck(deck, args, original, mpm3d))
        except BadInput as e:
            print("mpm3d-compare: %s" % e, file=sys.stderr)
            status = EXIT_BAD
    return status


if __name__ == "__main__":
    sys.exit(main())
