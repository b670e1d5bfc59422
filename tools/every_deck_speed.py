#!/usr/bin/env python3
"""Speed on every public deck: mpm3d against the original program that reads it, side by side.

usage: tools/every_deck_speed.py BUILD_DIR --repo MPM3D_F90 --book EXE --current EXE
                                 [--threads 1,2] [--rounds 3] [--target 4] [--only NAME[,NAME...]]
                                 [--csv docs/bench/every_deck.csv] [--doc docs/PERFORMANCE.md]
                                 [--newest EXE [--newest-decks DIR]]

The decks and originals are those of tools/public_decks.py (31 runs: the 26 readable decks of
the current version against the current program, the five book decks also against the book
program; with --newest also the newest program's six, 37 runs: its R1 dam breaks and the three
3D landslides written by its make_landslide_decks.py); the programs are built outside this
repository (see that tool). Each deck is cut so
that the original runs about TARGET seconds: its end time is set to the time mpm3d reaches at
step K, K scaled from a run of the original to mpm3d's time at step 50 and checked once more
(the current program computes its time step every step, so its steps may differ from ours),
and its TecPlot and ParaView animation cards (`tecp`, `para`) are taken out, so that neither
program writes animation frames, and so is `QuLo` (its load ramp's run-on rule carries both
programs past the end time to t = 100). Both programs read the same cut deck and write what it asks
(energies, curves).

Each round runs the original (serial, as it is built) and mpm3d once at each thread count, one
after the other, the order reversed every other round; every figure is the whole process's
wall time and peak resident memory (wait4); the original and the one-thread run of a round on
the same CPU (`taskset`, CPU 0 and CPU 1 in turn). Per deck and thread count the ratio is the median
of the per-round ratios original / mpm3d: this machine is noisy, and a ratio of two runs
seconds apart is what it can measure. Writes the rows to --csv and the table between the
EVERY_DECK markers of --doc.

With 1 and 2 threads in --threads, each round also measures what the machine's two cores
deliver on that deck (issue 56 scales its 2-thread floor with it): two one-thread runs of
mpm3d at once, pinned to CPUs 0 and 1 (`taskset`), capacity = t1/ta + t1/tb with t1 the
round's one-thread run alone (2.0 where the cores do not slow each other). The floors:
4x serially (`Taylor.mpm` against the book program 5x), and at 2 threads 6x times
min(1, capacity / 1.9), capacity the deck's median.
"""
import argparse
import csv
import datetime
import importlib.util
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BEGIN, END = "<!-- EVERY_DECK begin -->", "<!-- EVERY_DECK end -->"

_spec = importlib.util.spec_from_file_location("public_decks", os.path.join(HERE, "public_decks.py"))
public = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(public)

PROBE_STEPS = 50


def cut_deck(src, end_time, path):
    """The deck with its end time set (None: kept), its animation cards and QuLo taken out."""
    with open(src, errors="replace") as f:
        lines = f.readlines()
    with open(path, "w") as f:
        for line in lines:
            key = line.split()[0].lower()[:4] if line.split() else ""
            if key in ("tecp", "para"):
                continue
            if key == "qulo":  # its run-on rule carries both programs on to t = 100
                continue
            if key == "endt" and end_time is not None:
                line = "endtime %.9g\n" % end_time
            f.write(line)


def timed(cmd, cwd):
    """(exit status, wall seconds, peak resident bytes) of cmd, its output in cwd/run.log.
    The peak comes from GNU time (Debian's `time` package): a child forked from this script
    would report the script's own resident size where the program's is smaller."""
    peak_file = os.path.join(cwd, "peak.txt")
    wrap = ["/usr/bin/time", "-f", "%M", "-o", peak_file] if os.path.exists("/usr/bin/time") else []
    with open(os.path.join(cwd, "run.log"), "w") as log:
        t0 = time.perf_counter()
        rc = subprocess.run(wrap + cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=log,
                            stderr=subprocess.STDOUT).returncode
        wall = time.perf_counter() - t0
    peak = 0
    if wrap and os.path.exists(peak_file):
        with open(peak_file) as f:
            lines = [l for l in f.read().split() if l.isdigit()]
        peak = int(lines[-1]) * 1024 if lines else 0
    return rc, wall, peak


def fresh(work, deck):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    shutil.copy(deck, work)
    return os.path.basename(deck)


