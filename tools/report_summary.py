"""The summary of make report (tools/report.py) across the convergence cases: observed orders
and run-time exponents (docs/verification/orders.csv, error_vs_runtime.csv and the plots
error_vs_runtime.png, methods_error_vs_runtime.png, waves_spheres.png), the 'Reading the
table' paragraph, and the head of docs/VERIFICATION.md (summary table, skipped cases).
"""
import os

import numpy as np

import verification as V
from report_common import COLOR, METHODS, SMOOTH_MMS, STYLE, fmt, plt, write_csv


class Summary:
    """Suite's methods for the summary of the convergence cases."""

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

    def summary_section(self, head):
        """The head of docs/VERIFICATION.md: the summary of orders and run-time exponents,
        the reading of it and the cases skipped in this run."""
        L = ["# Verification", "",
             "How wrong MPM3D-CXX is on problems with known answers, how the error falls with resolution, "
             "and what each step of accuracy costs. " + head, "",
             "Files: `docs/verification/*.csv` (every run), `error_vs_runtime.png`, "
             "`methods_error_vs_runtime.png`, `dam_break.png`, `landslide_*.png`, `granular_columns.png`, `contact_spheres.png`, `vibrating_bar.png`, "
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
        return L
