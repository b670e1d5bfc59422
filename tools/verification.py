"""Verification and stability cases of MPM3D-CXX: deck generators, the runner of the
mpm3d_verify driver (tests/verification/verify_driver.cpp) and the analysis of each case.
Used by tools/report.py (make report) and tests/verification/check.py (make test).

Every case is a deck in the legacy format, written here for a given resolution and shape
function ('linear' or 'gimp'), so a deck the program refuses (a keyword not yet supported:
gimp, null, hiex, bulk ...) is reported as skipped with the program's own message.
"""
import json
import math
import os
import subprocess

import numpy as np

# The deck writer and the stability decks are in verification_decks.py and
# verification_stability.py; their names are imported here, so verification.deck,
# verification.blocks_deck ... are where they were.
from verification_decks import deck, lateral, sphere_count
from verification_stability import (blocks_deck, detonation_deck, hypervelocity_deck,
                                    leaving_deck, single_particle_deck, sparse_block_deck)

PI = math.pi


# ------------------------------------------------------------------ runner

class Run:
    """The result of one driver run: .info (the JSON), .series (columns), snapshots."""

    def __init__(self, prefix, rc):
        self.prefix, self.rc = prefix, rc
        with open(prefix + ".json") as f:
            self.info = json.load(f)
        self.status = self.info["status"]
        self.message = self.info.get("message", "")
        self.series = None
        if os.path.exists(prefix + "_series.csv") and self.status != "refused":
            d = np.genfromtxt(prefix + "_series.csv", delimiter=",", names=True)
            self.series = np.atleast_1d(d)

    @property
    def skipped(self):
        return self.status == "refused"

    @property
    def wall(self):
        return self.info.get("wall_seconds")

    def snapshot(self, k):
        raw = np.fromfile(f"{self.prefix}_snap_{k}.bin", dtype=np.float64)
        n = int(raw[0])
        s = {"t": raw[1]}
        off = 2
        for name, w in (("X0", 3), ("x", 3), ("v", 3), ("sig", 6)):
            s[name] = raw[off:off + w * n].reshape(n, w)
            off += w * n
        for name in ("mass", "vol", "ie", "epeff"):
            s[name] = raw[off:off + n]
            off += n
        return s


def run(driver, text, name, workdir, threads=2, args=()):
    os.makedirs(workdir, exist_ok=True)
    path = os.path.join(workdir, name + ".mpm")
    with open(path, "w") as f:
        f.write(text)
    prefix = os.path.join(workdir, name)
    for stale in [p for p in os.listdir(workdir) if p.startswith(name + "_snap_")]:
        os.remove(os.path.join(workdir, stale))
    cmd = [driver, path, "--threads", str(threads), "--out", prefix] + [str(a) for a in args]
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode not in (0, 3, 4):
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}): {p.stderr.strip()}")
    return Run(prefix, p.returncode)


def centred_energy(series, scheme="musl"):
    """Total energy with both parts taken at the same time. The driver records, after step
    k, the kinetic energy of the leap-frog velocities at t_k - dt/2 (t = 0 for k = 0) and
    the internal energy of the stress of that step: at t_k for MUSL and USL (stress after
    the grid update), at t_(k-1) for USF (stress from the velocities at the start of the
    step). The plain sum oscillates by O((omega dt)^2) even in a stable run; centring gives
    an O(dt^2) measure: MUSL/USL KE(t_k) ~ (KE_k + KE_(k+1)) / 2 with IE_k, USF
    IE(t_k - dt/2) ~ (IE_k + IE_(k+1)) / 2 with KE_k. Returns (t, E) for the steps that
    have a successor (row 0 is the initial state)."""
    ke, ie, t = series["kinetic"], series["internal"], series["t"]
    if len(ke) < 2:
        return t, ke + ie
    e = np.empty(len(ke) - 1)
    e[0] = ke[0] + ie[0]
    if scheme == "usf":
        e[1:] = ke[1:-1] + 0.5 * (ie[1:-1] + ie[2:])
    else:
        e[1:] = 0.5 * (ke[1:-1] + ke[2:]) + ie[1:-1]
    return t[:-1], e


def fit_order(h, err):
    """Least-squares slope of log(err) against log(h) (the observed order)."""
    h, err = np.asarray(h, float), np.asarray(err, float)
    ok = (err > 0) & np.isfinite(err)
    if ok.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(h[ok]), np.log(err[ok]), 1)[0])


