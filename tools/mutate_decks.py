#!/usr/bin/env python3
"""Hand-mutated decks: generate them (deterministic seed) and check how mpm3d answers.

    tools/mutate_decks.py --mpm3d build/cxx/mpm3d --work DIR [--ref build/fortran_ref/mpm3d_ref]
    tools/mutate_decks.py --list            # print the mutations only
    tools/mutate_decks.py --mpm3d EXE [--ref EXE] --refused DECK...   # regression decks

From the repository's small decks (tests/decks, fortran_ref/testdecks, inputs/impact,
inputs/taylor/taylor_coarse.mpm) the script derives, with random.Random(SEED), decks of
these classes: a token replaced by garbage, a line dropped, duplicated, two lines swapped,
the deck truncated, binary bytes inserted, an over-long line (> 256 characters), a number
out of range (negative, zero, NaN/Inf text, huge, tiny), a keyword misspelled, and a few
targeted holes (grid hi < lo, a load on a particle not yet defined, huge particle counts
and grids). Each deck runs as `mpm3d --steps 2 --no-output --quiet --threads 1 DECK` in
an empty directory and is classified:

  accepted   exit 0, stderr empty or only `mpm3d: warning:` lines
  refused    exit 1, exactly one stderr line `mpm3d: DECK:LINE: problem`, LINE within the
             deck, and nothing written in the directory
  health     exit 3, exactly one stderr line `mpm3d: numerical ...`

Anything else (a signal, another exit status, several lines, no line number, more than
TIMEOUT seconds) is a failure: the script prints the deck and the answer, exits 1.
With --refused, the given decks (tests/fuzz_regressions) are run instead and each must be
refused (exit 1, one `mpm3d: DECK:LINE: problem` line). With --ref, the Fortran reference reader runs each deck too and must not crash (exit 0, 1
or 3, no signal; its message is its own).
"""
import argparse
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
from collections import Counter, defaultdict

SEED = 20261121
PER_CLASS = {  # mutations per class (per deck where noted in generate())
    "garbage-token": 24, "drop-line": 20, "duplicate-line": 16, "swap-lines": 16,
    "truncate": 16, "binary-bytes": 12, "long-line": 8, "number-out-of-range": 36,
    "misspelled-keyword": 16,
}
TIMEOUT = 60
REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SOURCES = ["tests/decks/small.mpm", "tests/decks/layout_a.mpm", "tests/decks/layout_b.mpm",
           "tests/decks/mixed_thermal.mpm", "fortran_ref/testdecks/quirks.mpm",
           "fortran_ref/testdecks/musl_sjcf.mpm", "fortran_ref/testdecks/usf_john.mpm",
           "fortran_ref/testdecks/usl_blocks.mpm", "inputs/impact/two_blocks.mpm",
           "inputs/taylor/taylor_coarse.mpm"]
GARBAGE = ["xyz", "1.2.3", "1e", "--5", "@@", "0x10", "1.0-3", "+", ".", "e5", "1,5", "nan(0)",
           "\u00e9t\u00e9", "'1.0'", "1d+", "TRUE", "*", "99999999999999999999999", "1..2", "--"]
NUMBERS = ["-1", "0", "-0", "0.0", "NaN", "nan", "Inf", "-Infinity", "1e308", "1e309", "-1e309",
           "1e-320", "4.9e-324", "99999999999", "2147483648", "-2147483649", "1e12", "1000000000000",
           "1.0d300", "-1.0D300", "1e-300", "123456789012345678", "1234567890123456789012", "7.5"]
KEYWORDS = ["nbmp", "nbbo", "nmat", "nbco", "spx", "spy", "spz", "grid", "dcel", "dtsc", "endt",
            "outt", "rptt", "fixe", "mate", "part", "velo", "endv", "load", "endl", "seos", "outr",
            "curv", "curx", "endi", "musl", "usf", "usl", "jaum", "tecp", "para", "pt2d", "bloc",
            "sphe", "poin", "cyli", "node", "body", "grav", "elas", "pla1", "pla2", "john", "jcf",
            "sjc", "sjcf"]

NUM_RE = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eEdD][+-]?\d+)?$")


