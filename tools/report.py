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
import csv
import datetime
import glob
import json
import math
import os
import pickle
import platform
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import hypervelocity as H  # noqa: E402
import soft_beam as SB  # noqa: E402
import soft_cantilever as SC  # noqa: E402
import cook_membrane as CM  # noqa: E402
import dam_break as DB  # noqa: E402
import verification as V  # noqa: E402

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


class Suite:
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

    def bar(self):
        self.bar_rows, self.bar_curves = [], {}
        ns = (8, 16, 32) if self.quick else (8, 16, 32, 64)
        for amp, v0 in (("small", 0.01), ("large", 0.1)):
            V.BAR["v0"] = v0
            for shape in SHAPES:
                for scheme in ("musl", "usl", "usf"):
                    if shape == "gimp" and scheme != "musl":
                        continue
                    for n in ns:
                        r = self.run(V.bar_deck(n, scheme=scheme, shape=shape, periods=2, dtsc=0.5),
                                     f"bar_{amp}_{scheme}_{shape}_{n}", threads=1)
                        if r.skipped:
                            self.skip("vibrating bar", shape, r)
                            break
                        a = V.bar_analyse(r, scheme=scheme)
                        row = dict(amplitude=amp, v0=v0, scheme=scheme, shape=shape, n=n, status=r.status,
                                   steps=r.info["steps"], wall_seconds=r.wall, error=a["error"],
                                   period_error=a["period"] / a["period_exact"] - 1,
                                   amplitude_error=a["amplitude"] / a["amplitude_exact"] - 1,
                                   energy_drift=a["energy_drift"], energy_maxdev=a["energy_maxdev"],
                                   message=r.message)
                        self.bar_rows.append(row)
                        if scheme == "musl" and r.status == "ok":
                            self.add_conv(f"vibrating bar ({amp} amplitude, MUSL)", shape, n, 1.0 / n, r,
                                          a["error"], "RMS of v_cm error over 2 periods / (2 v0/pi)")
                        if n == 16 and shape == "linear":
                            self.bar_curves[(amp, scheme)] = a
        V.BAR["v0"] = 0.1
        write_csv(os.path.join(self.vdir, "vibrating_bar.csv"), self.bar_rows,
                  ["amplitude", "v0", "scheme", "shape", "n", "status", "steps", "wall_seconds", "error",
                   "period_error", "amplitude_error", "energy_drift", "energy_maxdev", "message"])
        fig, ax = plt.subplots(1, 2, figsize=(11, 4))
        for (amp, scheme), a in sorted(self.bar_curves.items()):
            if amp != "large":
                continue
            ax[0].plot(a["t"], a["vcm"], label=scheme.upper())
            ax[1].plot(a["te"], a["etot"], label=scheme.upper())
        a = self.bar_curves.get(("large", "musl"))
        if a:
            ax[0].plot(a["t"], a["exact"], "k--", lw=1, label="exact")
        ax[0].set(xlabel="t", ylabel="centre-of-mass velocity", title="vibrating bar, 16 cells, v0 = 0.1")
        ax[1].set(xlabel="t", ylabel="total energy / initial", title="total energy (kinetic and internal at the same time)")
        for x in ax:
            x.legend()
            x.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(self.vdir, "vibrating_bar.png"), dpi=90)
        plt.close(fig)

    def mms_runs(self, rows, case, label, shapes, ns, A, K=1, free=False, prefix="mms"):
        """The manufactured solution with amplitude A and profile sin(2 pi X)^K (free: free
        faces on a wider grid) for each shape and resolution: its rows, and the convergence
        rows of `case`."""
        for shape in shapes:
            for n in ns:
                r = self.run(V.mms_deck(n, shape=shape, free=free), f"{prefix}_{shape}_{n}", V.mms_args(A, K))
                if r.skipped:
                    self.skip(label, shape, r)
                    break
                if r.status != "ok":
                    rows.append(dict(A=A, shape=shape, n=n, status=r.status, message=r.message))
                    continue
                a = V.mms_analyse(r, A, K)
                rows.append(self.add_conv(case, shape, n, 1.0 / n, r, a["error"],
                                          "RMS over particles of |u - u_exact| / A at t = 1.5",
                                          dict(error_max=a["error_max"], A=A, max_disp_cells=A * n,
                                               check_step=r.info.get("energy_check_first_step", -1))))

    MMS_FIELDS = ["A", "shape", "n", "particles", "steps", "wall_seconds", "error", "error_max", "max_disp_cells",
                  "check_step", "status"]

    def mms(self):
        self.mms_rows = []
        for A, ns in ((0.001, (8, 16) if self.quick else (8, 16, 24, 32)),
                      (0.01, (8, 16) if self.quick else (8, 16, 24, 32, 48))):
            self.mms_runs(self.mms_rows, f"manufactured solution (3D, A = {A:g})", "manufactured solution",
                          METHODS if A == 0.001 else SHAPES, ns, A, prefix=f"mms_{A:g}")
        write_csv(os.path.join(self.vdir, "mms.csv"), self.mms_rows, self.MMS_FIELDS)

    def mms_smooth(self):
        """u_a = A sin(2 pi X_a)^3 sin(C pi t), nu = 0, traction-free faces on a grid two cells
        wider than the cube: no boundary condition enters, so the interior accuracy of each
        method shows (the roller cube above holds node layers that the 27-node stencils place
        inside the body)."""
        self.mms_smooth_rows = []
        self.mms_runs(self.mms_smooth_rows, SMOOTH_MMS, "smooth manufactured solution", METHODS,
                      (8, 16) if self.quick else (8, 16, 24, 32), 0.001, K=3, free=True, prefix="mms3")
        write_csv(os.path.join(self.vdir, "mms_smooth.csv"), self.mms_smooth_rows, self.MMS_FIELDS)

    def waves(self):
        self.wave_rows = []
        ns = (25, 50, 100) if self.quick else (25, 50, 100, 200)
        self.wave_profile = self.wave_profile_gimp = None
        for plastic in (False, True):
            label = "elastic-plastic wave (HEL)" if plastic else "elastic wave speed"
            for shape in SHAPES:
                for n in ns:
                    t1, t2 = V.wave_snap_times()
                    r = self.run(V.wave_deck(n, plastic=plastic, shape=shape),
                                 f"wave_{'plastic' if plastic else 'elastic'}_{shape}_{n}",
                                 ["--snap", f"{t1!r},{t2!r}"], threads=1)
                    if r.skipped:
                        self.skip(label, shape, r)
                        break
                    a = V.wave_analyse(r, plastic)
                    norm = ("|sigma_HEL - exact| / exact (plateau between the fronts)" if plastic
                            else "|c_L measured - c_L| / c_L (front at v0/2, two times)")
                    row = self.add_conv(label, shape, n, 1.0 / n, r, a["error"], norm)
                    row.update({k: a[k] for k in ("cl", "cl_exact", "cb", "cb_exact", "cb_error", "hel",
                                                  "hel_exact") if k in a})
                    self.wave_rows.append(row)
                    if plastic and shape == "linear":
                        self.wave_profile = (n, a["profile"])
                    elif plastic:
                        self.wave_profile_gimp = (n, a["profile"])
        write_csv(os.path.join(self.vdir, "waves.csv"), self.wave_rows,
                  ["case", "shape", "n", "particles", "steps", "wall_seconds", "error", "cl", "cl_exact", "cb",
                   "cb_exact", "cb_error", "hel", "hel_exact"])

    def spheres(self):
        self.sph_rows, self.sph_curve = [], None
        ns = (10, 20) if self.quick else (10, 20, 40)
        for shape in SHAPES:
            for n in ns:
                r = self.run(V.spheres_deck(n, shape=shape), f"spheres_{shape}_{n}")
                if r.skipped:
                    self.skip("colliding spheres", shape, r)
                    break
                a = V.spheres_analyse(r)
                row = self.add_conv("colliding spheres (energy)", shape, n, 1.0 / n, r, a["error"],
                                    "|E(T) - E0| / E0, T = 2.5",
                                    dict(energy_maxdev=a["energy_maxdev"], momentum_error=a["momentum_error"],
                                         kinetic_final=a["kinetic_final"]))
                self.sph_rows.append(row)
                if shape == "linear":
                    self.sph_curve = (n, a)
        write_csv(os.path.join(self.vdir, "spheres.csv"), self.sph_rows,
                  ["shape", "n", "particles", "steps", "wall_seconds", "error", "energy_maxdev", "momentum_error",
                   "kinetic_final", "status"])

    def sod(self):
        self.sod_rows, self.sod_curve = [], None
        ns = (50, 100) if self.quick else (50, 100, 200)
        for shape in SHAPES:
            for n in ns:
                r = self.run(V.sod_deck(n, shape=shape), f"sod_{shape}_{n}", ["--snap", "1e30"], threads=1)
                if r.skipped:
                    self.skip("Sod shock tube", shape, r)
                    break
                if r.status != "ok":
                    self.sod_rows.append(dict(shape=shape, n=n, status=r.status, message=r.message))
                    continue
                a = V.sod_analyse(r)
                row = self.add_conv("Sod shock tube", shape, n, 1.0 / n, r, a["error"],
                                    "L1 density error at t = 0.2")
                self.sod_rows.append(row)
                self.sod_curve = (n, a)
        write_csv(os.path.join(self.vdir, "sod.csv"), self.sod_rows,
                  ["shape", "n", "particles", "steps", "wall_seconds", "error", "status", "message"])

    def taylor(self):
        self.taylor_rows, self.legacy, self.profiles = [], None, {}
        models = [("coarse", "inputs/taylor/taylor_coarse.mpm")]
        if not self.quick:
            models.append(("medium", "inputs/taylor/taylor_medium.mpm"))
            if self.fine:
                models.append(("fine", "inputs/taylor/taylor_fine.mpm"))
        for name, path in models:
            full = os.path.join(ROOT, path)
            dp = V.taylor_dp(full)
            with open(full) as f:
                text = f.read()
            r = self.run(text, f"taylor_{name}", ["--taylor", f"{dp!r},0.38"])
            t = r.info.get("taylor", {})
            row = dict(model=name, particles=r.info["particles"], steps=r.info["steps"], wall_seconds=r.wall,
                       dp=dp, L=t.get("L"), D=t.get("D"), W=t.get("W"), status=r.status,
                       L_error=t.get("L", float("nan")) - V.EXPERIMENT["L"],
                       D_error=t.get("D", float("nan")) - V.EXPERIMENT["D"])
            self.taylor_rows.append(row)
            self.profiles[name] = (np.array(r.info.get("profile_z", [])), np.array(r.info.get("profile_r", [])))
        legacy = os.path.join(ROOT, "..", "shared", "decks", "Taylor.mpm")
        if os.path.exists(legacy):
            with open(legacy) as f:
                r = self.run(f.read(), "taylor_legacy", ["--taylor", "0.38,0.38"])
            t = r.info.get("taylor", {})
            self.legacy = dict(L=t.get("L"), D=t.get("D"), W=t.get("W"), steps=r.info["steps"],
                               energy=r.info["kinetic_energy"] + r.info["internal_energy"], wall=r.wall)
            self.profiles["legacy"] = (np.array(r.info.get("profile_z", [])), np.array(r.info.get("profile_r", [])))
        write_csv(os.path.join(self.vdir, "taylor.csv"), self.taylor_rows,
                  ["model", "particles", "steps", "wall_seconds", "dp", "L", "D", "W", "L_error", "D_error", "status"])
        ref = V.read_profile(os.path.join(ROOT, "..", "shared", "reference", "Taylor", "radius_profile.txt"))
        self.profile_ref = ref
        fig, ax = plt.subplots(figsize=(6.5, 4.2))
        for name, (z, rr) in self.profiles.items():
            if len(z):
                ax.plot(z - z.min() + 0.19 if name != "legacy" else z - z.min() + 0.19, rr, label=f"MPM3D-CXX {name}")
        if ref is not None:
            ax.plot(ref[0] - ref[0].min() + 0.19, ref[1], "k--", label="original MPM3D, Taylor.mpm")
        ax.set(xlabel="distance from the impact end (mm, bin centre)", ylabel="largest particle-centre radius (mm)",
               title="Taylor bar at 80 microseconds")
        ax.legend()
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(self.vdir, "taylor_profile.png"), dpi=90)
        plt.close(fig)
        if ref is not None and "legacy" in self.profiles:
            z, rr = self.profiles["legacy"]
            m = min(len(rr), len(ref[1]))
            self.profile_diff = float(np.max(np.abs(rr[:m] - ref[1][:m]))) if m else None
        else:
            self.profile_diff = None

    # ---------------------------------------------------------------- stability
    def stability(self):
        rows = []

        def energy_error(r):
            """max over steps of |E - E0 - W_ext| / |E0|, energies centred in time."""
            if r.series is None or len(r.series["t"]) < 2:
                return float("nan")
            te, et = V.centred_energy(r.series)
            w = r.series["external_work"][:len(et)]
            return float(np.max(np.abs(et - et[0] - w)) / abs(et[0])) if et[0] else float("nan")

        def check(case, r, external=False, note="", energy=True):
            i = r.info
            if r.skipped:
                self.skipped.append((case, short(r.message)))
                rows.append(dict(case=case, outcome="skipped", message=short(r.message)))
                return None
            E0 = i["initial_total_energy"]
            p0 = np.array(i["momentum_initial"], float)
            p1 = np.array([np.nan if v is None else v for v in i["momentum"]], float)
            pscale = max(np.linalg.norm(p0), math.sqrt(2 * i["mass_initial"] * abs(E0)), 1e-300)
            ok = r.status == "ok" and i["nonfinite_values"] == 0
            clean = r.status == "stopped" and "step" in r.message and "particle" in r.message
            row = dict(case=case, outcome="finished" if ok else ("clean stop" if clean else "FAILED"),
                       particles=i["particles"], steps=i["steps"], nonfinite=i["nonfinite_values"],
                       mass_change=(i["mass_final"] - i["mass_initial"]) / i["mass_initial"],
                       momentum_error=("external" if external else float(np.linalg.norm(p1 - p0) / pscale)),
                       energy_error=energy_error(r) if energy else "released by the burn",
                       outside=i["particles_outside_grid"], wall_seconds=r.wall, message=r.message, note=note)
            rows.append(row)
            return row

        # Very stiff (E x 1000) and nearly incompressible materials: two colliding blocks.
        for label, E, nu in (("reference block (E 200, nu 0.3)", 200.0, 0.3),
                             ("very stiff (E x 1000)", 2.0e5, 0.3),
                             ("nearly incompressible nu 0.49", 200.0, 0.49),
                             ("nearly incompressible nu 0.499", 200.0, 0.499),
                             ("nearly incompressible nu 0.4999", 200.0, 0.4999)):
            text, cl = V.blocks_deck(E=E, nu=nu)
            r = self.run(text, "stab_" + label.split()[0] + f"_{E:g}_{nu:g}", threads=1)
            check(label, r)
        # The current version's remedies for nearly incompressible solids on the same block.
        for shape in ("bimp", "sgmp"):
            for label, E, nu in (("very stiff (E x 1000)", 2.0e5, 0.3),
                                 ("nearly incompressible nu 0.4999", 200.0, 0.4999)):
                text, cl = V.blocks_deck(E=E, nu=nu, shape=shape)
                r = self.run(text, f"stab_{shape}_{E:g}_{nu:g}", threads=1)
                check(f"{label}, {shape}", r)
        r = self.run(V.hypervelocity_deck(), "stab_hypervelocity")
        check("hypervelocity Al sphere on Al plate, 6.18 km/s, dtscale 0.9", r)
        r = self.run(V.hypervelocity_deck(dtsc=0.3), "stab_hypervelocity_03")
        check("hypervelocity Al sphere on Al plate, 6.18 km/s, dtscale 0.3", r)
        r = self.run(V.detonation_deck(), "stab_detonation", threads=1)
        check("detonation of a TNT slab (hiex + JWL)", r, external=True, energy=False)
        r = self.run(V.single_particle_deck(), "stab_single", ["--snap", "1e30"], threads=1)
        row = check("single particle crossing 20 cells", r)
        if row and r.status == "ok":
            s = r.snapshot(0)
            exact = np.array([1.3, 1.7, 2.2]) + np.array([10.0, 7.3, -0.4]) * s["t"]
            row["note"] = f"position error {np.abs(s['x'][0] - exact).max():.2e} (x0 + v t)"
        r = self.run(V.sparse_block_deck(), "stab_sparse", threads=1)
        check("spinning block, 1 particle per cell", r)
        r = self.run(V.leaving_deck(), "stab_leaving", threads=1)
        row = check("block leaving the grid", r)
        if row:
            row["note"] = f"{r.info.get('particles_outside_grid')} particles outside, frozen and reported"
        self.stab_rows = rows
        write_csv(os.path.join(self.sdir, "stability.csv"), rows,
                  ["case", "outcome", "particles", "steps", "nonfinite", "mass_change", "momentum_error",
                   "energy_error", "outside", "wall_seconds", "message", "note"])

        # dt-scale sweep on the stiff case, a fixed number of steps.
        self.cfl_pred = V.grid_cfl_limit(0.3, 2)
        sweep = []
        # MUSL, USL, USF with the trilinear functions; MUSL with the current version's B-splines
        # and smoothed gradients (whose decks take its time step, recomputed each step, and
        # its default bulk viscosity).
        for scheme, shape in (("musl", "linear"), ("usl", "linear"), ("usf", "linear"), ("musl", "bimp"),
                              ("musl", "sgmp")):
            for dtsc in (0.25, 0.5, 0.7, 0.8, 0.9, 1.0, 1.1, 1.25, 1.5, 2.0, 2.5):
                text, cl = V.blocks_deck(E=2.0e5, nu=0.3, dtsc=dtsc, scheme=scheme, steps_time=1e30, shape=shape)
                label = scheme if shape == "linear" else f"{scheme}+{shape}"
                r = self.run(text, f"sweep_{label}_{dtsc}", ["--steps", "400", "--keep-going"], threads=1)
                i = r.info
                te, et = V.centred_energy(r.series, scheme)
                E0 = et[0]
                growth = float(et.max() / E0 - 1)
                # Unstable: a non-finite value, energy beyond 10 E0, or still growing at the end
                # (the peak of the last 100 steps more than 0.25 E0 above that of steps 100-200).
                late, mid = et[-100:].max() / E0, et[100:200].max() / E0 if len(et) > 200 else 1.0
                stable = r.status == "ok" and growth < 9.0 and late <= mid + 0.25
                sweep.append(dict(scheme=label, dtscale=dtsc, status=r.status, steps=i["steps"],
                                  energy_error=growth, final_energy=float(et[-1] / E0), stable=stable,
                                  check_step=i.get("energy_check_first_step", -1),
                                  message=r.message or i.get("energy_check_message", "")))
        self.sweep = sweep
        write_csv(os.path.join(self.sdir, "dt_sweep.csv"), sweep,
                  ["scheme", "dtscale", "status", "steps", "energy_error", "final_energy", "stable", "check_step",
                   "message"])
        fig, ax = plt.subplots(figsize=(6.5, 4.2))
        for scheme in ("musl", "usl", "usf", "musl+bimp", "musl+sgmp"):
            pts = [s for s in sweep if s["scheme"] == scheme]
            x = [s["dtscale"] for s in pts]
            y = [1 + s["energy_error"] if s["status"] == "ok" else 1e3 for s in pts]
            ax.semilogy(x, y, "o-", label=scheme.upper())
        ax.axvline(1.0, color="k", ls="--", lw=1, label=f"CFL prediction {self.cfl_pred:.2f} (grid, full cells)")
        ax.axhline(10, color="gray", ls=":", lw=1, label="10 E0")
        ax.set(xlabel="dtscale (dt c_L / h)", ylabel="max E / E0 (1e3: non-finite, stopped)",
               title="stiff breathing block (E x 1000), 400 steps")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(self.sdir, "dt_sweep.png"), dpi=90)
        plt.close(fig)

    # ---------------------------------------------------------------- plots and docs
    def orders(self):
        """Observed order and run-time exponent per (case, shape)."""
        res = []
        keys = []
        for r in self.conv:
            k = (r["case"], r["shape"])
            if k not in keys:
                keys.append(k)
        for case, shape in keys:
            rows = [r for r in self.conv if r["case"] == case and r["shape"] == shape and r["status"] == "ok"]
            h = [r["h"] for r in rows]
            order = V.fit_order(h, [r["error"] for r in rows])
            wall = [max(r["wall_seconds"], 1e-6) for r in rows]
            q = -V.fit_order(h, wall) if len(rows) > 1 else float("nan")
            res.append(dict(case=case, shape=shape, points=len(rows), norm=rows[0]["norm"] if rows else "",
                            order=order, runtime_exponent=q,
                            errors=", ".join(fmt(r["error"]) for r in rows),
                            ns=", ".join(str(r["n"]) for r in rows)))
        self.order_rows = res
        write_csv(os.path.join(self.vdir, "error_vs_runtime.csv"), self.conv,
                  ["case", "shape", "n", "h", "particles", "steps", "threads", "wall_seconds", "error", "norm",
                   "status"])
        write_csv(os.path.join(self.vdir, "orders.csv"), res,
                  ["case", "shape", "points", "order", "runtime_exponent", "ns", "errors", "norm"])
        fig, ax = plt.subplots(1, 2, figsize=(12, 6.4))
        for case, shape in keys:
            rows = [r for r in self.conv if r["case"] == case and r["shape"] == shape and r["status"] == "ok"]
            if not rows:
                continue
            st = STYLE.get(shape, "s--")
            ax[0].loglog([r["h"] for r in rows], [r["error"] for r in rows], st, label=f"{case} [{shape}]")
            ax[1].loglog([max(r["wall_seconds"], 1e-4) for r in rows], [r["error"] for r in rows], st,
                         label=f"{case} [{shape}]")
        if self.taylor_rows:
            w = [r["wall_seconds"] for r in self.taylor_rows]
            ax[1].loglog(w, [abs(r["L_error"]) / V.EXPERIMENT["L"] for r in self.taylor_rows], "^-",
                         label="Taylor bar |L - 16.2| / 16.2")
            ax[1].loglog(w, [max(abs(r["D_error"]), 1e-4) / V.EXPERIMENT["D"] for r in self.taylor_rows], "v-",
                         label="Taylor bar |D - 13.5| / 13.5")
        ax[0].set(xlabel="cell size h (case units)", ylabel="error (norm of each case)", title="error against h")
        ax[1].set(xlabel="wall time of the time loop (s)", ylabel="error", title="error against run time")
        for x in ax:
            x.grid(alpha=0.3, which="both")
        handles, labels = ax[1].get_legend_handles_labels()
        fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8)
        fig.tight_layout(rect=(0, 0.2, 1, 1))
        fig.savefig(os.path.join(self.vdir, "error_vs_runtime.png"), dpi=90)
        plt.close(fig)
        # Every method on the two manufactured solutions: error against h and against run time.
        fig, ax = plt.subplots(1, 2, figsize=(12, 5.2))
        for case, mark in ((SMOOTH_MMS, ""), ("manufactured solution (3D, A = 0.001)", "roller ")):
            for shape in METHODS:
                rows = [r for r in self.conv if r["case"] == case and r["shape"] == shape and r["status"] == "ok"]
                if not rows:
                    continue
                st = STYLE[shape] if not mark else STYLE[shape][0] + ":"
                kw = dict(alpha=0.45, mfc="none", color=COLOR[shape]) if mark else dict(color=COLOR[shape])
                lab = f"{shape}, {'roller cube' if mark else 'free faces'}"
                ax[0].loglog([r["h"] for r in rows], [r["error"] for r in rows], st, label=lab, **kw)
                ax[1].loglog([max(r["wall_seconds"], 1e-4) for r in rows], [r["error"] for r in rows], st,
                             label=lab, **kw)
        ax[0].set(xlabel="cell size h", ylabel="RMS displacement error / A", title="error against h")
        ax[1].set(xlabel="wall time of the time loop (s)", ylabel="RMS displacement error / A",
                  title="error against run time")
        for x in ax:
            x.grid(alpha=0.3, which="both")
        ax[1].legend(fontsize=8, ncol=2)
        fig.tight_layout()
        fig.savefig(os.path.join(self.vdir, "methods_error_vs_runtime.png"), dpi=90)
        plt.close(fig)

        if self.wave_profile or self.sph_curve:
            fig, ax = plt.subplots(1, 2, figsize=(11, 4))
            if self.wave_profile:
                n, (X, s) = self.wave_profile
                k = V.wave_consts()
                o = np.argsort(X)
                ax[0].plot(X[o], s[o], lw=1, label=f"MPM linear, {n} cells per unit")
                if getattr(self, "wave_profile_gimp", None):  # absent in results of older runs
                    ng, (X, s) = self.wave_profile_gimp
                    Xs, sm = V.slice_mean(X, s)
                    ax[0].plot(Xs, sm, "--", lw=1, label=f"MPM GIMP, {ng} cells per unit")
                ax[0].axhline(k["hel"], color="k", ls="--", lw=1, label="sigma_HEL exact")
                ax[0].set(xlabel="X", ylabel="-sigma_xx", title="elastic-plastic wave at t2")
                ax[0].legend()
            if self.sph_curve:
                n, a = self.sph_curve
                ax[1].plot(a["t"], a["ke"], label="kinetic")
                ax[1].plot(a["t"], a["ie"], label="internal (strain)")
                ax[1].plot(a["te"], a["et"], label="total (centred in time)")
                ax[1].set(xlabel="t", ylabel="energy / E0", title=f"colliding spheres, {n} cells per unit")
                ax[1].legend()
            for x in ax:
                x.grid(alpha=0.3)
            fig.tight_layout()
            fig.savefig(os.path.join(self.vdir, "waves_spheres.png"), dpi=90)
            plt.close(fig)

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

    def findings(self):
        """The 'Reading the table' paragraph, from the numbers: for each shape function which
        cases converge (order p >= 1), converge slowly (0.25 <= p < 1) or stop falling (p < 0.25)
        or rise at the finest resolutions, and GIMP's errors against linear ones at the finest
        resolution run with both."""
        def runs(case, shape):
            return [x for x in self.conv if x["case"] == case and x["shape"] == shape and x["status"] == "ok"]

        def rising(r):
            e = [x["error"] for x in runs(r["case"], r["shape"])]
            return len(e) > 1 and e[-1] > 1.05 * min(e)

        def last_order(r):
            x = runs(r["case"], r["shape"])
            return V.fit_order([x[-2]["h"], x[-1]["h"]], [x[-2]["error"], x[-1]["error"]]) if len(x) > 2 else None

        def kind(shape):
            rows = [r for r in self.order_rows if r["shape"] == shape and r["points"] > 1]
            poor = [r for r in rows if rising(r) or not r["order"] >= 0.25]
            good = [r for r in rows if r not in poor and r["order"] >= 1.0]
            slow = [r for r in rows if r not in poor and r not in good]
            return good, slow, poor

        def orders(rows):
            return ", ".join(f"{r['case']} (p = {fmt(r['order'], 2)})" for r in rows)

        def converging(good, slow, sod_note=False):
            parts = []
            if good:
                parts.append(orders(good) + " converge")
                drop = [(r, last_order(r)) for r in good]
                drop = [(r, q) for r, q in drop if q is not None and q < 0.6 * r["order"]]
                if drop:
                    parts[-1] += (" (" + ", ".join(f"{r['case']} at order {fmt(q, 2)} between its two finest "
                                                  "resolutions" for r, q in drop) + ")")
            if slow:
                parts.append(orders(slow) + " converge slowly")
                if sod_note and any(r["case"].startswith("Sod") for r in slow):
                    parts[-1] += (" (an L1 error of a solution with a shock and a contact discontinuity falls "
                                  "at most at first order: both are smeared over a few cells)")
            return "; ".join(parts)

        text = "Reading the table: "
        good, slow, poor = kind("linear")
        if good or slow:
            text += "with linear shape functions, " + converging(good, slow) + ". "
        if poor:
            text += ("Where the error stops falling or rises at the finest resolutions, " + ", ".join(
                f"{r['case']} (errors {r['errors']})" for r in poor) + ", the finest runs are those in which "
                "particles move across cell boundaries (the largest displacement reaches a sizeable part of a "
                "cell or more: large-amplitude bar at 64 cells, manufactured solution with A = 0.01 from 32 "
                "cells, the plastic bar at 200 cells where the material behind the plastic front has moved "
                "1.4 cells, the spheres at 40 cells where they travel 10 cells, the Sod gas, whose contact "
                "moves 0.19, 9 cells at 50 cells and 37 at 200): with linear shape functions the gradient "
                "jumps when a particle crosses a cell boundary, and that cell-crossing error grows as h falls. "
                "This is the known limitation of linear MPM that GIMP is designed to reduce; the same cases "
                "with small displacements (small-amplitude bar, manufactured solution with A = 0.001) "
                "converge. ")
        good, slow, poor = kind("gimp")
        if good or slow:
            text += "With GIMP, " + converging(good, slow, sod_note=True) + ". "
        if poor:
            text += ("With GIMP the error stops falling or rises at the finest resolutions in " + ", ".join(
                f"{r['case']} (errors {r['errors']})" for r in poor) + ". ")
        wave = [sh for sh in ("linear", "gimp") if any(r["case"] == "elastic wave speed" for r in kind(sh)[1])]
        if wave:
            text += (f"The elastic wave-speed error falls slowly ({' and '.join(wave).replace('gimp', 'GIMP')}) "
                     "because the front is measured at half amplitude and the dispersive ringing behind it "
                     "shrinks only slowly. ")
        # GIMP against linear at the finest resolution run with both.
        lower, same, higher = [], [], []
        for r in self.order_rows:
            if r["shape"] != "gimp":
                continue
            lin = {x["n"]: x["error"] for x in runs(r["case"], "linear")}
            both = [x for x in runs(r["case"], "gimp") if x["n"] in lin]
            if not both:
                continue
            g = both[-1]
            item = f"{r['case']} ({fmt(g['error'])} against {fmt(lin[g['n']])} at {g['n']} cells)"
            ratio = g["error"] / lin[g["n"]] if lin[g["n"]] > 0 else float("inf")
            (lower if ratio < 0.9 else same if ratio <= 1.1 else higher).append(item)
        if lower or same or higher:
            text += "At the finest resolution run with both, GIMP's error is " + "; ".join(
                f"{what} in " + ", ".join(items) for what, items in
                (("below the linear one", lower), ("within 10 % of it", same), ("above it", higher)) if items) + "."
        return text.strip()

    def smooth_mms_section(self):
        """The manufactured solution with free faces, every method; generated from the rows."""
        rows = getattr(self, "mms_smooth_rows", [])
        if not rows:
            return []
        m = V.MMS
        L = ["## 3D manufactured solution with free faces: every method", "",
             f"u_a = A sin(2 pi X_a)^3 sin(C pi t), A = 0.001, C = {m['C']}, E = {m['E']}, nu = 0, "
             f"rho = {m['rho']}, the unit cube on a grid two cells wider on every side, 2^3 particles per cell, "
             f"dtscale {m['dtsc']}, end time {m['T']}, MUSL, the same driver and body force as above "
             "(`mpm3d_verify --mms A,C,3`). The profile vanishes at every face with its slope, so the "
             "displacement and the stress (sigma_aa = 2 G ln F_aa with nu = 0) are zero there: the free "
             "surface is exact and no node is held. This is the case that measures the methods themselves: "
             "on the roller cube above, the current version's rule for B-splines and smoothed gradients "
             "holds two node layers on each symmetric face, and its B-spline node i carries the spline "
             "centred at the centre of cell i, so the held layers sit h/2 and 3h/2 inside the body where the "
             "exact solution moves; in the grid's first cell the B-spline's node below the grid is dropped "
             "(docs/DECK_FORMAT.md), which gives the particles there less than their full weight.", "",
             "| shape | cells per side | particles | steps | error (RMS / A) | max error / A | wall (s) |",
             "|---|---|---|---|---|---|---|"]
        for r in rows:
            if r.get("status") != "ok":
                L.append(f"| {r['shape']} | {r['n']} | - | - | {r['status']}: {r.get('message', '')} | | |")
                continue
            L.append(f"| {r['shape']} | {r['n']} | {r['particles']} | {r['steps']} | {fmt(r['error'])} | "
                     f"{fmt(r['error_max'])} | {fmt(r['wall_seconds'])} |")
        ok = [r for r in rows if r.get("status") == "ok"]
        orders = {o["shape"]: o for o in self.order_rows if o["case"] == SMOOTH_MMS}
        parts = []
        for shape in METHODS:
            x = [r for r in ok if r["shape"] == shape]
            if len(x) < 2:
                continue
            last = V.fit_order([x[-2]["h"], x[-1]["h"]], [x[-2]["error"], x[-1]["error"]])
            parts.append(f"{shape} p = {fmt(orders[shape]['order'], 2)} over {orders[shape]['ns']} cells "
                         f"({fmt(last, 2)} between the two finest; {fmt(x[-1]['error'])} at {x[-1]['n']} cells in "
                         f"{fmt(x[-1]['wall_seconds'])} s)")
        text = "Observed orders: " + "; ".join(parts) + "."
        # The run time each method needs for the largest of the methods' finest errors
        # (log-log interpolation between its two runs around it).
        finest = [max(r["error"] for r in ok if r["shape"] == sh and r["n"] == max(
            q["n"] for q in ok if q["shape"] == sh)) for sh in METHODS if any(r["shape"] == sh for r in ok)]
        target = max(finest) if finest else None
        need = []
        for shape in METHODS:
            x = sorted((r for r in ok if r["shape"] == shape), key=lambda r: r["n"])
            for a, b in zip(x, x[1:]):
                if a["error"] >= target >= b["error"] and a["error"] > b["error"]:
                    f = math.log(a["error"] / target) / math.log(a["error"] / b["error"])
                    w = math.exp(math.log(max(a["wall_seconds"], 1e-6)) +
                                 f * math.log(max(b["wall_seconds"], 1e-6) / max(a["wall_seconds"], 1e-6)))
                    need.append((w, shape))
                    break
        if need and target:
            need.sort()
            text += (f" Run time to reach an error of {fmt(target)} (the largest of the methods' finest errors; "
                     "interpolated between the two runs around it): " +
                     ", ".join(f"{sh} {fmt(w)} s" for w, sh in need) +
                     ". The B-splines' wide stencil (27 nodes, and a smoothing of the velocity field that "
                     "costs accuracy on the coarse grids, where the profile's third harmonic has under six "
                     "cells per wavelength) and GIMP's (27 nodes) cost run time per particle-step; the "
                     "smoothed gradient keeps the 8-node transfer. Run times from a shared 2-core machine: "
                     "compare the orders of magnitude.")
        L += ["", text, "", "![every method: error against h and run time](verification/methods_error_vs_runtime.png)",
              ""]
        return L

    def write_verification(self, head):
        L = ["# Verification", "",
             "How wrong MPM3D-CXX is on problems with known answers, how the error falls with resolution, "
             "and what each step of accuracy costs. " + head, "",
             "Files: `docs/verification/*.csv` (every run), `error_vs_runtime.png`, "
             "`methods_error_vs_runtime.png`, `dam_break.png`, `vibrating_bar.png`, "
             "`waves_spheres.png`, `taylor_profile.png`. Decks are generated by `tools/verification.py` "
             "(examples in `inputs/verification/`); the driver `mpm3d_verify` "
             "(`tests/verification/verify_driver.cpp`) runs them through the library exactly as `mpm3d` does.", ""]
        L += ["## Summary: observed orders and run-time exponents", "",
              "Order p: least-squares slope of log(error) against log(h) over the resolutions listed. "
              "Run-time exponent q: wall time ~ h^-q (ideal: 2 for the 1D cases, 4 for 3D ones: "
              "particles ~ h^-3 and steps ~ h^-1). Error against run time then falls as wall^(-p/q).", "",
              "| case | shape | cells per unit | errors | order p | run-time exponent q | norm |",
              "|---|---|---|---|---|---|---|"]
        for r in self.order_rows:
            L.append(f"| {r['case']} | {r['shape']} | {r['ns']} | {r['errors']} | {fmt(r['order'], 2)} | "
                     f"{fmt(r['runtime_exponent'], 2)} | {r['norm']} |")
        L += ["", self.findings(), "",
              "![error against h and against run time](verification/error_vs_runtime.png)", ""]
        if self.skipped:
            L += ["### Cases skipped in this run", "",
                  "The program refused these decks (a keyword not supported by this build); they run as soon as "
                  "it accepts them (`make report` again):", ""]
            seen = set()
            for case, why in self.skipped:
                if case in seen:
                    continue
                seen.add(case)
                L.append(f"- {case}: `{why}`")
            L.append("")
        # Vibrating bar
        L += ["## 1D vibrating bar", "",
              "Bar 0 <= x <= 1, fixed at x = 0, free at x = 1, E = 100, rho = 1, nu = 0 (uniaxial stress; "
              "one cell thick with symmetry faces, 2 x 2 particles per x-slice; the GIMP decks are two cells "
              "thick with 4 x 4, since GIMP's 3-node stencil needs two cells along each axis), first mode "
              "v = v0 sin(pi x / 2) cos(omega t), "
              "omega = pi c / 2, c = 10: period 0.4. Exact centre-of-mass velocity (2 v0 / pi) cos(omega t); the "
              "error norm is the RMS over all steps of the difference, divided by 2 v0 / pi (leap-frog: the "
              "velocity after step k belongs to t_k - dt/2). 2 particles per cell and direction, dtscale 0.5, "
              "two periods. Small amplitude v0 = 0.01 (largest displacement 0.0006, below a cell at every "
              "resolution) and large amplitude v0 = 0.1 (0.0064: 0.2 cells at 32 cells, 0.4 at 64, so particles "
              "near a cell boundary cross it).",
              "", "| amplitude | scheme | shape | cells | status | error | period error | amplitude error | "
              "energy drift | max energy deviation | wall (s) |", "|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in self.bar_rows:
            L.append(f"| {r['amplitude']} | {r['scheme'].upper()} | {r['shape']} | {r['n']} | {r['status']} | "
                     f"{fmt(r['error'])} | {fmt(r['period_error'])} | {fmt(r['amplitude_error'])} | "
                     f"{fmt(r['energy_drift'])} | {fmt(r['energy_maxdev'])} | {fmt(r['wall_seconds'])} |")
        stopped = [r for r in self.bar_rows if r["status"] != "ok"]
        if stopped:
            L += ["", "Runs stopped by the health check (the program's own message):", ""]
            for r in stopped:
                L.append(f"- {r['amplitude']} amplitude, {r['scheme'].upper()}, {r['n']} cells: `{r['message']}`")
        L += ["", "Energy: kinetic plus internal energy taken at the same time (`centred_energy` in "
              "`tools/verification.py`: the leap-frog kinetic energy is half a step behind the internal energy "
              "in MUSL and USL, half a step ahead in USF, and is averaged accordingly); 'energy drift' is its "
              "change over the two periods, 'max energy deviation' the largest excursion, both relative to the "
              "initial energy.",
              "", "![vibrating bar](verification/vibrating_bar.png)", ""]
        # MMS
        m = V.MMS
        L += ["## 3D manufactured solution (Wallstedt & Guilkey 2008, axis aligned)", "",
              f"u_a = A sin(2 pi X_a) sin(C pi t) on each axis a of the unit cube, C = {m['C']}, "
              f"E = {m['E']}, nu = {m['nu']}, rho = {m['rho']}, symmetry (roller) faces, 2^3 particles per cell, "
              f"dtscale {m['dtsc']}, end time {m['T']}. The paper uses a neo-Hookean material; our `elas` is "
              "hypoelastic with the Jaumann rate. For this motion F is diagonal, there is no spin, and the "
              "hypoelastic law integrates exactly to the Hencky law sigma = lambda ln J I + 2 G ln V, so the "
              "driver applies the body force of that law (b_a = u_a,tt - (1/rho0) (prod_{b!=a} F_bb) "
              "(lambda + 2G) F_aa,a / F_aa, derived in the driver) through the particles' external-force "
              "array before every step: the exact solution is exact for our model, not an approximation. "
              "Error: RMS over particles of |x_p - X_p - u(X_p, T)|, divided by A.", "",
              "Two amplitudes: A = 0.001, where the largest displacement stays below 0.05 cells at every "
              "resolution (no particle crosses a cell boundary it did not start next to), and the paper's "
              "A = 0.01, where the largest displacement is 0.08 cells at 8 cells per side and about half a "
              "cell at 48: particles cross cell boundaries, and the jump of the linear shape-function "
              "gradients at the crossing (the cell-crossing error) does not fall with h. The runs go on past "
              "the runaway-energy check (driver `--keep-going`); the step where it would have stopped the "
              "run is listed (its bound, twice the initial energy plus the external work, is tight for a "
              "forced problem that starts with little energy).", "",
              "| A | shape | cells per side | largest displacement (cells) | particles | steps | error (RMS / A) | "
              "max error / A | energy check tripped at step | wall (s) |",
              "|---|---|---|---|---|---|---|---|---|---|"]
        for r in self.mms_rows:
            if r.get("status") != "ok":
                L.append(f"| {r['A']:g} | {r['shape']} | {r['n']} | | - | - | {r['status']}: "
                         f"{r.get('message', '')} | | | |")
                continue
            cs = r["check_step"]
            L.append(f"| {r['A']:g} | {r['shape']} | {r['n']} | {fmt(r['max_disp_cells'], 2)} | {r['particles']} | "
                     f"{r['steps']} | {fmt(r['error'])} | {fmt(r['error_max'])} | {cs if cs >= 0 else '-'} | "
                     f"{fmt(r['wall_seconds'])} |")
        L += [""]
        L += self.smooth_mms_section()
        # Waves
        k = V.wave_consts()
        w = V.WAVE
        L += ["## Wave speeds and the Hugoniot elastic limit", "",
              f"A bar 0 <= X <= {w['Lbar']} in uniaxial strain (symmetry faces in y and z; one cell thick, "
              f"GIMP two cells with 4 x 4 particles per x-slice), E = {w['E']}, "
              f"nu = {w['nu']}, rho = {w['rho']}, moving at -v0 against the wall x = 0. Elastic (v0 = {w['v0']}): "
              f"the front travels at c_L = sqrt((lambda + 2G)/rho) = {k['cl']:.4f}; measured from the front "
              f"(where the mean v of an x-slice is -v0/2, interpolated in the reference coordinate X) at two "
              f"times, so the start-up "
              f"offset cancels. Elastic-perfectly plastic `pla1` (sigma_y = {w['sy']}, v0 = {w['v0p']}): a "
              f"precursor at c_L carrying sigma_HEL = sigma_y (1 - nu)/(1 - 2 nu) = {k['hel']:.4f}, then the "
              f"plastic wave at c_B = sqrt(K/rho) = {k['cb']:.4f}. The error norm of the plastic case is that of "
              "the precursor's stress plateau (mean of -sigma_xx over the middle half between the two fronts).",
              "", "| case | shape | cells per unit | c_L measured | error | c_B measured | c_B error | "
              "sigma_HEL measured | HEL error |", "|---|---|---|---|---|---|---|---|---|"]
        for r in self.wave_rows:
            pl = "cb" in r
            L.append(f"| {r['case']} | {r['shape']} | {r['n']} | {fmt(r['cl'], 5)} | "
                     f"{fmt(abs(r['cl'] - r['cl_exact']) / r['cl_exact'])} | {fmt(r.get('cb'), 5) if pl else '-'} | "
                     f"{fmt(r.get('cb_error')) if pl else '-'} | {fmt(r.get('hel'), 4) if pl else '-'} | "
                     f"{fmt(r['error']) if pl else '-'} |")
        L += ["", "![wave profile and sphere energies](verification/waves_spheres.png)", ""]
        # Spheres
        s = V.SPH
        L += ["## Two colliding elastic spheres", "",
              f"Spheres of radius {s['R']} (E = {s['E']}, nu = {s['nu']}, rho = {s['rho']}) approach at "
              f"+-{s['v0']} with a gap of 0.1, one velocity field (no contact algorithm, so they interact "
              f"through the shared grid nodes once within a cell of each other), free box, end time {s['T']}. "
              "Momentum is conserved to rounding (no external force); the energy error |E(T) - E0|/E0 measures "
              "the scheme's dissipation (MUSL).", "",
              "| shape | cells per unit | particles | steps | energy error at T | max energy deviation | "
              "momentum error | kinetic at T / E0 | wall (s) |", "|---|---|---|---|---|---|---|---|---|"]
        for r in self.sph_rows:
            L.append(f"| {r['shape']} | {r['n']} | {r['particles']} | {r['steps']} | {fmt(r['error'])} | "
                     f"{fmt(r['energy_maxdev'])} | {fmt(r['momentum_error'])} | {fmt(r['kinetic_final'])} | "
                     f"{fmt(r['wall_seconds'])} |")
        gain = [r for r in self.sph_rows if r.get("kinetic_final", 0) > 1.0]
        if gain:
            L += ["", "Energy is gained, not lost, at " + ", ".join(f"{r['n']} cells per unit ({r['shape']})"
                                                               for r in gain)
                  + ": the kinetic energy at T exceeds the initial energy. The spheres travel about 10 cells "
                  "there and interact through nodes they share while crossing cells, so this is the "
                  "cell-crossing error of the summary, not a dissipation; the health check does not stop it "
                  "(the growth stays below its factor of two)."]
        L += [""]
        # Sod
        L += ["## Sod shock tube (ideal gas)", "",
              "gamma = 1.4 as the `null` material with the linear polynomial EOS (`seos mid 1 0 0 0 0 0.4 0.4 0 "
              "E0`, i.e. p = 0.4 (1 + mu) E = (gamma - 1) rho e), left rho 1, p 1, right rho 0.125, p 0.1, "
              "interface at x = 0.5, t = 0.2, bulk viscosity 1.5 / 0.06, 2 particles per cell, one cell thick with "
              "symmetry faces (GIMP: two cells, 4 x 4 particles per x-slice), equal spacing in "
              "both gases (so the particle masses jump 8:1 at the contact). Error: mean over the particles of "
              "|rho_p - rho_exact(x_p)| (rho_p = m_p / V_p), exact Riemann solution as in Toro (2009), ch. 4.",
              ""]
        if self.sod_rows:
            L += ["| shape | cells | particles | steps | L1 density error | wall (s) |", "|---|---|---|---|---|---|"]
            for r in self.sod_rows:
                L.append(f"| {r['shape']} | {r['n']} | {r.get('particles', '-')} | {r.get('steps', '-')} | "
                         f"{fmt(r.get('error'))} | {fmt(r.get('wall_seconds'))} |")
        else:
            msg = next((why for c, why in self.skipped if c.startswith("Sod")), "")
            L += [f"Not run: the program refuses the deck (`{msg}`)."]
        L += [""]
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
        # Taylor
        L += ["## Taylor bar", ""]
        if self.legacy:
            g = self.legacy
            L += ["### Legacy deck `Taylor.mpm` against the original program", "",
                  f"`../shared/decks/Taylor.mpm` (21,172 particles, MUSL, `sjc` + Mie-Gruneisen, 190 m/s, "
                  f"{g['steps']} steps to 0.08 ms). Measures as defined in `../shared/reference/README.md` "
                  "(particle-centre extent plus one spacing, dp 0.38 mm):", "",
                  "| quantity | original MPM3D | MPM3D-CXX (this run) | difference |", "|---|---|---|---|",
                  f"| final length L (mm) | 16.58 | {g['L']:.3f} | {g['L'] - 16.58:+.3f} |",
                  f"| impact-end diameter D (mm) | 13.51 | {g['D']:.3f} | {g['D'] - 13.51:+.3f} |",
                  f"| W(0.2 L0) (mm) | 10.37 | {g['W']:.3f} | {g['W'] - 10.37:+.3f} |",
                  f"| total energy at 0.08 ms (N mm) | 1.881e5 | {g['energy']:.4g} | |", ""]
            ref_e = os.path.join(ROOT, "..", "shared", "reference", "Taylor", "EnergyPlot.dat")
            ours = os.path.join(self.work, "taylor_legacy_series.csv")
            if os.path.exists(ref_e) and os.path.exists(ours):
                ref = np.loadtxt(ref_e)
                se = np.genfromtxt(ours, delimiter=",", names=True)
                m = min(len(ref), len(se) - 1)
                ke, ie = se["kinetic"][1:m + 1], se["internal"][1:m + 1]
                d = {name: np.abs(col - ref[:m, j]) for name, col, j in
                     (("total", ke + ie, 1), ("kinetic", ke, 2), ("internal", ie, 3))}
                k0 = float(se["kinetic"][0])
                worst = max(d, key=lambda n: d[n].max())
                L += [f"Energy history (`EnergyPlot.dat` of the original, {len(ref)} rows, compared row by row "
                      f"with ours, {m} rows): the largest differences are {d['total'].max():.3g} N mm in the "
                      f"total, {d['kinetic'].max():.3g} in the kinetic (at t = {ref[int(np.argmax(d['kinetic'])), 0]:.3g} "
                      f"ms) and {d['internal'].max():.3g} in the internal energy, i.e. at most "
                      f"{100 * d[worst].max() / k0:.2f} % of the initial kinetic energy of {k0:.4g} N mm (the "
                      f"original prints four digits).", ""]
            if self.profile_diff is not None:
                L += [f"Radius profile (largest particle-centre radius in 0.38 mm bins from the impact end) "
                      f"against the original's `radius_profile.txt`: largest difference {self.profile_diff:.3f} mm.",
                      ""]
            L += ["Differences come from the original's single-precision deck reals and details of its stress "
                  "update; they are of the size of the rounding of its printed results.", ""]
        L += ["### The paper's three models against the experiment", "",
              "Copper per the paper's Table 1, 190 m/s, 80 microseconds, MUSL, cell = 2 spacings "
              "(`inputs/taylor/`). Experiment (Johnson & Cook 1983): L = 16.2 mm, D = 13.5 mm.", "",
              "| model | particles | steps | L (mm) | L - 16.2 | D (mm) | D - 13.5 | W(0.2 L0) (mm) | wall (s) |",
              "|---|---|---|---|---|---|---|---|---|"]
        for r in self.taylor_rows:
            L.append(f"| {r['model']} | {r['particles']:,} | {r['steps']} | {fmt(r['L'], 4)} | {r['L_error']:+.2f} | "
                     f"{fmt(r['D'], 4)} | {r['D_error']:+.2f} | {fmt(r['W'], 4)} | {fmt(r['wall_seconds'])} |")
        if not any(r["model"] == "fine" for r in self.taylor_rows):
            L.append("")
            L.append("The fine model (1,155,192 particles) was not part of this run (`--no-fine` or `--quick`).")
        ok = [r for r in self.taylor_rows if r["status"] == "ok" and r["L"] is not None]
        if ok:
            le = [r["L_error"] for r in ok]
            de = [r["D_error"] for r in ok]
            steps = [ok[i]["L"] - ok[i + 1]["L"] for i in range(len(ok) - 1)]
            L += ["", f"Across the models run ({', '.join(r['model'] for r in ok)}), L - 16.2 mm goes "
                  + " -> ".join(f"{x:+.2f}" for x in le) + " mm and D - 13.5 mm "
                  + " -> ".join(f"{x:+.2f}" for x in de) + " mm. "
                  + (f"L has not levelled off (changes of {', '.join(f'{x:.2f}' for x in steps)} mm between "
                     "successive models), so its agreement with the experiment at one resolution is not a "
                     "converged answer: the discretisation error and the model error (the paper's simplified "
                     "Johnson-Cook without thermal softening or rate term, C = 0, with a Mie-Gruneisen EOS) are "
                     "of the same size and cannot be separated here. " if steps else "")
                  + "The paper's own three models give L = 16.3-16.5 mm and D = 13.4-13.6 mm. The measures add "
                  "one particle spacing to the particle-centre extent, a convention whose own uncertainty is "
                  "half a spacing (0.14 mm coarse, 0.05 mm fine).", ""]
        L += ["![Taylor profile](verification/taylor_profile.png)", ""]
        with open(os.path.join(ROOT, "docs", "VERIFICATION.md"), "w") as f:
            f.write("\n".join(L))

    def write_stability(self, head):
        L = ["# Stability", "",
             "Stiff and extreme cases: each run either finishes with no NaN or Inf, exact mass, momentum "
             "conserved where no external force acts and a stated energy error, or stops cleanly with a "
             "message naming the step, the particle and the cause (the per-step health check of "
             "`Simulation::step`, exit status 3 of `mpm3d`). " + head, "",
             "Files: `docs/stability/stability.csv`, `dt_sweep.csv`, `dt_sweep.png`. Decks: "
             "`tools/verification.py` (examples in `inputs/stability/`).", "",
             "Columns: mass change (relative), momentum error |p(T) - p(0)| / (|p(0)| or sqrt(2 m E0)), "
             "energy error max over steps of |E - E0 - W_ext| / E0.", "",
             "| case | outcome | particles | steps | NaN/Inf values | mass change | momentum error | energy error | "
             "particles outside | note or message |", "|---|---|---|---|---|---|---|---|---|---|"]
        for r in self.stab_rows:
            if r["outcome"] == "skipped":
                L.append(f"| {r['case']} | skipped | | | | | | | | `{r['message']}` |")
                continue
            me = r["momentum_error"]
            L.append(f"| {r['case']} | {r['outcome']} | {r['particles']} | {r['steps']} | {r['nonfinite']} | "
                     f"{fmt(r['mass_change'])} | {me if isinstance(me, str) else fmt(me)} | "
                     f"{r['energy_error'] if isinstance(r['energy_error'], str) else fmt(r['energy_error'])} | "
                     f"{r['outside']} | {r['note'] or ''}"
                     f"{(' `' + r['message'] + '`') if r['message'] else ''} |")
        failed = [r for r in self.stab_rows if r["outcome"] == "FAILED"]
        L += ["", ("**Silent failures: none.**" if not failed else
                   "**Silent failures: " + ", ".join(r["case"] for r in failed) + "**"), ""]
        L += ["Blocks: a free elastic block of 8^3 particles (2 per cell) with the breathing velocity field "
              "v_a = v0 cos(pi X_a / l), v0 = 1 % of c_L, dtscale 0.5, four longitudinal wave transits (32 steps "
              "whatever the stiffness: dt follows c_L, which grows without bound as nu -> 0.5, c_L / c_S = 7, 22, "
              "71 at nu = 0.49, 0.499, 0.4999; the shear motion of a nearly incompressible body then takes that "
              "many times more steps). The energy error of these blocks, 11-18 % over 32 steps, is the cost of "
              "4 cells across the body (MUSL remapping smooths the breathing mode), not a growth; stiffness "
              "alone (E x 1000) changes nothing, as it should (the problem scales with c_L). Spinning block: one "
              "particle per cell, so many nodes carry little mass; the momentum error of a few 1e-6 comes from "
              "nodes below the small-mass cut-off (1e-5 rho h^3, as in the original), which are skipped when "
              "velocities are formed, and the 30 % energy error from the one-point quadrature of a body only "
              "6 cells wide. Hypervelocity impact: `pla1` aluminium "
              "(yield 300 MPa) with Mie-Gruneisen (c0 5328 m/s, s 1.338, gamma0 2), dp 0.25 mm, no artificial "
              "viscosity; the time step is set from c_L alone, while particles move at 6.18 km/s, about 0.9 cells "
              "per step at dtscale 0.9.", ""]
        # dt sweep
        L += ["## Time-step scale sweep (empirical stability limit)", "",
              f"Stiff breathing block (E x 1000), 400 steps at each dtscale (dt = dtscale h / c_L; the rows with "
              f"bimp and sgmp are decks of the current version: its time step, recomputed each step from c_L plus "
              f"the fastest particle, and its default bulk viscosity). A run counts "
              f"as stable when its total energy (kinetic and internal at the same time) stays bounded: below 10 E0 and no longer growing at the end (the peak of the last 100 steps at most 0.25 E0 above that of steps 100-200); an instability shows as exponential growth, far beyond that. Bounded is not accurate: the maximum energy error is in the table. The runs go on past the program's runaway-energy check (`--keep-going` of the driver: the check compares the uncentred total with 2 E0 and can trip on a stable run at large dt, see below); the step where it first tripped is listed. CFL prediction: for a uniform grid "
              f"with lumped node masses and 2^3 particles per cell as quadrature points, the highest plane-wave "
              f"frequency gives dt_crit = {self.cfl_pred:.3f} h / c_L (`grid_cfl_limit` in "
              f"`tools/verification.py`, a Fourier scan; the 1D bound h / c is the same number). Nodes at free "
              f"surfaces and in partly filled cells carry less mass, so the limit of a real body is lower.", "",
              "| scheme | " + " | ".join(f"{d:g}" for d in sorted({s['dtscale'] for s in self.sweep})) + " | largest "
              "stable |", "|---|" + "---|" * (len({s['dtscale'] for s in self.sweep}) + 1)]
        for scheme in ("musl", "usl", "usf", "musl+bimp", "musl+sgmp"):
            pts = [s for s in self.sweep if s["scheme"] == scheme]
            if not pts:
                continue
            cells = []
            for s in pts:
                c = f"{fmt(1 + s['energy_error'], 3)}" if s["status"] == "ok" else f"NaN@{s['steps']}"
                if s["check_step"] >= 0:
                    c += f" (check@{s['check_step']})"
                cells.append(c)
            stable = [s["dtscale"] for s in pts if s["stable"]]
            limit = None
            for s in pts:
                if not s["stable"]:
                    break
                limit = s["dtscale"]
            L.append(f"| {scheme.upper()} | " + " | ".join(cells) + f" | {fmt(limit) if limit else '-'} |")
        L += ["", "Cells: the largest total energy (kinetic and internal at the same time) over the initial one; `NaN@k`: the "
              "run met a non-finite value at step k and stopped cleanly (the message names the step, the "
              "particle and the quantity); `(check@k)`: the program's runaway-energy check would have stopped "
              "the run at step k. 'largest stable' is the largest dtscale up to which every run stayed bounded.", "",
              "![dt sweep](stability/dt_sweep.png)", ""]
        ex = [s for s in self.sweep if s["status"] != "ok"]
        if ex:
            L += ["Example of a clean stop: `" + ex[0]["message"] + "`", ""]
        early = [s for s in self.sweep if s["stable"] and s["check_step"] >= 0]
        if early:
            e = early[0]
            L += ["**The runaway-energy check can stop stable runs.** It compares the plain sum of the kinetic "
                  "energy (leap-frog velocities, half a step behind) and the internal energy with twice the "
                  "initial energy. When dt is a sizeable part of a mode's period, that sum overshoots by "
                  "O((omega dt)^2) although nothing grows: "
                  f"{len(early)} of the stable runs above would have been stopped, e.g. {e['scheme'].upper()} at "
                  f"dtscale {e['dtscale']:g} at step {e['check_step']} (`{e['message']}`), while the centred "
                  f"energy stayed within {fmt(1 + e['energy_error'], 3)} E0 for 400 steps. A centred kinetic "
                  "energy in the check (average of two half steps) would remove these false stops.", ""]
        with open(os.path.join(ROOT, "docs", "STABILITY.md"), "w") as f:
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
    s.orders()
    load1 = loadavg()
    save_results(s, load0, load1, time.time() - s.t0)
    s.write_docs(load0, load1)
    s.log("wrote docs/VERIFICATION.md, docs/STABILITY.md, docs/verification/, docs/stability/")


if __name__ == "__main__":
    main()