# ------------------------------------------------------------------ 1. vibrating bar
# Bar 0 <= x <= L = 1, fixed at x = 0, free at x = L, nu = 0 (uniaxial stress), rho = 1,
# E = 100 (c = 10), one cell thick (GIMP: two, see lateral()) with symmetry faces in y and
# z. First mode:
#   v(x, t) = v0 sin(beta x) cos(omega t), beta = pi / (2 L), omega = beta c,
#   centre-of-mass velocity v_cm(t) = (2 v0 / pi) cos(omega t); period 4 L / c = 0.4.

BAR = dict(L=1.0, E=100.0, rho=1.0, v0=0.1)


def bar_deck(n, scheme="musl", shape="linear", periods=1.0, E=None, dtsc=0.9):
    L, rho, v0 = BAR["L"], BAR["rho"], BAR["v0"]
    E = E or BAR["E"]
    h = L / n
    dp = h / 2
    c = math.sqrt(E / rho)
    T = 4 * L / c
    nx = 2 * n
    w, m = lateral(shape, h)
    velo = []
    for i in range(nx):
        x = (i + 0.5) * dp
        v = v0 * math.sin(PI * x / (2 * L))
        for j in range(m * m):
            velo.append(f"node {i * m * m + j + 1} {v!r} 0 0")
    return deck(f"vibrating bar, {n} cells, {scheme}", nx * m * m, 1, (0.0, L + 2 * h, 0.0, w, 0.0, w), h, dtsc,
                periods * T, [f"elas {rho!r} {E!r} 0.0"], [f"part bloc 1 1 {rho!r} {dp!r} 0 0 0 {nx} {m} {m}"],
                scheme=scheme, fix=(1, 0, 2, 2, 2, 2), velo=velo, shape=shape)


def bar_analyse(r, E=None, scheme="musl"):
    """Centre-of-mass velocity against the exact one; period and amplitude from the run."""
    E = E or BAR["E"]
    L, rho, v0 = BAR["L"], BAR["rho"], BAR["v0"]
    c = math.sqrt(E / rho)
    omega = PI * c / (2 * L)
    s = r.series
    mass = r.info["mass_initial"]
    dt = r.info["dt"]
    # Leap-frog: after step k >= 1 the velocities belong to t_k - dt/2.
    tv = np.where(s["step"] > 0, s["t"] - 0.5 * dt, 0.0)
    vcm = s["px"] / mass
    amp0 = 2 * v0 / PI
    exact = amp0 * np.cos(omega * tv)
    err = float(np.sqrt(np.mean((vcm - exact) ** 2)) / amp0)
    # Period from the downward and upward zero crossings (linear interpolation).
    cross = []
    for k in range(1, len(vcm)):
        if vcm[k - 1] == 0 or (vcm[k - 1] > 0) != (vcm[k] > 0):
            f = vcm[k - 1] / (vcm[k - 1] - vcm[k])
            cross.append(tv[k - 1] + f * (tv[k] - tv[k - 1]))
    period = 2 * (cross[1] - cross[0]) if len(cross) >= 2 else float("nan")
    # Amplitude: largest |v_cm| after the first quarter period, against 2 v0 / pi.
    late = tv > 0.5 * (2 * PI / omega)
    amp = float(np.max(np.abs(vcm[late]))) if late.any() else float("nan")
    te, etot = centred_energy(s, scheme)
    E0 = etot[0]
    return dict(error=err, period=period, period_exact=2 * PI / omega, amplitude=amp, amplitude_exact=amp0,
                energy_drift=float((etot[-1] - E0) / E0), energy_maxdev=float(np.max(np.abs(etot - E0)) / E0),
                t=tv, vcm=vcm, exact=exact, te=te, etot=etot / E0)


# ------------------------------------------------------------------ 2. manufactured solution
# Wallstedt & Guilkey (2008), axis aligned: u_a = A sin(2 pi X_a) sin(C pi t) on the unit
# cube, symmetry (roller) faces, body force of our hypoelastic material (see the driver).

MMS = dict(A=0.01, C=1.0, E=1.0, nu=0.3, rho=1.0, T=1.5, dtsc=0.5)