def tokens_of(line):
    """(start, end) of each blank/comma separated token before a '!' comment."""
    out, i, n = [], 0, len(line)
    cut = line.find("!")
    if cut >= 0:
        n = cut
    while i < n:
        if line[i] in " \t,":
            i += 1
            continue
        j = i
        while j < n and line[j] not in " \t,":
            j += 1
        out.append((i, j))
        i = j
    return out


def replace_token(lines, rng, pick, new):
    """Replaces a token chosen by pick(text) -> bool with new (str or callable)."""
    cands = [(li, s, e) for li, l in enumerate(lines) for (s, e) in tokens_of(l)
             if li > 0 and pick(l[s:e])]
    if not cands:
        return None
    li, s, e = rng.choice(cands)
    l = lines[li]
    repl = new(l[s:e]) if callable(new) else new
    out = list(lines)
    out[li] = l[:s] + repl + l[e:]
    return out, li + 1


def misspell(word, rng):
    w = list(word)
    k = rng.randrange(min(4, len(w)))
    choices = [c for c in "abcdefghijklmnopqrstuvwxyz0_" if c != w[k].lower()]
    w[k] = rng.choice(choices)
    return "".join(w)


def mutate(cls, text, rng):
    """Returns (mutated bytes, description) or None when the class does not apply."""
    lines = text.split("\n")
    if cls == "garbage-token":
        g = rng.choice(GARBAGE)
        r = replace_token(lines, rng, lambda t: True, g)
        return r and ("\n".join(r[0]).encode(), f"line {r[1]}: a token -> {g!r}")
    if cls == "drop-line":
        i = rng.randrange(len(lines))
        return "\n".join(lines[:i] + lines[i + 1:]).encode(), f"line {i + 1} dropped"
    if cls == "duplicate-line":
        i = rng.randrange(len(lines))
        return "\n".join(lines[:i + 1] + [lines[i]] + lines[i + 1:]).encode(), f"line {i + 1} duplicated"
    if cls == "swap-lines":
        i, j = sorted(rng.sample(range(len(lines)), 2))
        out = list(lines)
        out[i], out[j] = out[j], out[i]
        return "\n".join(out).encode(), f"lines {i + 1} and {j + 1} swapped"
    if cls == "truncate":
        raw = text.encode()
        k = rng.randrange(len(raw))
        return raw[:k], f"truncated after byte {k}"
    if cls == "binary-bytes":
        raw = bytearray(text.encode())
        k = rng.randrange(len(raw))
        junk = bytes(rng.choice([0, 1, 7, 8, 12, 27, 127, 128, 200, 255, 0xC3]) for _ in range(rng.randint(1, 4)))
        return bytes(raw[:k] + junk + raw[k:]), f"bytes {junk.hex()} at byte {k}"
    if cls == "long-line":
        i = rng.randrange(1, len(lines))
        n = rng.choice([257, 300, 1000, 70000])
        fill = rng.choice([" ", "0", "1.0 ", "!"])
        out = list(lines)
        out[i] = (out[i] + fill * n)[:max(n, len(out[i]) + 1)]
        return "\n".join(out).encode(), f"line {i + 1} made {len(out[i])} characters long"
    if cls == "number-out-of-range":
        v = rng.choice(NUMBERS)
        r = replace_token(lines, rng, lambda t: bool(NUM_RE.match(t)), v)
        return r and ("\n".join(r[0]).encode(), f"line {r[1]}: a number -> {v}")
    if cls == "misspelled-keyword":
        r = replace_token(lines, rng, lambda t: t[:4].lower() in KEYWORDS and not NUM_RE.match(t),
                          lambda t: misspell(t, rng))
        return r and ("\n".join(r[0]).encode(), f"line {r[1]}: a keyword misspelled")
    raise ValueError(cls)


SMALL = """mpm3d *** targeted: {what}
nbmp {nbmp}
nbbo 1
nmat 1
{box}
dcel {dcel}
endt 1.0
mate
1 elas 1.0 100.0 0.25
{part}
{extra}
endi
"""


