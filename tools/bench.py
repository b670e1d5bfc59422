#!/usr/bin/env python3
"""make bench (through tools/bench.sh): the C++ solver's speed, thread scaling and memory.

For every deck, adaptive grid (off, on) and thread
count (1, 2, 4, ... up to the machine's cores, and the core count itself), the best of
BENCH_REPEATS runs of `mpm3d --steps BENCH_STEPS --no-output`: ns per particle-step (the
step loop alone, from the summary), speedup and efficiency against 1 thread of the same
configuration, bytes per particle (peak resident memory from /usr/bin/time -v divided by
the particles), the share of each stage (stage_seconds in the summary), the patch
statistics, and the 1-minute load average before the run.

Without the adaptive grid the runs go in BENCH_ROUNDS rounds instead:
each round runs 1 thread pinned to each CPU in turn (taskset), then every thread count
once, so that a round's figures are seconds apart. The 1-thread time is then the best of
all unpinned and pinned runs (on a virtual machine whose CPUs run at different speeds, an
unpinned run may land on the slow one and flatter the speedup). `capacity` is the sum over
the CPUs of (1-thread time / best time pinned to that CPU), the speedup the CPUs could give
if every one ran as fast as it does alone (2.0 on two equal, idle cores; less when the
virtual machine's CPUs run at different speeds), and `capacity_efficiency` the speedup at
the full core count divided by it. As these best-of figures may come from different
minutes, each round also gives its own speedup at the full core count (over the round's
fastest pinned 1-thread run) and that speedup over the round's own capacity:
`round_speedup` and `round_capacity_efficiency` are their medians over the rounds.
Timings on a loaded machine are not worth much: compare rows measured side by side, and
rerun on a quiet machine.

usage: bench.py BUILD_DIR CSV [max_threads] [deck ...]
Also, per deck, the thread team's loops a step and the step's time outside them on 2 threads
against its time on 1 (regions.csv beside CSV; the summary's team.regions and
team.seconds_in_regions).

environment: BENCH_STEPS (default 100), BENCH_REPEATS (3), BENCH_ROUNDS (5), BENCH_REGRID (20),
             BENCH_FINE=1 adds taylor_fine.mpm
"""
import csv
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

STAGES = ["bin", "p2g", "forces", "integrate", "g2p", "stress", "energy"]


def load1():
    with open("/proc/loadavg") as f:
        return float(f.read().split()[0])


def run_once(exe, deck, threads, steps, regrid, tmp, cpu=None):
    summary = os.path.join(tmp, "s.json")
    pin = ["taskset", "-c", str(cpu)] if cpu is not None else []
    cmd = ["/usr/bin/time", "-v"] + pin + [exe, "--threads", str(threads), "--steps", str(steps), "--no-output",
           "--quiet", "--summary", summary, "--regrid-every", str(regrid), deck]
    load = load1()
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit(f"bench: {' '.join(cmd)} failed:\n{p.stderr}")
    rss_kb = 0
    for line in p.stderr.splitlines():
        if "Maximum resident set size" in line:
            rss_kb = int(line.split()[-1])
    with open(summary) as f:
        s = json.load(f)
    return s, rss_kb * 1024, load


def regions_once(exe, deck, steps, tmp):
    """The team's loops of the step loop on 2 threads, every step on both (--team fixed), the
    set-up's left out (the summary's team.regions and team.seconds_in_regions): (summary of the
    run, loops, seconds inside them)."""
    summary = os.path.join(tmp, "r.json")

    def counted(n):
        subprocess.run([exe, "--threads", "2", "--team", "fixed", "--steps", str(n), "--no-output", "--quiet",
                        "--summary", summary, deck], check=True)
        with open(summary) as f:
            s = json.load(f)
        return s, s["team"]["regions"], s["team"]["seconds_in_regions"]

    _, setup, setup_inside = counted(0)
    s, regions, inside = counted(steps)
    return s, regions - setup, inside - setup_inside