def pinned(cpu):
    """The command prefix that keeps a run on one CPU (none without taskset or a CPU)."""
    return ["taskset", "-c", str(cpu)] if cpu is not None and shutil.which("taskset") else []


def run_original(exe, deck, work, cpu=None):
    name = fresh(work, deck)
    return timed(pinned(cpu) + [exe, name], work)


def run_mpm3d(exe, deck, threads, work, steps=None, cpu=None):
    name = fresh(work, deck)
    cmd = pinned(cpu) + [exe, "--threads", str(threads), "--quiet", "--out-dir", ".", "--summary", "summary.json"]
    if steps:
        cmd += ["--no-output", "--steps", str(steps)]
    rc, wall, peak = timed(cmd + [name], work)
    info = {}
    if rc == 0:
        with open(os.path.join(work, "summary.json")) as f:
            info = json.load(f)
    return rc, wall, peak, info


def run_pair(exe, deck, tmp):
    """Wall seconds of two one-thread mpm3d runs of deck started together, pinned to CPUs 0 and
    1 where taskset is there; None if one failed."""
    procs = []
    for cpu in (0, 1):
        work = os.path.join(tmp, "pair%d" % cpu)
        name = fresh(work, deck)
        cmd = pinned(cpu) + [exe, "--threads", "1", "--quiet", "--out-dir", ".", name]
        procs.append((subprocess.Popen(cmd, cwd=work, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                       stderr=subprocess.DEVNULL), time.perf_counter()))
    walls = [None, None]
    while None in walls:
        for i, (proc, t0) in enumerate(procs):
            if walls[i] is None and proc.poll() is not None:
                walls[i] = time.perf_counter() - t0
        time.sleep(0.002)
    return None if any(proc.returncode != 0 for proc, _ in procs) else walls


def floor_2(capacity):
    """Issue 56's 2-thread floor on a machine whose two cores deliver `capacity` times one."""
    return 6.0 * min(1.0, capacity / 1.9)


def full_end_time(deck):
    with open(deck, errors="replace") as f:
        for line in f:
            w = line.split()
            if w and w[0].lower()[:4] == "endt":  # a comment may follow the number without a space
                return float(w[1].split("!")[0].replace("d", "e").replace("D", "e"))
    return None


def measure(name, src, exe_orig, mpm3d, threads, rounds, target, tmp):
    """One deck's rows, or a refusal."""
    work = os.path.join(tmp, "run")
    deck = os.path.join(tmp, os.path.basename(src))
    end_full = full_end_time(src)
    # Probe: the time mpm3d reaches at PROBE_STEPS, and how long the original takes to get
    # there; then step K scaled from it, checked once more (the programs' time steps may
    # differ: the current one computes it every step).
    uncut = os.path.join(tmp, "probe_" + os.path.basename(src))
    cut_deck(src, None, uncut)
    steps, end = PROBE_STEPS, None
    for attempt in range(3):
        rc, _, _, info = run_mpm3d(mpm3d, uncut, 1, work, steps)
        if rc != 0:
            return {"refused": "mpm3d: " + open(os.path.join(work, "run.log"), errors="replace").read().strip()[-200:]}
        end = min(info["time"], end_full) if end_full else info["time"]
        cut_deck(src, end, deck)
        if attempt == 2 or end == end_full:
            break
        rc, wall, _ = run_original(exe_orig, deck, work)
        if rc != 0:
            return {"refused": "the original: exit %d" % rc}
        if attempt > 0 and target / 1.5 < wall < target * 1.5:
            break
        steps = max(PROBE_STEPS, int(steps * target / max(wall, 1e-3)))
    orig, ours = [], {t: [] for t in threads}
    ratio = {t: [] for t in threads}
    peak = {t: 0 for t in threads}
    peak_orig, particles, our_steps = 0, None, None
    pairs = 1 in threads and 2 in threads and (os.cpu_count() or 1) >= 2
    capacity = []
    for r in range(rounds):
        order = ["orig"] + threads if r % 2 == 0 else threads[::-1] + ["orig"]
        # The serial runs of a round share one CPU, the other one in the next round: the
        # two vCPUs of the 2-core VM have run one program at up to 1.45 times the other's speed.
        cpu = r % 2 if (os.cpu_count() or 1) >= 2 else None
        walls = {}
        for who in order:
            if who == "orig":
                rc, walls[who], pk = run_original(exe_orig, deck, work, cpu)
                if rc != 0:
                    return {"refused": "the original: exit %d" % rc}
                peak_orig = max(peak_orig, pk)
            else:
                rc, walls[who], pk, info = run_mpm3d(mpm3d, deck, who, work, cpu=cpu if who == 1 else None)
                if rc != 0:
                    return {"refused": "mpm3d: exit %d" % rc}
                peak[who] = max(peak[who], pk)
                particles, our_steps = info["particles"], info["steps"]
        if pairs:
            pair = run_pair(mpm3d, deck, tmp)
            if pair is None:
                return {"refused": "mpm3d: a run of the pair failed"}
            capacity.append(walls[1] / pair[0] + walls[1] / pair[1])
        orig.append(walls["orig"])
        for t in threads:
            ours[t].append(walls[t])
            ratio[t].append(walls["orig"] / walls[t])
    return {"end_time": end, "particles": particles, "steps": our_steps,
            "orig_s": statistics.median(orig), "peak_orig": peak_orig,
            "ours_s": {t: statistics.median(ours[t]) for t in threads},
            "ratio": {t: statistics.median(ratio[t]) for t in threads},
            "ratio_range": {t: (min(ratio[t]), max(ratio[t])) for t in threads},
            "peak": peak, "capacity": statistics.median(capacity) if capacity else None}


