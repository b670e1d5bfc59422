"""The vibrating bar of make report (tools/report.py): its runs (docs/verification/
vibrating_bar.csv and .png) and its section of docs/VERIFICATION.md.
"""
import os

import verification as V
from report_common import SHAPES, fmt, plt, write_csv


class BarStudy:
    """Suite's methods for the 1D vibrating bar."""

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

    def bar_section(self):
        """The 1D vibrating bar's section of docs/VERIFICATION.md."""
        L = []
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
        return L
