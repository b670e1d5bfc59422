#!/usr/bin/env python3
"""make report: runs the verification and stability suite and rewrites docs/VERIFICATION.md,
docs/STABILITY.md, the CSV files and PNG plots in docs/verification/ and docs/stability/.

usage: tools/report.py BUILD_DIR [--threads N] [--quick] [--no-fine] [--docs-only | --only CASES]
  --quick      smaller resolutions and no medium/fine Taylor models (a few minutes)
  --no-fine    everything but the fine Taylor model (1.16 M particles, the longest run)
  --docs-only  rewrite the docs from the results of the last run (BUILD_DIR/report/results.pkl)
  --only CASES rerun only these convergence cases (comma-separated: bar, mms, wave, spheres,
               sod) and take everything else from the last run's results.pkl, e.g.
               `--only bar,wave,sod` after a change to the 1D decks (minutes instead of the
               whole report); needs a full run first, uses its resolutions (--quick or not)
Idempotent: every run starts from the decks (tools/verification.py) and rewrites the docs.
"""
import argparse
import glob
import os
import pickle
import platform
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# The shared constants and helpers (pyplot with the Agg backend first), and one module per
# study with Suite's methods for it: its runs, files and section of the docs.
from report_common import GROUPS, ROOT, group_of, loadavg, short, utc_now  # noqa: E402
from report_bar import BarStudy  # noqa: E402
from report_mms import MmsStudy  # noqa: E402
from report_waves import WaveStudy  # noqa: E402
from report_spheres import SpheresStudy  # noqa: E402
from report_sod import SodStudy  # noqa: E402
from report_taylor import TaylorStudy  # noqa: E402
from report_stability import StabilityStudy  # noqa: E402
from report_summary import Summary  # noqa: E402

import hypervelocity as H  # noqa: E402
import soft_beam as SB  # noqa: E402
import soft_cantilever as SC  # noqa: E402
import cook_membrane as CM  # noqa: E402
import landslide_result as LS  # noqa: E402
import dam_break as DB  # noqa: E402
import granular_columns as GC  # noqa: E402
import contact_spheres as CS  # noqa: E402
import verification as V  # noqa: E402