def serial_profile(exe, deck, steps, repeats, tmp):
    """The team's loops per step and the step's time outside them on 2 threads (the best of
    the repeats), against the step's time on 1 thread, with the speedup that serial part
    alone would allow at 8 and 16 threads."""
    best = None
    for _ in range(repeats):
        s, regions, inside = regions_once(exe, deck, steps, tmp)
        step_s = s["ns_per_particle_step"] * 1e-9 * s["particles"] * steps
        serial = max(0.0, step_s - inside)
        if best is None or serial < best[1]:
            best = (s, serial, regions)
    s, serial, regions = best
    one = run_once(exe, deck, 1, steps, 0, tmp)[0]
    step_s = one["ns_per_particle_step"] * 1e-9 * one["particles"] * steps
    f = min(1.0, serial / step_s)
    row = {"deck": os.path.basename(deck), "particles": s["particles"], "steps": steps,
           "regions_per_step": f"{regions / steps:g}", "step_us_1thread": f"{1e6 * step_s / steps:.1f}",
           "serial_us_per_step": f"{1e6 * serial / steps:.2f}", "serial_fraction": f"{f:.5f}"}
    for t in (8, 16):
        sp = 1.0 / (f + (1.0 - f) / t)
        row[f"amdahl_speedup_{t}"] = f"{sp:.2f}"
        row[f"amdahl_efficiency_{t}"] = f"{sp / t:.3f}"
    return row


def thread_counts(maxt):
    ts, t = [], 1
    while t <= maxt:
        ts.append(t)
        t *= 2
    if ts[-1] != maxt:
        ts.append(maxt)
    return ts


