"""The files of an MPM3D-F90 run and of an mpm3d run, read and compared: the column tables
(EnergyPlot.dat, NAME_curv.dat, Fortran E12.4 numbers) and the TecPlot animation's frames, as
rows of largest differences in % of the original's largest magnitude. Used by mpm3d-compare
(tools/mpm3d_compare.py), which runs the programs, and by the tools that read their files.
Plain Python 3 (no numpy), as mpm3d-compare."""
import bisect
import math
import os
import re

FORTRAN_BIG_EXPONENT = re.compile(r"^([+-]?(?:\d+\.?\d*|\.\d+))([+-]\d{3,})$")


def parse_number(token):
    """A number as Fortran prints it. E12.4 drops the 'E' when the exponent has three
    digits (0.1234-100), and an overflowing field is all stars: that one reads as NaN."""
    try:
        return float(token)
    except ValueError:
        m = FORTRAN_BIG_EXPONENT.match(token)
        return float(m.group(1) + "e" + m.group(2)) if m else float("nan")


def is_header(tokens):
    """A header line starts with a word ('Time engk1 ...'); NaN and Infinity are data."""
    word = tokens[0]
    return word[0].isalpha() and word.lower() not in ("nan", "inf", "infinity")


def read_table(path):
    """(column names or None, rows) of a whitespace-separated file with an optional
    header line. Rows with another column count (a torn last line) are left out."""
    names, rows = None, []
    with open(path, errors="replace") as f:
        for line in f:
            tokens = line.split()
            if not tokens:
                continue
            if names is None and not rows and is_header(tokens):
                names = tokens
                continue
            if rows and len(tokens) != len(rows[0]):
                continue
            rows.append([parse_number(t) for t in tokens])
    return names, rows


def collapse_ties(rows):
    """One row per printed time, the mean of the rows that share it. Both programs print
    the time with 4 digits (E12.4), so a long run prints many steps under one time;
    means give a function of time that both files can be interpolated on."""
    out, i = [], 0
    while i < len(rows):
        j = i
        while j < len(rows) and rows[j][0] == rows[i][0]:
            j += 1
        group = rows[i:j]
        out.append([sum(col) / len(group) for col in zip(*group)])
        i = j
    return out


def read_series(path, default_names=None):
    """(names, times, {name: values}) of a time-history file; columns without a header
    name are called col1, col2, ... by position."""
    names, rows = read_table(path)
    width = len(rows[0]) if rows else len(names or default_names or [])
    names = list(names or default_names or [])
    names = (names + ["col%d" % k for k in range(len(names), width)])[:width]
    rows = collapse_ties(rows)
    columns = {name: [r[k] for r in rows] for k, name in enumerate(names)}
    return names, [r[0] for r in rows], columns


def curve_file(run_dir, stem):
    """NAME_curv.dat, NAME being the deck's name without extension; failing that the one
    *_curv.dat in the directory (both programs derive NAME from the deck's file name)."""
    path = os.path.join(run_dir, stem + "_curv.dat")
    if os.path.isfile(path):
        return path
    found = [f for f in os.listdir(run_dir) if f.endswith("_curv.dat")]
    return os.path.join(run_dir, found[0]) if len(found) == 1 else None


def has_data(path):
    """Whether a time-history file exists and holds at least one row."""
    return os.path.isfile(path) and bool(read_table(path)[1])


# ---------------------------------------------------------------------------- comparing

class Row:
    """One line of the table: what was compared, the two differences (in %) and the verdict."""

    def __init__(self, file, column, max_diff=None, final_diff=None, note=""):
        self.file, self.column, self.note = file, column, note
        self.max_diff, self.final_diff = max_diff, final_diff
        self.cut, self.exit_diff = False, None  # cut: particles left; exit_diff decides

    def decisive(self):
        """The largest difference, before particles left the grid where they did (cut)."""
        return self.exit_diff if self.cut else self.max_diff

    def failed(self, tolerance):
        """Beyond tolerance; columns not compared (note set) do not fail. Where particles
        left the grid (cut), the largest difference before they did decides alone."""
        if self.cut:
            return self.exit_diff is not None and not self.exit_diff <= tolerance
        if self.max_diff is None:
            return False
        return not (self.max_diff <= tolerance and (self.final_diff or 0.0) <= tolerance)


def match_columns(orig_names, our_names):
    """(label, original name, our name or None) per original column after the time: by
    name where both name it, else the column at the same position unless that one is
    named by the original too (then it belongs to that name, not to this column)."""
    ours = set(our_names)
    taken = set(orig_names)
    pairs = []
    for k, name in enumerate(orig_names[1:], start=1):
        if name in ours:
            pairs.append((name, name, name))
        elif k < len(our_names) and our_names[k] not in taken:
            pairs.append(("%s/%s" % (name, our_names[k]), name, our_names[k]))
        else:
            pairs.append((name, name, None))
    return pairs


def interpolate(times, values, t):
    """Linear interpolation of values(times) at t, times ascending and t within them."""
    k = bisect.bisect_left(times, t)
    if k < len(times) and times[k] == t:
        return values[k]
    t0, t1, v0, v1 = times[k - 1], times[k], values[k - 1], values[k]
    return v0 + (v1 - v0) * (t - t0) / (t1 - t0)


def relative(diff, scale):
    """diff in % of scale; NaN (a run that blew up) counts as infinitely different."""
    if diff != diff:
        return math.inf
    return 100.0 * diff / scale if scale > 0 else (0.0 if diff == 0 else math.inf)


def largest(diffs):
    """The largest of the differences, NaN if any is NaN (max() would depend on order)."""
    return math.nan if any(d != d for d in diffs) else max(diffs, default=0.0)


