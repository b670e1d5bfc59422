#!/usr/bin/env python3
"""Cost model of mpm3d's MPI ranks: halo volume against patch volume, for the Taylor bar.

usage: tools/rank_cost_model.py [--ns-per-particle-step 150] [--latency-us 2] [--gbytes-per-s 10]
                                [--ranks 2,3,4,16,64,256,1024] [--check docs/bench/ranks.csv]

The particles of a Taylor bar (radius 3.8, length 25.4, the lattice spacing dp of each model,
cells of 2 dp, patches of 4^3 cells, the decks' boxes) are counted per patch; the ranks' patch
runs are drawn by mpm3d's rule (contiguous patch indices, equal particle shares); for every
rank the model counts what it sends in one MUSL step as cxx/parallel/ does:
- of the buffers of its non-empty patches next to another rank's patches, the nodes inside
  the node spans of that rank's patches (8 bytes x 7 fields for P2G, 3 for the remap; a
  face neighbour's share is one layer of 25 of the 125 nodes), one copy per neighbouring
  rank;
- its contribution to the per-patch particle counts (4 bytes per patch of the grid, an
  MPI_Allreduce) and its own columns of the energy partials (48 bytes per non-empty patch,
  an MPI_Allgatherv), as the summary's rank_bytes_sent_per_step counts them;
- migrating particles are left out (a few KB a step in the measured runs).
A step then costs compute = (the largest rank's particles) x ns per particle-step, plus
communication = messages x latency + (the halo bytes a rank sends and receives + the 4
bytes per patch and 48 per non-empty patch every rank receives from the two per-patch
collectives) / bandwidth, with the
collectives at latency x log2(ranks) each (8 a step). Nothing overlaps (the implementation
waits at each exchange). Efficiency = one rank's compute / (ranks x that step time).
The last two columns are the same model with the two per-patch collectives replaced by
exchanges between neighbouring ranks (counts of the ghost patches only; energy partials
folded in fixed groups of 4096 patches, only the groups split by a rank boundary crossing
ranks): what reaching 1024 ranks would take.
With --check, the predicted bytes are printed beside the measured ones of tools/rank_bench.py's
CSV (its rows with more than one rank).
"""
import argparse
import csv
import math

import numpy as np

P = 4                 # cells per patch edge
OFFSETS = [(dx, dy, dz) for dz in (-1, 0, 1) for dy in (-1, 0, 1) for dx in (-1, 0, 1)]
FIELDS_PER_STEP = 7 + 3  # MUSL: P2G (mass, momentum, force), remap (momentum)
COLLECTIVES = 8          # counts, partials, outside, 2 health mins, signal, (dt max), gather-free
BAR_R, BAR_L = 3.8, 25.4

# name: (particle spacing dp, box half width, box height), as the decks (inputs/taylor; the
# fine one is the paper's 1.16M-particle model); bar_100M: the same bar with 100M particles.
MODELS = {
    "taylor_coarse": (0.271428571428571, 8.142857142857, 26.6),
    "taylor_medium": (0.165217391304348, 8.260869565217, 26.765217391304),
    "taylor_fine": (0.1, 8.2, 26.6),
    "bar_100M": (0.1 * (1155192 / 1.0e8) ** (1.0 / 3.0), 8.2, 26.6),
}


