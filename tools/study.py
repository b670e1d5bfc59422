"""Shared pieces of the report's studies (tools/soft_beam.py, soft_cantilever.py, dam_break.py,
cook_membrane.py): running a generated deck, and their result files (docs/verification/*.csv):
a study's run() writes its rows, its section_lines() reads them back with their date."""
import contextlib
import csv
import datetime
import os
import subprocess
import sys
import tempfile


@contextlib.contextmanager
def deck_run(mpm3d, text, threads, what, name="beam"):
    """Runs the deck `text` (written as NAME.mpm) in a scratch folder and yields the folder,
    whose output files (NAME_curv.dat, EnergyPlot.dat, ...) the caller reads; a failed run
    ends the study with mpm3d's message."""
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, name + ".mpm")
        with open(path, "w") as f:
            f.write(text)
        p = subprocess.run([mpm3d, "--threads", str(threads), "--quiet", "--out-dir", work, path],
                           capture_output=True, text=True)
        if p.returncode != 0:
            sys.exit(f"{what}: mpm3d failed: {p.stderr.strip()}")
        yield work


def write_dicts(path, rows):
    """Rows (dicts with the same keys, in column order) to a CSV file."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def section_start(title, path, how_to_run):
    """A report section's heading and its study's rows from the CSV at path: (lines, rows, the
    CSV's date); without the CSV, rows is None and the lines say how to run the study."""
    L = [title, ""]
    rows, when = read_dicts(path)
    if rows is None:
        L += ["Not run (%s)." % how_to_run, ""]
    return L, rows, when


def read_dicts(path):
    """(rows, the file's UTC date as YYYY-MM-DD), or (None, None) when the study has not run."""
    if not os.path.exists(path):
        return None, None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows, datetime.datetime.utcfromtimestamp(os.path.getmtime(path)).strftime("%Y-%m-%d")