class Suite(BarStudy, MmsStudy, WaveStudy, SpheresStudy, SodStudy, TaylorStudy, StabilityStudy, Summary):
    """The report: the runner and the convergence bookkeeping here, the studies' runs and
    sections in their modules (tools/report_*.py), assembled by write_docs."""

    def __init__(self, build, threads, quick, fine):
        cand = glob.glob(os.path.join(build, "tests", "verification", "mpm3d_verify")) + \
            glob.glob(os.path.join(build, "**", "mpm3d_verify"), recursive=True)
        if not cand:
            sys.exit(f"report: no mpm3d_verify in {build} (build the project first: make build)")
        self.driver = os.path.abspath(cand[0])
        self.work = os.path.join(os.path.abspath(build), "report")
        self.build = os.path.abspath(build)
        self.threads, self.quick, self.fine = threads, quick, fine
        self.vdir = os.path.join(ROOT, "docs", "verification")
        self.sdir = os.path.join(ROOT, "docs", "stability")
        os.makedirs(self.vdir, exist_ok=True)
        os.makedirs(self.sdir, exist_ok=True)
        self.skipped = []  # (case, reason)
        self.conv = []     # rows of the error-against-run-time study
        self.t0 = time.time()

    def log(self, msg):
        print(f"[{time.time() - self.t0:7.1f} s] {msg}", flush=True)

    def run(self, text, name, args=(), threads=None):
        r = V.run(self.driver, text, name, self.work, threads or self.threads, args)
        if r.skipped:
            self.log(f"{name}: skipped ({r.message})")
        else:
            self.log(f"{name}: {r.status}, {r.info['particles']} particles, {r.info['steps']} steps, "
                     f"{r.wall:.2f} s")
        return r

    def skip(self, case, shape, r):
        self.skipped.append((f"{case} ({shape})", short(r.message)))

    # ---------------------------------------------------------------- convergence cases
    def rerun(self, names):
        """Run the convergence cases `names` (GROUPS) again in place of their results from the
        last run; the rows of the others, their order and the skipped list stay as they were."""
        for i, (name, method, _) in enumerate(GROUPS):
            if name not in names:
                continue
            self.conv = [r for r in self.conv if group_of(r["case"]) != i]
            self.skipped = [(c, w) for c, w in self.skipped if group_of(c) != i]
            getattr(self, method)()
        self.conv.sort(key=lambda r: group_of(r["case"]))  # stable: the full run's order
        self.skipped.sort(key=lambda cw: group_of(cw[0]))

    def add_conv(self, case, shape, n, h, r, err, norm, extra=None):
        row = dict(case=case, shape=shape, n=n, h=h, particles=r.info["particles"], steps=r.info["steps"],
                   wall_seconds=r.wall, error=err, norm=norm, status=r.status, threads=r.info["threads"])
        row.update(extra or {})
        self.conv.append(row)
        return row

    # ---------------------------------------------------------------- docs
    def write_docs(self, load_start, load_end):
        when = getattr(self, "run_date", None) or utc_now()  # that of the full run
        machine = f"{platform.machine()}, {os.cpu_count()} cores"
        total = time.time() - self.t0
        head = (f"Generated by `make report` (`tools/report.py`) on {when}, {machine}, "
                f"`--threads {self.threads}` for the 3D cases and 1 thread for the 1D ones; the whole report took "
                f"{total / 60:.1f} minutes. Machine load (/proc/loadavg, 1/5/15 min) at the start: {load_start}, "
                f"at the end: {load_end}. **Run times are noisy**: the machine was shared with other jobs, so "
                f"compare the run-time exponents and the errors, not the absolute seconds. Times are those of "
                f"the time loop (set-up and file output excluded).")
        if self.quick:
            head += " This was a `--quick` run (reduced resolutions)."
        for p in getattr(self, "partial_runs", []):
            head += (f" The {', '.join(p['cases'])} cases were then rerun alone (`--only "
                     f"{','.join(p['cases'])}`"
                     + (f", `--threads {p['threads']}` for the 3D ones" if p.get("threads") else "")
                     + f") on {p['when']} ({p['minutes']:.1f} minutes, load {p['load_start']} at the start, "
                     f"{p['load_end']} at the end); their rows and plots are from that rerun, the rest from the "
                     "full run.")
        self.write_verification(head)
        self.write_stability(head)

    def write_verification(self, head):
        L = self.summary_section(head)
        L += self.bar_section()
        L += self.mms_section()
        L += self.smooth_mms_section()
        L += self.waves_section()
        L += self.spheres_section()
        # Colliding spheres through the contact, ours and the originals' (tools/contact_spheres.py)
        L += CS.section_lines()
        L += self.sod_section()
        # Hypervelocity (tools/hypervelocity.py: its files in docs/verification/)
        L += H.section_lines()
        # The free soft beam (tools/soft_beam.py: docs/verification/soft_beam.csv)
        L += SB.section_lines()
        # The soft cantilever, TLmp with and without sgmp (tools/soft_cantilever.py)
        L += SC.section_lines()
        # Cook's membrane (tools/cook_membrane.py: docs/verification/cook_membrane.csv)
        L += CM.section_lines()
        # The dam break against Martin & Moyce (tools/dam_break.py: docs/verification/dam_break.csv)
        L += DB.section_lines()
        # Granular columns against Lube et al. (tools/granular_columns.py: docs/verification/granular_columns.csv)
        L += GC.section_lines()
        # The newest program's landslides, run once (tools/landslide_result.py: docs/verification/landslides.csv)
        L += LS.section_lines()
        L += self.taylor_section()
        with open(os.path.join(ROOT, "docs", "VERIFICATION.md"), "w") as f:
            f.write("\n".join(L))


def load_results(s):
    """The results of the last run (saved by a full run, updated by --only)."""
    path = os.path.join(s.work, "results.pkl")
    if not os.path.exists(path):
        sys.exit(f"report: no results of an earlier run in {path}: run the whole report first "
                 "(make report, or tools/report.py BUILD_DIR --threads 2)")
    with open(path, "rb") as f:
        return pickle.load(f)


