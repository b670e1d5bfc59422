// Index helpers of the step stages: cell decoding, node and patch-buffer indices, the nodes
// a patch owns, and the 27-node GIMP stencil. Internal linkage, so the AVX2 unit
// (transfer_lanes_avx2.cpp) compiles its own copies (see lanes.hpp).
#pragma once
#include <cstddef>
#include <cstdint>

#include "core/grid.hpp"
#include "core/step_state.hpp"

namespace mpm3d {
namespace {

// Exact division of a non-negative 32-bit integer by a fixed divisor with one 128-bit
// multiply (Lemire, Kaser & Kurz 2019): the integer index decoding of the hot loops.
// The multiplier ceil(2^64 / d) does not fit 64 bits for d = 1 (it wrapped to 0, so a grid
// with one cell along y decoded every cell to k = 0): d = 1 is the identity.
struct FastDiv {
  uint64_t m;
  bool one;
  explicit FastDiv(uint32_t d) : m(d == 1 ? 0 : UINT64_C(0xFFFFFFFFFFFFFFFF) / d + 1), one(d == 1) {}
  uint32_t operator()(uint32_t n) const { return one ? n : uint32_t((__uint128_t(m) * n) >> 64); }
};

// Cell index -> (i, j, k).
struct CellDecoder {
  FastDiv div0, div1;
  int nc0, nc1;
  explicit CellDecoder(const StepContext* c)
      : div0(uint32_t(c->grid.nc[0])), div1(uint32_t(c->grid.nc[1])), nc0(c->grid.nc[0]), nc1(c->grid.nc[1]) {}
  void operator()(int cell, int& i, int& j, int& k) const {
    const int r = int(div0(uint32_t(cell)));
    i = cell - r * nc0;
    k = int(div1(uint32_t(r)));
    j = r - k * nc1;
  }
};

// Global node index of the base node of a cell.
inline int base_node(const StepContext* c, const CellDecoder& dec, int cell) {
  int i, j, k;
  dec(cell, i, j, k);
  return i + c->grid.nn[0] * (j + c->grid.nn[1] * k);
}

// Global node index of local node k (offsets a, b, c) relative to a base node.
inline int node_of(const StepContext* c, int base, int k) {
  return base + (k & 1) + c->grid.nn[0] * (((k >> 1) & 1) + c->grid.nn[1] * ((k >> 2) & 1));
}

// Nodes in one patch buffer: (patch_cells + 1 + 2 halo)^3.
inline int patch_nodes(const StepContext* c) {
  const int Q = c->patch.patch_cells + 1 + 2 * c->patch.patch_halo;
  return Q * Q * Q;
}

inline double* patch_buffer(const StepContext* c, int slot) {
  return c->patch.patch_buf + size_t(slot) * size_t(patch_nodes(c)) * kNodeFields;
}

// Local node index, in the buffer of patch (qx, qy, qz), of the base node of a cell.
inline int patch_base(const StepContext* c, const CellDecoder& dec, const int q3[3], int cell) {
  const int P = c->patch.patch_cells, Q = P + 1;
  int i, j, k;
  dec(cell, i, j, k);
  return (i - q3[0] * P) + Q * ((j - q3[1] * P) + Q * (k - q3[2] * P));
}

inline void patch_coords(const StepContext* c, int q, int q3[3]) {
  q3[0] = q % c->patch.npd[0];
  q3[1] = (q / c->patch.npd[0]) % c->patch.npd[1];
  q3[2] = q / (c->patch.npd[0] * c->patch.npd[1]);
}

inline int patch_local(int P, int k) {
  const int Q = P + 1;
  return (k & 1) + Q * (((k >> 1) & 1) + Q * ((k >> 2) & 1));
}

// Nodes owned by patch q: [lo, hi) per axis; the last patch of an axis also owns the
// grid's last node layer. A patch is active when it or one of its seven lower neighbours
// holds particles (GIMP, halo 1: one of its 26 neighbours); nodes of inactive patches are
// never read by any stage, so node loops skip them (their values are left as they were).
struct OwnedNodes {
  int lo[3], hi[3];
  bool active;
};

inline OwnedNodes owned_nodes(const StepContext* c, int q) {
  OwnedNodes o;
  const int P = c->patch.patch_cells;
  int q3[3];
  patch_coords(c, q, q3);
  for (int a = 0; a < 3; ++a) {
    o.lo[a] = q3[a] * P;
    o.hi[a] = q3[a] == c->patch.npd[a] - 1 ? c->grid.nn[a] : o.lo[a] + P;
  }
  o.active = false;
  const int ne = 2 + c->patch.patch_halo;
  for (int cz = 0; cz < ne && !o.active; ++cz)
    for (int cy = 0; cy < ne && !o.active; ++cy)
      for (int cx = 0; cx < ne && !o.active; ++cx) {
        const int px = q3[0] - 1 + cx, py = q3[1] - 1 + cy, pz = q3[2] - 1 + cz;
        if (px >= 0 && py >= 0 && pz >= 0 && px < c->patch.npd[0] && py < c->patch.npd[1] && pz < c->patch.npd[2] &&
            c->patch.patch_slot[px + c->patch.npd[0] * (py + c->patch.npd[1] * pz)] >= 0)
          o.active = true;
      }
  return o;
}

// f(n) for every node n owned by o, in k, j, i order (i fastest).
template <class F>
inline void for_owned_nodes(const StepContext* c, const OwnedNodes& o, F&& f) {
  for (int k = o.lo[2]; k < o.hi[2]; ++k)
    for (int j = o.lo[1]; j < o.hi[1]; ++j)
      for (int i = o.lo[0]; i < o.hi[0]; ++i) f(i + c->grid.nn[0] * (j + c->grid.nn[1] * k));
}

// 27-node stencil of one particle (shape 1 GIMP, 2 B-spline): its cell (i, j, k), the
// stencil offsets o and the 27 weights and gradients; node (a, b, c) of the stencil is grid
// node (i + o0 + a, j + o1 + b, k + o2 + c).
struct GimpStencil {
  int ci[3], o[3];
  double N[27], G[81];
};

// The stencil offsets o of a particle in cell ci with local coordinates lx.
inline void stencil_offsets(const StepContext* c, const int ci[3], const double* lx, int o[3]) {
  stencil_27_offsets(c->method.shape, ci, lx, c->grid.nc, o);
}

// gradients false: the weights alone (G left unset).
inline void gimp_stencil(const StepContext* c, const CellDecoder& dec, int p, GimpStencil& s, bool gradients = true) {
  dec(c->part.cell[p], s.ci[0], s.ci[1], s.ci[2]);
  const double lp_cells = c->method.shape == 1 ? c->part.psize[p] * c->grid.inv_h : 0.0;
  stencil_27(c->method.shape, s.ci, c->part.lx + 3 * p, c->grid.nc, lp_cells, c->grid.inv_h, s.o, s.N,
             gradients ? s.G : nullptr);
}

// Global node index of the stencil's first node (a = b = c = 0).
inline int gimp_corner(const StepContext* c, const GimpStencil& s) {
  return (s.ci[0] + s.o[0]) + c->grid.nn[0] * ((s.ci[1] + s.o[1]) + c->grid.nn[1] * (s.ci[2] + s.o[2]));
}

// Buffer node index, in the buffer of patch q3 (halo 1), of the stencil's first node.
inline int gimp_patch_corner(const StepContext* c, const int q3[3], const GimpStencil& s) {
  const int P = c->patch.patch_cells, H = c->patch.patch_halo, Q = P + 1 + 2 * H;
  return (s.ci[0] + s.o[0] - q3[0] * P + H) +
         Q * ((s.ci[1] + s.o[1] - q3[1] * P + H) + Q * (s.ci[2] + s.o[2] - q3[2] * P + H));
}

// Offset of stencil node k = a + 3 b + 9 c from the stencil's first node, in an array of
// row length r0 and plane size r0 r1.
inline int stencil_offset(int k, int r0, int r1) {
  const int a = k % 3, b = (k / 3) % 3, cc = k / 9;
  return a + r0 * (b + r1 * cc);
}

// All 27 of them, for the loops over a stencil's nodes (no division per node).
struct StencilOffsets {
  int of[27];
  StencilOffsets(int r0, int r1) {
    for (int k = 0; k < 27; ++k) of[k] = stencil_offset(k, r0, r1);
  }
};

}  // namespace
}  // namespace mpm3d
