"""The result files of the report's studies (docs/verification/*.csv): a study's run() writes
its rows, its section_lines() reads them back with the date they were written."""
import csv
import datetime
import os


def write_dicts(path, rows):
    """Rows (dicts with the same keys, in column order) to a CSV file."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def read_dicts(path):
    """(rows, the file's UTC date as YYYY-MM-DD), or (None, None) when the study has not run."""
    if not os.path.exists(path):
        return None, None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows, datetime.datetime.utcfromtimestamp(os.path.getmtime(path)).strftime("%Y-%m-%d")