def main():
    build, out_csv = sys.argv[1], sys.argv[2]
    maxt = int(sys.argv[3]) if len(sys.argv) > 3 else os.cpu_count()
    decks = sys.argv[4:]
    if not decks:
        decks = ["inputs/taylor/taylor_coarse.mpm", "inputs/taylor/taylor_coarse_elastic.mpm",
                 "inputs/taylor/taylor_medium.mpm"]
        if os.environ.get("BENCH_FINE") == "1":
            decks.append("inputs/taylor/taylor_fine.mpm")
        if os.path.isfile("../shared/decks/Taylor.mpm"):
            decks.insert(0, "../shared/decks/Taylor.mpm")
    steps = int(os.environ.get("BENCH_STEPS", "100"))
    repeats = int(os.environ.get("BENCH_REPEATS", "3"))
    rounds = int(os.environ.get("BENCH_ROUNDS", "5"))
    regrid = int(os.environ.get("BENCH_REGRID", "20"))
    exe = os.path.join(build, "cxx", "mpm3d")
    fields = ["deck", "particles", "regrid_every", "threads", "steps", "ns_per_particle_step",
              "speedup", "efficiency", "peak_rss_bytes_per_particle"] + [f"share_{s}" for s in STAGES] + \
             ["patches", "patches_empty", "patch_imbalance", "load1_before", "load1_max", "capacity",
              "capacity_efficiency", "round_speedup", "round_capacity_efficiency"]
    pinning = shutil.which("taskset") is not None
    rows = []
    with tempfile.TemporaryDirectory() as tmp, open(out_csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for deck in decks:
            for rg in (0, regrid):
                base = None
                paired = pinning and rg == 0
                # samples[t]: (summary, rss, load) of every run at t threads; cpu_ns[r][k]:
                # round r's 1-thread time pinned to CPU k. In the paired configuration the
                # runs go in rounds (every CPU pinned, then each thread count), so that a
                # round's figures are seconds apart and share the CPUs' speeds.
                samples = {t: [] for t in thread_counts(maxt)}
                cpu_ns = []
                for _ in range(rounds if paired else 1):
                    if paired:
                        cpu_ns.append([run_once(exe, deck, 1, steps, rg, tmp, cpu)[0]["ns_per_particle_step"]
                                       for cpu in range(os.cpu_count())])
                    for t in thread_counts(maxt):
                        for _ in range(1 if paired else repeats):
                            samples[t].append(run_once(exe, deck, t, steps, rg, tmp))
                for t in thread_counts(maxt):
                    s, rss, _ = min(samples[t], key=lambda x: x[0]["ns_per_particle_step"])
                    loads = [x[2] for x in samples[t]]
                    ns = s["ns_per_particle_step"]
                    if t == 1 and cpu_ns:
                        ns = min([ns] + [c for r in cpu_ns for c in r])  # the fastest CPU's 1-thread time
                    base = base or ns
                    total = sum(s["stage_seconds"].values()) or 1.0
                    row = {"deck": os.path.basename(deck), "particles": s["particles"],
                           "regrid_every": rg, "threads": t, "steps": s["steps"],
                           "ns_per_particle_step": f"{ns:.1f}", "speedup": f"{base / ns:.3f}",
                           "efficiency": f"{base / ns / t:.3f}",
                           "peak_rss_bytes_per_particle": f"{rss / s['particles']:.0f}",
                           "patches": s["patches"], "patches_empty": s["patches_empty"],
                           "patch_imbalance": f"{s['patch_imbalance']:.3f}",
                           "load1_before": f"{loads[0]:.2f}", "load1_max": f"{max(loads):.2f}"}
                    for st in STAGES:
                        row[f"share_{st}"] = f"{s['stage_seconds'][st] / total:.3f}"
                    for k in ("capacity", "capacity_efficiency", "round_speedup", "round_capacity_efficiency"):
                        row[k] = ""
                    extra = ""
                    if cpu_ns and t == maxt:
                        cap = sum(base / min(r[k] for r in cpu_ns) for k in range(len(cpu_ns[0])))
                        row["capacity"] = f"{cap:.3f}"
                        row["capacity_efficiency"] = f"{base / ns / cap:.3f}"
                        # Per round: the speedup over that round's fastest pinned 1-thread
                        # run, and that against the round's own capacity; their medians.
                        rs, re = [], []
                        for r, cpus in enumerate(cpu_ns):
                            tn = samples[t][r][0]["ns_per_particle_step"]
                            rs.append(min(cpus) / tn)
                            re.append(min(cpus) / tn / sum(min(cpus) / c for c in cpus))
                        row["round_speedup"] = f"{statistics.median(rs):.3f}"
                        row["round_capacity_efficiency"] = f"{statistics.median(re):.3f}"
                        extra = (f" capacity {row['capacity']} (eff {row['capacity_efficiency']}); rounds: speedup "
                                 + " ".join(f"{x:.3f}" for x in rs) + f" median {row['round_speedup']}, against the "
                                 f"round's capacity median {row['round_capacity_efficiency']}; 1 thread pinned: "
                                 + "; ".join(" ".join(f"{c:.1f}" for c in r) for r in cpu_ns) + " ns")
                    w.writerow(row)
                    f.flush()
                    rows.append(row)
                    print(f"{row['deck']:24s} regrid {rg:3d} threads {t:2d}: {row['ns_per_particle_step']:>7s} ns "
                          f"speedup {row['speedup']} eff {row['efficiency']} {row['peak_rss_bytes_per_particle']} B/p "
                          f"(load {loads[0]:.2f})" + extra, flush=True)

    # The serial part of a step and the team's loops (2 threads), from the summary.
    out = os.path.join(os.path.dirname(out_csv) or ".", "regions.csv")
    with tempfile.TemporaryDirectory() as tmp, open(out, "w", newline="") as f:
        w = None
        for deck in decks:
            row = serial_profile(exe, deck, steps, repeats, tmp)
            if w is None:
                w = csv.DictWriter(f, fieldnames=list(row))
                w.writeheader()
            w.writerow(row)
            print(f"{row['deck']:24s} {row['regions_per_step']} team loops a step; on 2 threads "
                  f"{row['serial_us_per_step']} us a step outside them, of {row['step_us_1thread']} us on 1 (serial "
                  f"fraction {row['serial_fraction']}); that alone allows {row['amdahl_speedup_8']} at 8 "
                  f"threads, {row['amdahl_speedup_16']} at 16", flush=True)


if __name__ == "__main__":
    main()