def mms_deck(n, shape="linear", T=None, free=False):
    """The unit cube with symmetry (roller) faces on a grid that ends at its faces; free:
    traction-free faces on a grid two cells wider on every side (for the profile
    sin(2 pi X)^3 and nu = 0, whose displacement and stress vanish at the faces, so that
    the free surface is exact and no boundary condition enters; with nu = 0 the axes
    decouple: sigma_aa = 2 G ln F_aa)."""
    m = MMS
    h = 1.0 / n
    dp = h / 2
    pad = 2 * h if free else 0.0
    return deck(f"manufactured solution, {n}^3 cells", (2 * n) ** 3, 1,
                (-pad, 1.0 + pad, -pad, 1.0 + pad, -pad, 1.0 + pad), h,
                m["dtsc"], T or m["T"], [f"elas {m['rho']!r} {m['E']!r} {0.0 if free else m['nu']!r}"],
                [f"part bloc 1 1 {m['rho']!r} {dp!r} 0 0 0 {2 * n} {2 * n} {2 * n}"],
                fix=(0,) * 6 if free else (2,) * 6, load=["node 1 0 0 0"], shape=shape)


def mms_args(A=None, K=1):
    """Driver options: the body force of amplitude A (profile sin(2 pi X)^K), a snapshot at
    the end, and no stop by the runaway-energy heuristic (the error against the exact
    solution is the measure)."""
    return ["--mms", f"{A or MMS['A']!r},{MMS['C']!r},{K}", "--snap", "1e30", "--keep-going"]


def mms_analyse(r, A=None, K=1):
    s = r.snapshot(0)
    A, C = A or MMS["A"], MMS["C"]
    t = s["t"]
    X0 = s["X0"]
    u_exact = A * np.sin(2 * PI * X0) ** K * math.sin(C * PI * t)
    e = np.linalg.norm(s["x"] - X0 - u_exact, axis=1)
    return dict(error=float(np.sqrt(np.mean(e ** 2)) / A), error_max=float(e.max() / A), t=t)


# ------------------------------------------------------------------ 3. wave speeds
# A bar 0 <= X <= 2 in uniaxial strain (symmetry faces in y, z; one cell thick, GIMP two,
# see lateral()) moving at -v0 against the wall x = 0. Elastic: the front moves at
# c_L = sqrt((lambda + 2G)/rho) in X. Elastic-perfectly plastic (pla1): a precursor at c_L
# carrying the Hugoniot elastic limit sigma_HEL = sigma_y (1 - nu) / (1 - 2 nu), then the
# plastic wave at c_B = sqrt(K / rho).

WAVE = dict(E=100.0, nu=0.3, rho=1.0, v0=0.002, sy=0.1, v0p=0.05, Lbar=2.0)


def wave_consts():
    w = WAVE
    E, nu, rho = w["E"], w["nu"], w["rho"]
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    G = E / (2 * (1 + nu))
    K = lam + 2 * G / 3
    cl = math.sqrt((lam + 2 * G) / rho)
    cb = math.sqrt(K / rho)
    hel = w["sy"] * (1 - nu) / (1 - 2 * nu)
    return dict(cl=cl, cb=cb, hel=hel, vhel=hel / (rho * cl))


def wave_deck(n, plastic=False, shape="linear"):
    w = WAVE
    k = wave_consts()
    Lb = w["Lbar"]
    h = 1.0 / n
    dp = h / 2
    nx = int(round(2 * Lb * n))
    v0 = w["v0p"] if plastic else w["v0"]
    mat = (f"pla1 {w['rho']!r} {w['E']!r} {w['nu']!r} {w['sy']!r}" if plastic
           else f"elas {w['rho']!r} {w['E']!r} {w['nu']!r}")
    tend = 0.85 * Lb / k["cl"]
    wl, m = lateral(shape, h)
    return deck(f"{'elastic-plastic' if plastic else 'elastic'} wave, {n} cells per unit", nx * m * m, 1,
                (0.0, Lb + 2 * h, 0.0, wl, 0.0, wl), h, 0.9, tend, [mat],
                [f"part bloc 1 1 {w['rho']!r} {dp!r} 0 0 0 {nx} {m} {m}"], fix=(2, 0, 2, 2, 2, 2),
                velo=[f"body 1 {-v0!r} 0 0"], shape=shape)


def wave_snap_times():
    k = wave_consts()
    Lb = WAVE["Lbar"]
    return (0.35 * Lb / k["cl"], 0.8 * Lb / k["cl"])