def patch_counts(dp, half, height):
    """Particles per patch (patch index x fastest, z slowest) and the patch grid."""
    h = 2.0 * dp
    nc = [int(math.ceil(2 * half / h - 1e-9)), int(math.ceil(2 * half / h - 1e-9)), int(math.ceil(height / h - 1e-9))]
    npd = [(n + P - 1) // P for n in nc]
    # One lattice layer of the bar's cross-section, then the layers along z.
    n = int(math.floor(BAR_R / dp))
    g = (np.arange(-n, n + 1) * dp)
    X, Y = np.meshgrid(g, g, indexing="xy")
    inside = X ** 2 + Y ** 2 <= BAR_R ** 2 + 1e-12
    px = ((X[inside] + half) / (h * P)).astype(int)
    py = ((Y[inside] + half) / (h * P)).astype(int)
    col = np.zeros((npd[1], npd[0]), dtype=np.int64)
    np.add.at(col, (py, px), 1)
    zs = np.arange(0.0, BAR_L + 1e-9, dp)
    lay = np.bincount((zs / (h * P)).astype(int), minlength=npd[2])[: npd[2]]
    counts = (lay[:, None, None] * col[None, :, :]).astype(np.int64)  # [z, y, x]
    return counts.reshape(-1), npd


def partition(counts, ranks):
    prefix = np.concatenate([[0], np.cumsum(counts)])
    total = prefix[-1]
    first = [int(np.searchsorted(prefix[:-1], total * u // ranks, side="left")) for u in range(ranks)]
    first[0] = 0
    first.append(len(counts))
    owner = np.zeros(len(counts), dtype=np.int64)
    for u in range(ranks):
        owner[first[u]:first[u + 1]] = u
    return first, owner


def span_nodes(code):
    """Nodes of a patch buffer ((P + 1)^3, trilinear) inside the node spans of the
    neighbours whose OFFSETS index has its bit set in code: neighbour d's span is local
    d P .. d P + P per axis."""
    mark = np.zeros((P + 1,) * 3, dtype=bool)
    for i, d in enumerate(OFFSETS):
        if code >> i & 1:
            lo = [max(0, e * P) for e in d]
            hi = [min(P, e * P + P) for e in d]
            mark[lo[2]:hi[2] + 1, lo[1]:hi[1] + 1, lo[0]:hi[0] + 1] = True
    return int(mark.sum())


def per_rank_sends(counts, npd, owner, ranks):
    """Per rank: buffer nodes sent, (patch, neighbouring rank) pairs and neighbouring ranks."""
    nz, ny, nx = npd[2], npd[1], npd[0]
    own = owner.reshape(nz, ny, nx)
    filled = (counts > 0).reshape(nz, ny, nx)
    zz, yy, xx = np.nonzero(filled)
    pq, pa, pb = [], [], []  # the (patch, sending rank, receiving rank) pairs
    for dx, dy, dz in OFFSETS:
        z2, y2, x2 = zz + dz, yy + dy, xx + dx
        ok = (z2 >= 0) & (z2 < nz) & (y2 >= 0) & (y2 < ny) & (x2 >= 0) & (x2 < nx)
        a = own[zz[ok], yy[ok], xx[ok]]
        b = own[z2[ok], y2[ok], x2[ok]]
        q = (zz[ok] * ny + yy[ok]) * nx + xx[ok]
        pq.append(q[a != b]), pa.append(a[a != b]), pb.append(b[a != b])
    key = np.unique(np.stack([np.concatenate(pq), np.concatenate(pb), np.concatenate(pa)]), axis=1)
    q, b, a = key
    # Which of q's 27 neighbours (itself included) rank b owns: one bit each.
    qz, qy, qx = q // (nx * ny), (q // nx) % ny, q % nx
    code = np.zeros(len(q), dtype=np.int64)
    for i, (dx, dy, dz) in enumerate(OFFSETS):
        z2, y2, x2 = qz + dz, qy + dy, qx + dx
        ok = (z2 >= 0) & (z2 < nz) & (y2 >= 0) & (y2 < ny) & (x2 >= 0) & (x2 < nx)
        o = np.full(len(q), -1)
        o[ok] = own[z2[ok], y2[ok], x2[ok]]
        code |= (o == b).astype(np.int64) << i
    codes, inverse = np.unique(code, return_inverse=True)
    nodes = np.array([span_nodes(int(c)) for c in codes])[inverse]
    sent = np.bincount(a, weights=nodes, minlength=ranks)
    nbrs = [len(set(b[a == u].tolist())) for u in range(ranks)]
    return sent, np.bincount(a, minlength=ranks), nbrs


def model(counts, npd, ranks, ns_pp, lat, bw):
    npatch = len(counts)
    first, owner = partition(counts, ranks)
    mine = np.array([counts[first[u]:first[u + 1]].sum() for u in range(ranks)])
    nodes, pairs, nbrs = per_rank_sends(counts, npd, owner, ranks)
    halo = nodes * 8 * FIELDS_PER_STEP
    filled = counts > 0
    cols = np.array([np.count_nonzero(filled[first[u]:first[u + 1]]) + (u == ranks - 1) for u in range(ranks)])
    sent = halo + (npatch + 1) * 4 + cols * 48
    compute = mine.max() * ns_pp * 1e-9
    latency = (2 * max(nbrs) * 2) * lat + COLLECTIVES * lat * math.log2(ranks)
    comm = latency + (2 * halo.max() + npatch * 4 + cols.sum() * 48) / bw
    # Neighbour-only counts (4 bytes per halo patch) and grouped partials (48 bytes per group).
    comm_scalable = latency + (2 * halo.max() + pairs.max() * 4 + (npatch // 4096 + 1) * 48) / bw
    serial = counts.sum() * ns_pp * 1e-9
    return {"imbalance": mine.max() * ranks / counts.sum(), "bytes_sent": sent.max(), "halo_bytes": halo.max(),
            "compute_s": compute, "comm_s": comm, "efficiency": serial / (ranks * (compute + comm)),
            "comm_scalable_s": comm_scalable, "efficiency_scalable": serial / (ranks * (compute + comm_scalable))}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ns-per-particle-step", type=float, default=150.0)
    ap.add_argument("--latency-us", type=float, default=2.0)
    ap.add_argument("--gbytes-per-s", type=float, default=10.0)
    ap.add_argument("--ranks", default="2,3,4,16,64,256,1024")
    ap.add_argument("--check")
    a = ap.parse_args()
    lat, bw = a.latency_us * 1e-6, a.gbytes_per_s * 1e9
    ranks = [int(r) for r in a.ranks.split(",")]
    print("model,particles,patches,ranks,imbalance,bytes_sent_per_step_per_rank,halo_bytes_per_step_per_rank,"
          "compute_ms,comm_ms,efficiency,comm_ms_neighbour_only,efficiency_neighbour_only")
    for name, (dp, half, height) in MODELS.items():
        counts, npd = patch_counts(dp, half, height)
        for r in ranks:
            if r > np.count_nonzero(counts):
                continue
            m = model(counts, npd, r, a.ns_per_particle_step, lat, bw)
            print(f"{name},{counts.sum()},{len(counts)},{r},{m['imbalance']:.3f},{m['bytes_sent']:.0f},"
                  f"{m['halo_bytes']:.0f},{m['compute_s'] * 1e3:.3f},{m['comm_s'] * 1e3:.3f},{m['efficiency']:.3f},"
                  f"{m['comm_scalable_s'] * 1e3:.3f},{m['efficiency_scalable']:.3f}")
    if a.check:
        with open(a.check) as f:
            for row in csv.DictReader(f):
                if int(row["ranks"]) < 2:
                    continue
                name = next(k for k in MODELS if k.startswith(row["deck"].replace(".mpm", "")))
                counts, npd = patch_counts(*MODELS[name])
                m = model(counts, npd, int(row["ranks"]), a.ns_per_particle_step, lat, bw)
                print(f"check {row['deck']} ranks {row['ranks']}: measured {float(row['bytes_per_step_per_rank']):.0f} "
                      f"bytes a step, model {m['bytes_sent']:.0f}")


if __name__ == "__main__":
    main()
