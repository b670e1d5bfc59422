"""The wave speeds and the Hugoniot elastic limit of make report (tools/report.py): their runs
(docs/verification/waves.csv) and their section of docs/VERIFICATION.md.
"""
import os

import verification as V
from report_common import SHAPES, fmt, write_csv


class WaveStudy:
    """Suite's methods for the elastic and elastic-plastic waves."""

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

    def waves_section(self):
        """The waves' section of docs/VERIFICATION.md."""
        L = []
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
        return L