def slice_mean(X, f):
    """Profile of a 1D deck: the distinct reference positions X of its x-slices (sorted)
    and the mean of f over the particles of each slice (2 x 2 or, for GIMP, 4 x 4 of them),
    so the answer does not depend on the cross-section."""
    Xs, inv = np.unique(X, return_inverse=True)
    return Xs, np.bincount(inv, weights=f) / np.bincount(inv)


def _front(X, v, level):
    """Largest X where the slice-mean v crosses `level` going from above to below."""
    X, v = slice_mean(X, v)
    idx = np.where((v[:-1] >= level) & (v[1:] < level))[0]
    if len(idx) == 0:
        return float("nan")
    i = idx[-1]
    f = (v[i] - level) / (v[i] - v[i + 1])
    return float(X[i] + f * (X[i + 1] - X[i]))


def wave_analyse(r, plastic=False):
    k = wave_consts()
    v0 = WAVE["v0p"] if plastic else WAVE["v0"]
    out = {}
    fronts = []
    for j in range(2):
        s = r.snapshot(j)
        X, v = s["X0"][:, 0], s["v"][:, 0]
        if not plastic:
            fronts.append((s["t"], _front(X, v, -0.5 * v0), None))
        else:
            fe = _front(X, v, -v0 + 0.5 * k["vhel"])
            fp = _front(X, v, -0.5 * (v0 - k["vhel"]))
            fronts.append((s["t"], fe, fp))
            if j == 1:
                gap = fe - fp
                sel = (X > fp + 0.25 * gap) & (X < fe - 0.25 * gap)
                out["hel"] = float(np.mean(-s["sig"][sel, 0])) if sel.any() else float("nan")
                out["hel_exact"] = k["hel"]
                out["profile"] = (X, -s["sig"][:, 0])
    (t1, e1, p1), (t2, e2, p2) = fronts
    out["cl"] = (e2 - e1) / (t2 - t1)
    out["cl_exact"] = k["cl"]
    out["error"] = abs(out["cl"] - k["cl"]) / k["cl"]
    if plastic:
        out["cb"] = (p2 - p1) / (t2 - t1)
        out["cb_exact"] = k["cb"]
        out["cb_error"] = abs(out["cb"] - k["cb"]) / k["cb"]
        out["hel_error"] = abs(out["hel"] - k["hel"]) / k["hel"]
        out["error"] = out["hel_error"]
    return out


# ------------------------------------------------------------------ 4. colliding spheres
# Two elastic spheres (R = 0.2, rho = 1000, E = 1000, nu = 0.3) approach along x at
# +-v0 = 0.1 with a gap of 0.1; one velocity field (no contact algorithm), free faces.

SPH = dict(R=0.2, rho=1000.0, E=1000.0, nu=0.3, v0=0.1, T=2.5)


def spheres_deck(n, shape="linear"):
    s = SPH
    h = 1.0 / n
    dp = h / 2
    nr = int(round(s["R"] / dp))
    cnt = sphere_count(nr)
    mat = f"elas {s['rho']!r} {s['E']!r} {s['nu']!r}"
    return deck(f"colliding spheres, {n} cells per unit", 2 * cnt, 1, (-0.5, 1.5, 0.0, 1.0, 0.0, 1.0), h, 0.9,
                s["T"], [mat], [f"part sphe 1 1 {s['rho']!r} {dp!r} 0.25 0.5 0.5 {nr}",
                                f"part sphe 1 1 {s['rho']!r} {dp!r} 0.75 0.5 0.5 {nr}"],
                velo=[f"body 1 {s['v0']!r} 0 0", f"body 2 {-s['v0']!r} 0 0"], shape=shape)


def spheres_analyse(r):
    s = r.series
    te, et = centred_energy(s)
    E0 = et[0]
    pscale = r.info["mass_initial"] * SPH["v0"] / 2
    dp = np.sqrt((s["px"] - s["px"][0]) ** 2 + (s["py"] - s["py"][0]) ** 2 + (s["pz"] - s["pz"][0]) ** 2)
    return dict(error=float(abs(et[-1] - E0) / E0), energy_maxdev=float(np.max(np.abs(et - E0)) / E0),
                momentum_error=float(dp.max() / pscale), kinetic_final=float(s["kinetic"][-1] / E0),
                t=s["t"], ke=s["kinetic"] / E0, ie=s["internal"] / E0, te=te, et=et / E0)