def targeted():
    """Known holes and resource bombs: (deck, what, the text of the line the error must name)."""
    base = dict(nbmp=8, box="spx 0 4\nspy 0 4\nspz 0 4", dcel="1.0",
                part="part bloc 1 1 1.0 0.5 1 1 1 2 2 2", extra="")

    def deck(what, at=None, **kw):
        text = SMALL.format(**dict(base, what=what, **kw))
        line = None
        if at is not None:
            line = 1 + next(i for i, l in enumerate(text.split("\n")) if i > 0 and at in l)
        return text.encode(), what, line

    return [
        deck("grid card with hi < lo", "grid", box="grid 0 4 4 0 0 4"),
        deck("grid card with hi = lo", "grid", box="grid 0 4 0 4 2 2"),
        deck("load node on a particle not yet defined", "node 3",
             part="load\nnode 3 1 0 0\nendl\npart bloc 1 1 1.0 0.5 1 1 1 2 2 2"),
        deck("velo node on a particle not yet defined", "node 3",
             part="velo\nnode 3 1 0 0\nendv\npart bloc 1 1 1.0 0.5 1 1 1 2 2 2"),
        deck("1e12 particles", "nbmp", nbmp="1000000000000"),
        # Refused at nbmp where 2e8 x 256 bytes exceed the memory, else at endi (8 particles
        # defined): the arrays grow with the particles, nothing is allocated for nbmp.
        deck("nbmp 2e8 (the hard limit) with 8 particles", None, nbmp="200000000"),
        deck("a block of 1e15 particles", "part", part="part bloc 1 1 1.0 0.5 1 1 1 100000 100000 100000"),
        deck("a sphere far larger than nbmp", "part", part="part sphe 1 1 1.0 0.5 2 2 2 10000"),
        deck("a cylinder far larger than nbmp", "part", part="part cyli 1 1 1.0 1e-5 2 2 0 1 3"),
        deck("a cylinder thinner than half a spacing", "part", part="part cyli 1 1 1.0 0.5 2 2 0 1 0.1"),
        deck("a huge grid", None, box="spx 0 1e6\nspy 0 1e6\nspz 0 1e6"),
        deck("a grid of 1e-300 cells", "dcel", dcel="1e-300"),
        deck("a box shorter than half a cell", "dcel", dcel="100"),
        deck("spacing 1e-200 (zero volume)", "part", part="part bloc 1 1 1.0 1e-200 1 1 1 2 2 2"),
        deck("spacing 1e200 (infinite volume)", "part", part="part bloc 1 1 1.0 1e200 1 1 1 2 2 2"),
        deck("block origin 1e308 (infinite positions)", "part", part="part bloc 1 1 1.0 0.5 1e308 1 1 2 2 2"),
        deck("Young's modulus 1e308 (infinite wave speed)", "1e308",
             extra="mate\n1 elas 1e-300 1e308 0.25"),
        (b"mpm3d *** t\nnbmp 1\nnbbo 1\nnmat 0\nendi\n", "nmat 0", 4),
    ]


def generate(sources):
    rng = random.Random(SEED)
    out = []  # (class, name, bytes, description, expected line or None)
    texts = {s: open(os.path.join(REPO, s), encoding="latin-1").read() for s in sources}
    for cls, n in PER_CLASS.items():
        made = 0
        while made < n:
            src = sources[made % len(sources)]
            r = mutate(cls, texts[src], rng)
            if r is None:
                continue
            data, desc = r
            out.append((cls, f"{cls}-{made:03d}.mpm", data, f"{src}: {desc}", None))
            made += 1
    for i, (data, what, line) in enumerate(targeted()):
        out.append(("targeted", f"targeted-{i:03d}.mpm", data, what, line))
    return out


def classify(rc, err_lines, deck_path, nlines, wrote, expect_line):
    if rc == 0:
        if all(l.startswith("mpm3d: warning:") for l in err_lines):
            return "accepted", None
        return None, "exit 0 with unexpected stderr"
    if rc == 1:
        if len(err_lines) != 1:
            return None, f"exit 1 with {len(err_lines)} stderr lines"
        m = re.match(r"^mpm3d: " + re.escape(deck_path) + r":(\d+): \S", err_lines[0])
        if not m:
            return None, "exit 1 without a 'mpm3d: FILE:LINE: problem' line"
        line = int(m.group(1))
        if not 1 <= line <= nlines:
            return None, f"line {line} outside the deck (1..{nlines})"
        if expect_line is not None and line != expect_line:
            return None, f"line {line}, expected {expect_line}"
        if wrote:
            return None, "refused, but wrote " + ", ".join(wrote)
        return "refused", None
    if rc == 3:
        if len(err_lines) == 1 and err_lines[0].startswith("mpm3d: numerical"):
            return "health", None
        return None, "exit 3 without one 'numerical ...' line"
    return None, f"exit status {rc}" + (f" (signal {-rc})" if rc < 0 else "")


