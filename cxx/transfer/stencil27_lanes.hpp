// The 27-node stencils (uGIMP, quadratic B-spline) of kStencilLanes particles at once:
// each particle's offsets and 1-D weights one lane after the other (gimp_1d,
// bspline_1d: their branches differ by lane), then the tensor products of shape_27 in
// vector lanes. A lane performs its particle's scalar products in the scalar order, so
// the weights are shape_27's bits. The block holds node k of lane i at [k][i]; the
// particle loops of stencil27.cpp read a lane with stride kStencilLanes. Compiled for the
// baseline instruction set in stencil27.cpp and for AVX2 in transfer_lanes_avx2.cpp.
#pragma once
#include "core/grid.hpp"
#include "core/lanes.hpp"
#include "core/patch_index.hpp"
#include "transfer/transfer_lanes.hpp"

namespace mpm3d {

constexpr int kStencilLanes = 4;

struct Stencil27Block {
  int ci[3][kStencilLanes], o[3][kStencilLanes];  // cell and stencil offsets per axis
  alignas(32) double N[27][kStencilLanes];
  alignas(32) double G[81][kStencilLanes];
};

namespace {

// Lanes first .. first + TL::W - 1 of s from particles part[0 .. TL::W), whose cells the
// caller has put in s.ci; gradients false: the weights alone (G left unset).
template <class TL>
void stencil27_lanes(const StepContext* c, const int* part, bool gradients, Stencil27Block& s, int first) {
  typedef decltype(TL::splat(0.0)) T;
  alignas(32) double w[3][3][kStencilLanes], g[3][3][kStencilLanes];  // axis, node, lane
  const int shape = c->method.shape;
  const double inv_h = c->grid.inv_h;
  for (int i = 0; i < TL::W; ++i) {
    const int p = part[i], l = first + i;
    const int ci[3] = {s.ci[0][l], s.ci[1][l], s.ci[2][l]};
    int o[3];
    const double* lx = c->part.lx + 3 * p;
    stencil_27_offsets(shape, ci, lx, c->grid.nc, o);
    const double lp_cells = shape == 1 ? c->part.psize[p] * inv_h : 0.0;
    for (int a = 0; a < 3; ++a) {
      double wa[3], ga[3];
      if (shape == 2)
        bspline_1d(lx[a], o[a], inv_h, wa, ga);
      else
        gimp_1d(lx[a], o[a], lp_cells, inv_h, wa, ga);
      for (int k = 0; k < 3; ++k) w[a][k][l] = wa[k], g[a][k][l] = ga[k];
      s.o[a][l] = o[a];
    }
  }
  T wx[3], wy[3], wz[3];
  for (int k = 0; k < 3; ++k) {
    wx[k] = TL::load(&w[0][k][first]);
    wy[k] = TL::load(&w[1][k][first]);
    wz[k] = TL::load(&w[2][k][first]);
  }
  if (!gradients) {
    for (int cc = 0; cc < 3; ++cc)
      for (int b = 0; b < 3; ++b)
        for (int a = 0; a < 3; ++a) TL::store(&s.N[a + 3 * b + 9 * cc][first], (wx[a] * wy[b]) * wz[cc]);
    return;
  }
  T gx[3], gy[3], gz[3];
  for (int k = 0; k < 3; ++k) {
    gx[k] = TL::load(&g[0][k][first]);
    gy[k] = TL::load(&g[1][k][first]);
    gz[k] = TL::load(&g[2][k][first]);
  }
  for (int cc = 0; cc < 3; ++cc)
    for (int b = 0; b < 3; ++b)
      for (int a = 0; a < 3; ++a) {
        const int k = a + 3 * b + 9 * cc;
        const T wxy = wx[a] * wy[b];
        TL::store(&s.N[k][first], wxy * wz[cc]);
        TL::store(&s.G[3 * k + 0][first], (gx[a] * wy[b]) * wz[cc]);
        TL::store(&s.G[3 * k + 1][first], (wx[a] * gy[b]) * wz[cc]);
        TL::store(&s.G[3 * k + 2][first], wxy * gz[cc]);
      }
}

// The stencils of particles part[0 .. n), n <= kStencilLanes, their cells in s.ci: a full
// block in vector lanes, a shorter one lane by lane (the same bits).
template <class VL>
void stencil27_block(const StepContext* c, const int* part, int n, bool gradients, Stencil27Block& s) {
  if (n == kStencilLanes)
    stencil27_lanes<VL>(c, part, gradients, s, 0);
  else
    for (int i = 0; i < n; ++i) stencil27_lanes<ScalarLane>(c, part + i, gradients, s, i);
}

// Grid node index of lane l's first stencil node (a = b = c = 0).
inline int block_grid_corner(const StepContext* c, const Stencil27Block& s, int l) {
  return (s.ci[0][l] + s.o[0][l]) + c->grid.nn[0] * ((s.ci[1][l] + s.o[1][l]) + c->grid.nn[1] * (s.ci[2][l] + s.o[2][l]));
}

// G2P of the particles part[0 .. TL::W) in lanes first.. of s: the sums of N f / m and
// N p / m over the nodes above the mass cut-off (node k of a lane at its corner + of[k]:
// g2p_node_lanes), then advance_particle's update of each (advance_lanes).
template <class TL>
void g2p27_lanes(StepContext* c, const Stencil27Block& s, const int* part, const int* of, int first) {
  typedef decltype(TL::splat(0.0)) T;
  int base[kStencilLanes], n1[kStencilLanes], n3[kStencilLanes], i3[kStencilLanes];
  for (int i = 0; i < TL::W; ++i) base[i] = block_grid_corner(c, s, first + i), i3[i] = 3 * part[i];
  T acc[6];
  for (int d = 0; d < 6; ++d) acc[d] = TL::splat(0.0);
  for (int k = 0; k < 27; ++k) {
    for (int i = 0; i < TL::W; ++i) n1[i] = base[i] + of[k], n3[i] = 3 * n1[i];
    g2p_node_lanes<TL>(c, n1, n3, TL::load(&s.N[k][first]), acc);
  }
  T v[3];
  advance_lanes<TL>(c, part, i3, acc, v);
}

// Velocity gradients L[3a+b][lane] = d v_a / d x_b of lanes first.. of s from the node
// velocities gvel (the scalar sums' order, a light node adding +0.0).
template <class TL>
void gradient27_lanes(const StepContext* c, const Stencil27Block& s, const double* gvel, const int* of,
                      double L[9][kStencilLanes], int first) {
  typedef decltype(TL::splat(0.0)) T;
  int base[kStencilLanes], n1[kStencilLanes], n3[kStencilLanes];
  for (int i = 0; i < TL::W; ++i) base[i] = block_grid_corner(c, s, first + i);
  const double cutoff = c->grid.mass_cutoff;
  const T zero = TL::splat(0.0);
  T l[9];
  for (int r = 0; r < 9; ++r) l[r] = zero;
  for (int k = 0; k < 27; ++k) {
    for (int i = 0; i < TL::W; ++i) n1[i] = base[i] + of[k], n3[i] = 3 * n1[i];
    const auto heavy = TL::gather(c->grid.gmass, n1) > cutoff;
    const T v[3] = {TL::gather(gvel, n3), TL::gather(gvel + 1, n3), TL::gather(gvel + 2, n3)};
    const T g[3] = {TL::load(&s.G[3 * k][first]), TL::load(&s.G[3 * k + 1][first]), TL::load(&s.G[3 * k + 2][first])};
    for (int a = 0; a < 3; ++a)
      for (int d = 0; d < 3; ++d) l[3 * a + d] = l[3 * a + d] + TL::select(heavy, v[a] * g[d], zero);
  }
  for (int r = 0; r < 9; ++r) TL::store(&L[r][first], l[r]);
}

// G2P and the velocity gradients of a block of n particles: all lanes in vectors, a
// shorter block lane by lane (the same bits).
template <class VL>
void g2p27_block(StepContext* c, const Stencil27Block& s, const int* part, int n, const int* of) {
  if (n == kStencilLanes)
    g2p27_lanes<VL>(c, s, part, of, 0);
  else
    for (int i = 0; i < n; ++i) g2p27_lanes<ScalarLane>(c, s, part + i, of, i);
}

template <class VL>
void gradient27_block(const StepContext* c, const Stencil27Block& s, int n, const double* gvel, const int* of,
                      double L[9][kStencilLanes]) {
  if (n == kStencilLanes)
    gradient27_lanes<VL>(c, s, gvel, of, L, 0);
  else
    for (int i = 0; i < n; ++i) gradient27_lanes<ScalarLane>(c, s, gvel, of, L, i);
}

}  // namespace

// transfer_lanes_avx2.cpp: the block kernels above for AVX2 (lanes_use_avx2()).
void stencil27_block_avx2(const StepContext* c, const int* part, int n, bool gradients, Stencil27Block& s);
void g2p27_block_avx2(StepContext* c, const Stencil27Block& s, const int* part, int n, const int* of);
void gradient27_block_avx2(const StepContext* c, const Stencil27Block& s, int n, const double* gvel, const int* of,
                           double L[9][kStencilLanes]);

}  // namespace mpm3d
