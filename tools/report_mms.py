"""The manufactured solutions of make report (tools/report.py): the roller cube (docs/verification/
mms.csv) and the cube with free faces for every method (mms_smooth.csv), their runs and
their sections of docs/VERIFICATION.md.
"""
import math
import os

import verification as V
from report_common import METHODS, SHAPES, SMOOTH_MMS, fmt, write_csv


class MmsStudy:
    """Suite's methods for the 3D manufactured solutions."""

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

    def mms_section(self):
        """The roller cube's section of docs/VERIFICATION.md."""
        L = []
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
        return L

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
