"""The decks of the stability cases of the verification and stability suite
(tools/verification.py, which imports these names; make report runs them into
docs/STABILITY.md): stiff and nearly incompressible blocks, hypervelocity impact,
detonation, a single particle, a sparse spinning block, a block leaving the grid.
"""
import math

from verification_decks import deck, sphere_count

PI = math.pi


# ------------------------------------------------------------------ stability cases

def blocks_deck(E=200.0, nu=0.3, rho=1.0, n=8, v0=None, dtsc=0.5, steps_time=None, scheme="musl", shape="linear",
                title="breathing block"):
    """A free elastic block of n^3 particles (2 per cell, side l = n h / 2) with the initial
    velocity v_a = v0 cos(pi X_a / l) on each axis (zero momentum, a volumetric breathing
    motion that loads the bulk modulus), v0 = 1 % of c_L unless given; runs four wave
    transits of the block (or steps_time)."""
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    G = E / (2 * (1 + nu))
    cl = math.sqrt((lam + 2 * G) / rho)
    v0 = v0 if v0 is not None else 0.01 * cl
    h = 1.0 / 8
    dp = h / 2
    side = n * dp
    o = 1.0
    T = steps_time if steps_time else 4 * side / cl
    velo = []
    c = [math.cos(PI * (i + 0.5) / n) for i in range(n)]
    # A deck of the current version (bimp, sgmp) numbers a block's particles x fastest, the
    # book's z fastest.
    current = shape in ("bimp", "sgmp")
    for i in range(n):
        for j in range(n):
            for k in range(n):
                num = (k * n + j) * n + i + 1 if current else (i * n + j) * n + k + 1
                velo.append(f"node {num} {v0 * c[i]!r} {v0 * c[j]!r} {v0 * c[k]!r}")
    box = (0.0, side + 2.0, 0.0, side + 2.0, 0.0, side + 2.0)
    return deck(title, n ** 3, 1, box, h, dtsc, T, [f"elas {rho!r} {E!r} {nu!r}"],
                [f"part bloc 1 1 {rho!r} {dp!r} {o!r} {o!r} {o!r} {n} {n} {n}"],
                velo=velo, scheme=scheme, shape=shape), cl


def hypervelocity_deck(dp=0.25, dtsc=0.9, shape="linear"):
    """Aluminium sphere (R 1.5 mm) on an aluminium plate (12 x 12 x 2 mm) at 6.18 km/s.
    Units mm g N ms MPa. Aluminium: rho 2.7e-3, E 70 GPa, nu 0.33, J2 yield 300 MPa,
    Mie-Gruneisen c0 5328 m/s, s 1.338, gamma0 2.0. Ends after 2 microseconds."""
    nr = int(round(1.5 / dp))
    ns = sphere_count(nr)
    nxy = int(round(12.0 / dp))
    nz = int(round(2.0 / dp))
    h = 2 * dp
    mat = "pla1 2.7d-3 70.0d3 0.33 300.0"
    return deck("hypervelocity impact, Al sphere on Al plate, 6.18 km/s", ns + nxy * nxy * nz, 1,
                (-8.0, 8.0, -8.0, 8.0, -8.0, 6.0), h, dtsc, 0.002, [mat],
                [f"part bloc 1 1 2.7d-3 {dp!r} -6.0 -6.0 -2.0 {nxy} {nxy} {nz}",
                 f"part sphe 1 1 2.7d-3 {dp!r} 0.0 0.0 {1.5 + 0.5 * dp!r} {nr}"],
                velo=["body 2 0.0 0.0 -6180.0"], seos=["seos 1 2 5328.0 1.338 2.0 0.0"], shape=shape)


def detonation_deck(shape="linear"):
    """1D TNT slab (hiex + JWL) detonated at one end, 400 particles; needs hiex/JWL/deto."""
    n = 100
    dp = 0.25
    h = 2 * dp
    return deck("detonation of a TNT slab", n * 4, 1, (0.0, 30.0, 0.0, h, 0.0, h), h, 0.3, 0.003,
                ["hiex 1.63d-3 6930.0"], [f"part bloc 1 1 1.63d-3 {dp!r} 0 0 0 {n} 2 2"],
                fix=(2, 0, 2, 2, 2, 2), seos=["seos 1 3 3.712d5 3.231d3 4.15 0.95 0.30 7.0d3"],
                extra=["deto 0.0 0.125 0.125", "bulk 1.5 0.06"], shape=shape)


def single_particle_deck(shape="linear"):
    """One particle flying diagonally through 20 cells: x = x0 + v t exactly."""
    return deck("single particle crossing cells", 1, 1, (0.0, 24.0, 0.0, 24.0, 0.0, 24.0), 1.0, 0.9, 2.0,
                ["elas 1.0 100.0 0.25"], ["part poin 1 1  1 1 0.125 1.3 1.7 2.2"],
                velo=["node 1 10.0 7.3 -0.4"], shape=shape)


def sparse_block_deck(shape="linear"):
    """An elastic block with one particle per cell, spinning and drifting: cells empty and
    fill again every step, some nodes carry one particle's mass."""
    n = 6
    h = 1.0
    velo = []
    xc = 8.0 + n * h / 2
    w = 2.0  # spin rate about z through the block centre
    for i in range(n):
        for j in range(n):
            for k in range(n):
                x, y = 8.0 + (i + 0.5) * h, 8.0 + (j + 0.5) * h
                velo.append(f"node {(i * n + j) * n + k + 1} {3.0 - w * (y - xc)!r} {w * (x - xc)!r} 1.0")
    return deck("sparse spinning block (1 particle per cell)", n ** 3, 1, (0.0, 24.0, 0.0, 24.0, 0.0, 24.0), h, 0.9,
                1.0, ["elas 1.0 100.0 0.25"], [f"part bloc 1 1 1.0 {h!r} 8.0 8.0 8.0 {n} {n} {n}"], velo=velo,
                shape=shape)


def leaving_deck(shape="linear"):
    """A block flies out through the open face x = 6 of the grid."""
    return deck("block leaving the grid", 64, 1, (0.0, 6.0, 0.0, 6.0, 0.0, 6.0), 1.0, 0.9, 0.5,
                ["elas 1.0 100.0 0.25"], ["part bloc 1 1 1.0 0.5 3.0 2.0 2.0 4 4 4"],
                velo=["body 1 10.0 0.5 0.0"], shape=shape)