# ------------------------------------------------------------------ 5. Sod shock tube
# Ideal gas (gamma 1.4) as a null material with the linear polynomial EOS
# p = (C4 + C5 mu) e = (gamma - 1) rho/rho0 e, left rho 1 p 1, right rho 0.125 p 0.1,
# interface at x = 0.5, t = 0.2; artificial bulk viscosity.

SOD = dict(gamma=1.4, rhoL=1.0, pL=1.0, rhoR=0.125, pR=0.1, T=0.2)


def sod_deck(n, shape="linear"):
    g = SOD["gamma"]
    h = 1.0 / n
    dp = h / 2
    nx = n  # particles per half (2 per cell)
    eL, eR = SOD["pL"] / (g - 1), SOD["pR"] / (g - 1)
    cL = math.sqrt(g * SOD["pL"] / SOD["rhoL"])
    w, m = lateral(shape, h)
    return deck(f"Sod shock tube, {n} cells", 2 * nx * m * m, 2, (0.0, 1.0, 0.0, w, 0.0, w), h, 0.3, SOD["T"],
                [f"null {SOD['rhoL']!r} {cL!r}", f"null {SOD['rhoR']!r} {cL!r}"],
                [f"part bloc 1 1 {SOD['rhoL']!r} {dp!r} 0 0 0 {nx} {m} {m}",
                 f"part bloc 1 2 {SOD['rhoR']!r} {dp!r} 0.5 0 0 {nx} {m} {m}"],
                fix=(2, 2, 2, 2, 2, 2), shape=shape, extra=["bulk 1.5 0.06"],
                seos=[f"seos 1 1 0 0 0 0 {g - 1!r} {g - 1!r} 0 {eL!r}",
                      f"seos 2 1 0 0 0 0 {g - 1!r} {g - 1!r} 0 {eR!r}"])


def sod_exact(x, t, x0=0.5):
    """Exact Riemann solution (density) of the Sod problem (Toro, chapter 4)."""
    g = SOD["gamma"]
    rL, pL, rR, pR = SOD["rhoL"], SOD["pL"], SOD["rhoR"], SOD["pR"]
    aL, aR = math.sqrt(g * pL / rL), math.sqrt(g * pR / rR)

    def f(p, r, pk, a):
        if p > pk:
            A, B = 2 / ((g + 1) * r), (g - 1) / (g + 1) * pk
            return (p - pk) * math.sqrt(A / (p + B))
        return 2 * a / (g - 1) * ((p / pk) ** ((g - 1) / (2 * g)) - 1)

    lo, hi = 1e-8, 10.0
    for _ in range(200):
        pm = 0.5 * (lo + hi)
        if f(pm, rL, pL, aL) + f(pm, rR, pR, aR) > 0:
            hi = pm
        else:
            lo = pm
    um = 0.5 * (f(pm, rR, pR, aR) - f(pm, rL, pL, aL))
    rmL = rL * (pm / pL) ** (1 / g)
    rmR = rR * ((pm / pR + (g - 1) / (g + 1)) / ((g - 1) / (g + 1) * pm / pR + 1))
    S = (rmR * um) / (rmR - rR)  # shock speed from mass conservation (right state at rest)
    amL = aL * (pm / pL) ** ((g - 1) / (2 * g))
    out = np.empty_like(x)
    for i, xi in enumerate(x):
        s = (xi - x0) / t
        if s < -aL:
            out[i] = rL
        elif s < um - amL:
            out[i] = rL * (2 / (g + 1) + (g - 1) / ((g + 1) * aL) * (0 - s)) ** (2 / (g - 1))
        elif s < um:
            out[i] = rmL
        elif s < S:
            out[i] = rmR
        else:
            out[i] = rR
    return out


def sod_analyse(r):
    s = r.snapshot(0)
    x = s["x"][:, 0]
    rho = s["mass"] / s["vol"]
    ex = sod_exact(x, s["t"])
    return dict(error=float(np.mean(np.abs(rho - ex))), x=x, rho=rho, exact=ex)


# ------------------------------------------------------------------ 6. Taylor bar

TAYLOR_MODELS = (("coarse", 0.271428571428571), ("medium", 0.1652), ("fine", None))
EXPERIMENT = dict(L=16.2, D=13.5)