def compare_column(t_orig, y_orig, t_ours, y_ours, until=math.inf):
    """(largest, final) |ours - original| in % of the original's largest magnitude, on
    the original's times inside both runs' time ranges (and up to until); None without an
    overlap. Where the original's column is zero throughout, mpm3d's largest magnitude is
    the scale."""
    lo, hi = max(t_orig[0], t_ours[0]), min(t_orig[-1], t_ours[-1], until)
    at = [k for k, t in enumerate(t_orig) if lo <= t <= hi]
    if not at:
        return None
    ours = [interpolate(t_ours, y_ours, t_orig[k]) for k in at]
    diffs = [abs(o - y_orig[k]) for o, k in zip(ours, at)]
    scale = max((abs(v) for v, t in zip(y_orig, t_orig) if math.isfinite(v) and t <= until),
                default=0.0)
    if scale == 0.0:
        scale = max((abs(v) for v in ours if math.isfinite(v)), default=0.0)
    return relative(largest(diffs), scale), relative(diffs[-1], scale)


def compare_file(label, orig_path, our_path, default_names=None, until=None):
    """Table rows for one time-history file, plus (names, series) of both for the plot;
    with until (particles left the grid after it), each row's figure up to until too."""
    o_names, o_t, o_cols = read_series(orig_path, default_names)
    if not o_t:
        return [Row(label, "-", note="no data in the original's file")], []
    if not our_path or not has_data(our_path):
        return [Row(label, "-", note="not written by mpm3d")], []
    c_names, c_t, c_cols = read_series(our_path, default_names)
    rows, plots = [], []
    for shown, o_name, c_name in match_columns(o_names, c_names):
        if c_name is None:
            rows.append(Row(label, shown, note="not in mpm3d's file"))
            continue
        result = compare_column(o_t, o_cols[o_name], c_t, c_cols[c_name])
        if result is None:
            rows.append(Row(label, shown, note="no common time range"))
        else:
            rows.append(Row(label, shown, *result))
            if until is not None:
                rows[-1].cut = True
                rows[-1].exit_diff = (compare_column(o_t, o_cols[o_name], c_t, c_cols[c_name],
                                                     until) or (None,))[0]
        plots.append((label, shown, o_t, o_cols[o_name], c_t, c_cols[c_name]))
    return rows, plots


# ------------------------------------------------------------------ particle fields (TecPlot)

def zone_time(line):
    """The time of a TecPlot zone line: the last number inside T="..." (the original
    writes T="time 0.140E-01", mpm3d T="1.400059E-02")."""
    m = re.search(r'T\s*=\s*"([^"]*)"', line)
    words = m.group(1).split() if m else []
    return parse_number(words[-1]) if words else math.nan


def scan_anim(path):
    """(variable names, [(zone time, byte offset of its first particle line)])."""
    names, zones, offset = [], [], 0
    with open(path, "rb") as f:
        for raw in f:
            offset += len(raw)
            line = raw.decode(errors="replace")
            if line.startswith("VARIABLES"):
                names = [n.strip() for n in re.findall(r'"([^"]*)"', line)]
            elif line.startswith("ZONE"):
                zones.append((zone_time(line), offset))
    return names, zones


def read_zone(path, offset):
    """The particle rows of the zone whose lines start at offset."""
    rows = []
    with open(path, "rb") as f:
        f.seek(offset)
        for raw in f:
            tokens = raw.decode(errors="replace").split()
            if not tokens or tokens[0].startswith("ZONE"):
                break
            rows.append([parse_number(t) for t in tokens])
    return rows


def compare_particles(stem, orig_dir, our_dir, until=None):
    """Rows comparing the original's last animation frame (up to until, where particles
    left the grid after it; that frame decides) with mpm3d's frame at the same time; []
    when the original wrote no TecPlot animation."""
    name = stem + "_anim.dat"
    orig_path, our_path = os.path.join(orig_dir, name), os.path.join(our_dir, name)
    if not os.path.isfile(orig_path):
        return []
    if not os.path.isfile(our_path):
        return [Row(name, "-", note="not written by mpm3d")]
    o_names, o_zones = scan_anim(orig_path)
    o_zones = [z for z in o_zones if until is None or z[0] <= until]
    c_names, c_zones = scan_anim(our_path)
    if not o_zones or not c_zones:
        return [Row(name, "-", note="no frames to compare")]
    t, o_off = o_zones[-1]
    c_t, c_off = min(c_zones, key=lambda z: abs(z[0] - t))
    # The original prints a frame's time with 3 digits (E10.3).
    if not abs(c_t - t) <= 0.01 * abs(t):
        return [Row(name, "-", note="mpm3d wrote no frame at t=%.3e" % t)]
    label = "%s t=%.3e" % (name, t)
    o_rows, c_rows = read_zone(orig_path, o_off), read_zone(our_path, c_off)
    if len(o_rows) != len(c_rows):
        return [Row(label, "-", note="%d particles in the original's frame, %d in mpm3d's"
                    % (len(o_rows), len(c_rows)))]
    rows = []
    for shown, o_name, c_name in match_columns(["-"] + o_names, ["-"] + c_names):
        if c_name is None:
            rows.append(Row(label, shown, note="not in mpm3d's file"))
            continue
        i, j = o_names.index(o_name), c_names.index(c_name)
        o_vals = [r[i] if i < len(r) else math.nan for r in o_rows]
        c_vals = [r[j] if j < len(r) else math.nan for r in c_rows]
        scale = max((abs(v) for v in o_vals if math.isfinite(v)), default=0.0)
        diff = largest([abs(a - b) for a, b in zip(o_vals, c_vals)])
        rows.append(Row(label, shown, relative(diff, scale), None))
        rows[-1].cut, rows[-1].exit_diff = until is not None, rows[-1].max_diff
    return rows