def save_results(s, load0, load1, elapsed):
    keep = {k: v for k, v in vars(s).items() if k not in ("t0",)}
    keep["elapsed"] = elapsed
    with open(os.path.join(s.work, "results.pkl"), "wb") as f:
        pickle.dump((keep, load0, load1), f)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("--threads", type=int, default=None,
                    help="threads of the 3D cases (default 2; with --only that of the last run; the 1D cases use 1)")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--no-fine", action="store_true")
    ap.add_argument("--docs-only", action="store_true",
                    help="rewrite the docs from the results of the last run (BUILD/report/results.pkl)")
    ap.add_argument("--only", metavar="CASES",
                    help="rerun only these convergence cases, comma-separated (" + ", ".join(g[0] for g in GROUPS)
                         + "), and take the others from the last run (BUILD/report/results.pkl)")
    a = ap.parse_args()
    if a.docs_only and a.only:
        ap.error("--docs-only and --only exclude each other")
    only = []
    if a.only:
        only = [c.strip() for c in a.only.split(",") if c.strip()]
        unknown = [c for c in only if c not in [g[0] for g in GROUPS]]
        if unknown or not only:
            ap.error(f"--only: unknown case(s) {', '.join(unknown)} (known: {', '.join(g[0] for g in GROUPS)})")
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
    s = Suite(a.build, a.threads or 2, a.quick, not a.no_fine)
    if a.docs_only:
        keep, load0, load1 = load_results(s)
        vars(s).update(keep)
        s.t0 = time.time() - keep["elapsed"]
        s.orders()
        s.write_docs(load0, load1)
        s.log("rewrote docs/VERIFICATION.md and docs/STABILITY.md from the last run")
        return
    if only:
        keep, load0, load1 = load_results(s)
        here = {k: getattr(s, k) for k in ("driver", "work", "vdir", "sdir")}
        vars(s).update(keep)
        vars(s).update(here)
        s.threads = a.threads or keep["threads"]  # for rerun 3D cases; the 1D ones run on 1 thread
        if a.quick != keep["quick"] or a.no_fine == keep["fine"]:
            s.log("--quick/--no-fine are those of the last run with --only (its resolutions are kept)")
        s.run_date = keep.get("run_date") or "an earlier date (not recorded in its results)"
        start, s.t0 = loadavg(), time.time()
        s.log(f"load {start}; driver {s.driver}; rerunning {', '.join(only)}, the rest from {s.work}/results.pkl")
        s.rerun(only)
        earlier = [p for p in keep.get("partial_runs", []) if not set(p["cases"]) <= set(only)]
        s.partial_runs = earlier + [
            dict(cases=[g[0] for g in GROUPS if g[0] in only], when=utc_now(), minutes=(time.time() - s.t0) / 60,
                 load_start=start, load_end=loadavg(),
                 threads=s.threads if any(c in ("mms", "spheres") for c in only) else None)]
        s.threads = keep["threads"]  # that of the full run, which the docs' head names
        s.orders()
        save_results(s, load0, load1, keep["elapsed"])
        s.log(f"reran {', '.join(only)}; rewriting docs/VERIFICATION.md, docs/STABILITY.md and their files")
        s.t0 = time.time() - keep["elapsed"]  # the docs' head gives the full run's duration
        s.write_docs(load0, load1)
        return
    load0 = loadavg()
    s.run_date = utc_now()
    s.partial_runs = []
    s.log(f"load {load0}; driver {s.driver}; work in {s.work}")
    for folder, name, text in V.example_decks():
        os.makedirs(os.path.join(ROOT, "inputs", folder), exist_ok=True)
        with open(os.path.join(ROOT, "inputs", folder, name + ".mpm"), "w") as f:
            f.write(text)
    s.bar()
    s.mms()
    s.mms_smooth()
    s.waves()
    s.spheres()
    s.sod()
    s.stability()
    s.taylor()
    s.log("hypervelocity: inputs/impact/lead_sphere_small.mpm")
    H.run_small(s.build, s.threads)
    H.make_plot()
    s.log("free soft beam: tools/soft_beam.py")
    SB.run(s.build, s.threads)
    s.log("soft cantilever: tools/soft_cantilever.py")
    SC.run(s.build, s.threads)
    s.log("Cook's membrane: tools/cook_membrane.py")
    CM.run(s.build, s.threads)
    s.log("dam break: tools/dam_break.py")
    DB.run(s.build, s.threads)
    s.log("granular columns: tools/granular_columns.py")
    GC.run(s.build, s.threads)
    s.log("colliding spheres, contact: tools/contact_spheres.py")
    CS.run(s.build, s.threads)
    s.orders()
    load1 = loadavg()
    save_results(s, load0, load1, time.time() - s.t0)
    s.write_docs(load0, load1)
    s.log("wrote docs/VERIFICATION.md, docs/STABILITY.md, docs/verification/, docs/stability/")


if __name__ == "__main__":
    main()
