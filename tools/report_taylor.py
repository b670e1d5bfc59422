"""The Taylor bar of make report (tools/report.py): the paper's three models and the legacy deck
against the original program (docs/verification/taylor.csv, taylor_profile.png) and its
section of docs/VERIFICATION.md.
"""
import os

import numpy as np

import verification as V
from report_common import ROOT, fmt, plt, write_csv


class TaylorStudy:
    """Suite's methods for the Taylor bar."""

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

    def taylor_section(self):
        """The Taylor bar's section of docs/VERIFICATION.md."""
        L = []
        # Taylor
        L += ["## Taylor bar", ""]
        if self.legacy:
            g = self.legacy
            L += ["### Legacy deck `Taylor.mpm` against the original program", "",
                  f"`Taylor.mpm` (21,172 particles, MUSL, `sjc` + Mie-Gruneisen, 190 m/s, "
                  f"{g['steps']} steps to 0.08 ms), from the public decks folder beside the checkout "
                  "(`shared/decks`, not in the repository; `make report` leaves this comparison out without "
                  "it). Measures as defined in the README of the reference folder beside it "
                  "(`shared/reference`): particle-centre extent plus one spacing, dp 0.38 mm:", "",
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
        return L
