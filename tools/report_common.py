"""Shared pieces of make report (tools/report.py) and its study modules (tools/report_*.py):
the project root, the shape functions and their plot styles, the convergence groups of
--only, the helpers (time stamps, number format, CSV writer) and pyplot with the Agg backend.
"""
import csv
import datetime
import math
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402, F401  (the studies' plots)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHAPES = ("linear", "gimp")
# Every shape function and gradient treatment, for the manufactured solutions: the
# current version's B-splines (bimp) and smoothed gradients (sgmp) beside the book's.
METHODS = ("linear", "gimp", "bimp", "sgmp")
STYLE = {"linear": "o-", "gimp": "s--", "bimp": "D-.", "sgmp": "^:"}
COLOR = {"linear": "C0", "gimp": "C1", "bimp": "C2", "sgmp": "C3"}
SMOOTH_MMS = "smooth manufactured solution (3D, free faces)"
# The convergence cases in the order the report runs them: (--only name, Suite method,
# prefixes of their case names in Suite.conv and Suite.skipped).
GROUPS = (("bar", "bar", ("vibrating bar",)),
          ("mms", "mms", ("manufactured solution",)),
          ("mms3", "mms_smooth", ("smooth manufactured solution",)),
          ("wave", "waves", ("elastic wave speed", "elastic-plastic wave")),
          ("spheres", "spheres", ("colliding spheres",)),
          ("sod", "sod", ("Sod shock tube",)))


def group_of(case):
    """Index in GROUPS of a case name; len(GROUPS) for the others (stability, Taylor)."""
    for i, (_, _, prefixes) in enumerate(GROUPS):
        if case.startswith(prefixes):
            return i
    return len(GROUPS)


def utc_now():
    return datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M UTC")


def loadavg():
    try:
        with open("/proc/loadavg") as f:
            return " ".join(f.read().split()[:3])
    except OSError:
        return "n/a"


def fmt(x, d=3):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-"
    if isinstance(x, int):
        return str(x)
    if x != 0 and (abs(x) < 1e-3 or abs(x) >= 1e5):
        return f"{x:.{d - 1}e}"
    return f"{x:.{d}g}"


def short(msg):
    """A refusal message without the machine's work directory (deck base name kept)."""
    return re.sub(r"^\S*/", "", msg or "")


def write_csv(path, rows, keys):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(keys)
        for r in rows:
            w.writerow([r.get(k, "") for k in keys])
