"""The Sod shock tube of make report (tools/report.py): its runs (docs/verification/sod.csv)
and its section of docs/VERIFICATION.md.
"""
import os

import verification as V
from report_common import SHAPES, fmt, write_csv


class SodStudy:
    """Suite's methods for the Sod shock tube."""

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

    def sod_section(self):
        """The Sod shock tube's section of docs/VERIFICATION.md."""
        L = []
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
        return L