def run_one(exe, deck_path, cwd, extra):
    try:
        p = subprocess.run([exe] + extra + [deck_path], cwd=cwd, capture_output=True, timeout=TIMEOUT,
                           env=dict(os.environ, OMP_NUM_THREADS="1"))
        return p.returncode, p.stderr.decode("latin-1").splitlines()
    except subprocess.TimeoutExpired:
        return "timeout", []


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mpm3d")
    ap.add_argument("--ref", help="mpm3d_ref: run each deck through the Fortran reader too")
    ap.add_argument("--work", help="directory for the decks (default: a temporary one)")
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--keep", action="store_true", help="keep the decks")
    ap.add_argument("--verbose", "-v", action="store_true", help="one line per deck")
    ap.add_argument("--refused", nargs="+", metavar="DECK", help="check that these decks are refused")
    a = ap.parse_args()
    if a.refused:
        decks = [("regression", os.path.basename(d), open(d, "rb").read(), d, None) for d in sorted(a.refused)]
    else:
        decks = generate(SOURCES)
    if a.list:
        for cls, name, data, desc, _ in decks:
            print(f"{name:28s} {desc}")
        print(f"{len(decks)} decks")
        return 0
    if not a.mpm3d:
        ap.error("--mpm3d is required")
    exe = os.path.abspath(a.mpm3d)
    ref = os.path.abspath(a.ref) if a.ref else None
    work = a.work or tempfile.mkdtemp(prefix="mpm3d-mutants-")
    if os.path.isdir(work):
        shutil.rmtree(work)
    os.makedirs(work)
    counts = defaultdict(Counter)
    failures = []
    for cls, name, data, desc, expect_line in decks:
        deck_path = os.path.join(work, name)
        with open(deck_path, "wb") as f:
            f.write(data)
        nlines = data.count(b"\n") + 1
        run_dir = os.path.join(work, "run-" + name)
        os.makedirs(run_dir)
        rc, err = run_one(exe, deck_path, run_dir, ["--steps", "2", "--no-output", "--quiet", "--threads", "1"])
        wrote = sorted(os.listdir(run_dir))
        if rc == "timeout":
            outcome, why = None, f"no answer within {TIMEOUT} s"
        else:
            outcome, why = classify(rc, err, deck_path, nlines, wrote, expect_line)
        if a.refused and outcome not in (None, "refused"):
            outcome, why = None, f"{outcome}, expected refused"
        if outcome is None:
            failures.append((name, desc, why, err[:5]))
            outcome = "FAILED"
        counts[cls][outcome] += 1
        if a.verbose:
            print(f"{name:28s} {outcome:9s} {desc}: {err[0][:200] if err else ''}")
        if ref:
            ref_dir = os.path.join(work, "ref-" + name)
            os.makedirs(ref_dir)
            rrc, rerr = run_one(ref, deck_path, ref_dir, ["--steps", "2"])
            if rrc not in (0, 1, 3) or any("Sanitizer" in l or "runtime error" in l for l in rerr):
                failures.append((name, desc, f"mpm3d_ref: exit {rrc}", rerr[-5:]))
                counts[cls]["fortran FAILED"] += 1
            else:
                counts[cls][f"fortran exit {rrc}"] += 1
            shutil.rmtree(ref_dir, ignore_errors=True)
        shutil.rmtree(run_dir, ignore_errors=True)
    total = Counter()
    print(f"{'class':22s} {'decks':>5s}  outcomes")
    for cls in (["regression"] if a.refused else list(PER_CLASS) + ["targeted"]):
        c = counts[cls]
        n = sum(v for k, v in c.items() if not k.startswith("fortran"))
        total.update(c)
        print(f"{cls:22s} {n:5d}  " + ", ".join(f"{k} {v}" for k, v in sorted(c.items())))
    n = sum(v for k, v in total.items() if not k.startswith("fortran"))
    print(f"{'all':22s} {n:5d}  " + ", ".join(f"{k} {v}" for k, v in sorted(total.items())))
    for name, desc, why, err in failures:
        print(f"FAILED {name} ({desc}): {why}")
        for l in err:
            print(f"    {l[:300]}")
    if not a.keep and not a.work:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
