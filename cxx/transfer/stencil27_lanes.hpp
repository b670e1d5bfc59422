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
#include "stages/patch_index.hpp"

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

}  // namespace

// transfer_lanes_avx2.cpp: stencil27_block for AVX2 (lanes_use_avx2()).
void stencil27_block_avx2(const StepContext* c, const int* part, int n, bool gradients, Stencil27Block& s);

}  // namespace mpm3d