def taylor_dp(deckpath):
    with open(deckpath) as f:
        for line in f:
            t = line.replace(",", " ").split()
            if len(t) > 5 and t[0].lower().startswith("part") and t[1].lower().startswith("cyli"):
                return float(t[5])
    raise ValueError(f"{deckpath}: no 'part cyli' card")


def read_profile(path):
    if not os.path.exists(path):
        return None
    d = np.loadtxt(path)
    return d[:, 0], d[:, 1]


# ------------------------------------------------------------------ stability cases
# (their decks: verification_stability.py)

def grid_cfl_limit(nu=0.3, ppc=2):
    """Largest stable dt * c_L / h of the central-difference update on a uniform grid with
    lumped node masses and `ppc`^3 particles per cell as quadrature points (trilinear
    shape functions), from the highest frequency over plane waves (a Fourier scan)."""
    E, rho, h = 1.0, 1.0, 1.0
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    G = E / (2 * (1 + nu))
    D = np.zeros((6, 6))
    D[:3, :3] = lam
    for i in range(3):
        D[i, i] += 2 * G
        D[3 + i, 3 + i] = G
    nodes = [(a, b, c) for c in (0, 1) for b in (0, 1) for a in (0, 1)]
    q = [(i + 0.5) / ppc for i in range(ppc)]
    Ke = np.zeros((24, 24))
    for qx in q:
        for qy in q:
            for qz in q:
                B = np.zeros((6, 24))
                for k, (a, b, c) in enumerate(nodes):
                    w = [(1 - qx, qx)[a], (1 - qy, qy)[b], (1 - qz, qz)[c]]
                    g = [(-1, 1)[a], (-1, 1)[b], (-1, 1)[c]]
                    dN = [g[0] * w[1] * w[2], w[0] * g[1] * w[2], w[0] * w[1] * g[2]]
                    B[0, 3 * k], B[1, 3 * k + 1], B[2, 3 * k + 2] = dN
                    B[3, 3 * k + 1], B[3, 3 * k + 2] = dN[2], dN[1]
                    B[4, 3 * k], B[4, 3 * k + 2] = dN[2], dN[0]
                    B[5, 3 * k], B[5, 3 * k + 1] = dN[1], dN[0]
                Ke += B.T @ D @ B * (h ** 3 / ppc ** 3)
    M = rho * h ** 3
    wmax = 0.0
    ks = np.linspace(0, 2 * PI, 13)
    for kx in ks:
        for ky in ks:
            for kz in ks:
                K = np.zeros((3, 3), complex)
                for a, na in enumerate(nodes):
                    for b, nb in enumerate(nodes):
                        ph = np.exp(1j * (kx * (nb[0] - na[0]) + ky * (nb[1] - na[1]) + kz * (nb[2] - na[2])))
                        K += Ke[3 * a:3 * a + 3, 3 * b:3 * b + 3] * ph
                wmax = max(wmax, math.sqrt(max(np.linalg.eigvalsh(K).max(), 0) / M))
    cl = math.sqrt((lam + 2 * G) / rho)
    return 2.0 / wmax * cl / h


def example_decks():
    """The decks of the suite at one representative resolution, as (folder, name, text):
    written to inputs/verification/ and inputs/stability/ by tools/report.py. They run with
    `mpm3d` as they are, except the manufactured solution, whose body force needs the
    driver (`mpm3d_verify deck --mms 0.01,1.0`)."""
    saved = BAR["v0"]
    BAR["v0"] = 0.01
    out = [("verification", "vibrating_bar_16", bar_deck(16, periods=2, dtsc=0.5))]
    BAR["v0"] = saved
    out += [("verification", "mms_16", mms_deck(16)),
            ("verification", "wave_elastic_50", wave_deck(50)),
            ("verification", "wave_plastic_100", wave_deck(100, plastic=True)),
            ("verification", "spheres_20", spheres_deck(20)),
            ("verification", "sod_100", sod_deck(100)),
            ("stability", "block_stiff", blocks_deck(E=2.0e5)[0]),
            ("stability", "block_nu04999", blocks_deck(nu=0.4999)[0]),
            ("stability", "hypervelocity", hypervelocity_deck(dtsc=0.3)),
            ("stability", "detonation", detonation_deck()),
            ("stability", "single_particle", single_particle_deck()),
            ("stability", "sparse_block", sparse_block_deck()),
            ("stability", "leaving_grid", leaving_deck())]
    return out