def serial_floor(r):
    return 5.0 if r["name"] == "Taylor" and r["program"] == "book" else 4.0


def floors_met(results):
    """(runs measured, at the serial floor, at the 2-thread floor or None) over the results."""
    done = [r for r in results if "refused" not in r]
    serial = sum(1 for r in done if r["ratio"].get(1, 0.0) >= serial_floor(r))
    two = None
    if all(r.get("capacity") and 2 in r["ratio"] for r in done) and done:
        two = sum(1 for r in done if r["ratio"][2] >= floor_2(r["capacity"]))
    return len(done), serial, two


def table(results, threads, rounds, target, when):
    t_hdr = " | ".join(f"{t} thr" for t in threads)
    with_capacity = any(r.get("capacity") for r in results)
    out = [BEGIN, f"`tools/every_deck_speed.py` ({'make bench'} with the originals given), {when}, "
           f"{platform.machine()}, {os.cpu_count()} cores: every public deck cut so that the original runs "
           f"about {target:g} s, whole process, wall time; the ratio original / mpm3d is the median of "
           f"{rounds} interleaved rounds (range in brackets). Book decks against the book program, "
           "current decks against the current program, the newest decks against the newest program, all "
           "gfortran 12 `-O2`, serial. Memory: mpm3d's "
           "peak resident bytes per particle at the highest thread count (the original's in brackets)."
           + (" Capacity: what the two cores deliver on the deck, two one-thread runs at once (2.0: no "
              "slowing), the median over the rounds; a ratio in bold meets issue 56's floor (4x serially, "
              "`Taylor.mpm` against the book program 5x; at 2 threads 6x times min(1, capacity / 1.9))."
              if with_capacity else ""), "",
           f"| deck | program | particles | steps | original s | {t_hdr} | "
           + ("capacity | " if with_capacity else "") + "bytes/particle |",
           "|---|---|---|---|---|" + "---|" * len(threads) + ("---|" if with_capacity else "") + "---|"]
    for r in results:
        if "refused" in r:
            out.append(f"| {r['name']} | {r['program']} | - | - | - | " + " | ".join("-" for _ in threads)
                       + (" | -" if with_capacity else "") + f" | refused: {r['refused']} |")
            continue

        def cell(t):
            text = "%.2fx (%.2f-%.2f)" % ((r["ratio"][t],) + r["ratio_range"][t])
            floor = serial_floor(r) if t == 1 else (floor_2(r["capacity"]) if t == 2 and r.get("capacity") else None)
            return f"**{text}**" if floor is not None and r["ratio"][t] >= floor else text

        cells = " | ".join(cell(t) for t in threads)
        cap = ("%.2f | " % r["capacity"] if r.get("capacity") else "- | ") if with_capacity else ""
        tmax = threads[-1]
        out.append(f"| {r['name']} | {r['program']} | {r['particles']} | {r['steps']} | {r['orig_s']:.2f} | "
                   f"{cells} | {cap}{r['peak'][tmax] / r['particles']:.0f} ({r['peak_orig'] / r['particles']:.0f}) |")
    n, serial, two = floors_met(results)
    if with_capacity:
        out += ["", f"Floors met: serially {serial} of {n} runs" + ("" if two is None else f", at 2 threads {two} of {n}")
                + "."]
    out.append(END)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    public.add_program_args(ap)
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--target", type=float, default=4.0, help="seconds the original should run")
    ap.add_argument("--only", default="", help="only the decks whose names contain one of these")
    ap.add_argument("--csv", default=os.path.join(ROOT, "docs", "bench", "every_deck.csv"))
    ap.add_argument("--doc", default=os.path.join(ROOT, "docs", "PERFORMANCE.md"))
    ap.add_argument("--newest", help="the newest program (commit 17fd4ee): also its six decks (37 runs)")
    ap.add_argument("--newest-decks", default=os.path.join(ROOT, "..", "shared", "decks", "newest"),
                    help="the newest decks (the R1 dam breaks and make_landslide_decks.py)")
    a = ap.parse_args()
    mpm3d = os.path.join(os.path.abspath(a.build), "cxx", "mpm3d")
    threads = [int(t) for t in a.threads.split(",")]
    wanted = [w for w in a.only.split(",") if w]
    results = []
    print(f"every_deck_speed: load before: {open('/proc/loadavg').read().split()[0]}", flush=True)
    todo = list(public.DECKS)
    landslides = tempfile.TemporaryDirectory()
    if a.newest:  # each deck is cut by the target below, so the list's end times are not used
        todo += [(name, rel, "newest", None) for name, rel, _ in public.NEWEST_DECKS]
        subprocess.run([sys.executable, os.path.join(a.newest_decks, "make_landslide_decks.py"), landslides.name],
                       check=True, stdout=subprocess.DEVNULL)
    for name, rel, which, _ in todo:
        if wanted and not any(w in name for w in wanted):
            continue
        if which == "newest":
            src = os.path.join(landslides.name if rel in public.LANDSLIDES else a.newest_decks, rel)
        else:
            src = os.path.join(a.repo, rel)
        if not os.path.exists(src):
            print(f"every_deck_speed: {src} not found: skipped", file=sys.stderr)
            continue
        exe = os.path.abspath({"book": a.book, "current": a.current, "newest": a.newest or ""}[which])
        with tempfile.TemporaryDirectory() as tmp:
            r = measure(name, src, exe, mpm3d, threads, a.rounds, a.target, tmp)
        r.update(name=name, program=which)
        results.append(r)
        if "refused" in r:
            print(f"every_deck_speed: {name}: refused: {r['refused']}", flush=True)
        else:
            print(f"every_deck_speed: {name}: original {r['orig_s']:.2f} s, "
                  + ", ".join("%d thr %.2fx" % (t, r["ratio"][t]) for t in threads)
                  + (", capacity %.2f" % r["capacity"] if r.get("capacity") else ""), flush=True)
    os.makedirs(os.path.dirname(a.csv), exist_ok=True)
    with open(a.csv, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["deck", "program", "particles", "steps", "end_time", "original_s"]
                   + [f"mpm3d_s_{t}" for t in threads] + [f"ratio_{t}" for t in threads]
                   + [f"ratio_min_{t}" for t in threads] + [f"ratio_max_{t}" for t in threads]
                   + ["peak_bytes_original"] + [f"peak_bytes_{t}" for t in threads] + ["capacity"])
        for r in results:
            if "refused" in r:
                w.writerow([r["name"], r["program"], "refused: " + r["refused"]])
                continue
            w.writerow([r["name"], r["program"], r["particles"], r["steps"], "%.6g" % r["end_time"],
                        "%.3f" % r["orig_s"]] + ["%.3f" % r["ours_s"][t] for t in threads]
                       + ["%.3f" % r["ratio"][t] for t in threads]
                       + ["%.3f" % r["ratio_range"][t][0] for t in threads]
                       + ["%.3f" % r["ratio_range"][t][1] for t in threads]
                       + [r["peak_orig"]] + [r["peak"][t] for t in threads]
                       + ["%.3f" % r["capacity"] if r.get("capacity") else ""])
    when = datetime.datetime.utcnow().strftime("%Y-%m-%d")
    if not wanted:
        public.write(a.doc, table(results, threads, a.rounds, a.target, when), BEGIN, END)
    n, serial, two = floors_met(results)
    print(f"every_deck_speed: floors met: serially {serial} of {n}"
          + ("" if two is None else f", at 2 threads {two} of {n}"))
    print(f"every_deck_speed: wrote {a.csv}" + ("" if wanted else f" and the table in {a.doc}"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
