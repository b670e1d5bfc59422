// GridData: trilinear shape functions of the 8 nodes of a cell.
// Local node k = a + 2 b + 4 c sits at offset (a, b, c) h from the cell's base node;
// N_k = wx_a wy_b wz_c with w_0 = 1 - l, w_1 = l; dN_k/dx = (+-1/h) wy_b wz_c, etc.
#include <gtest/gtest.h>

#include <cmath>
#include <array>
#include <random>
#include <vector>

#include "core/grid.hpp"
#include "core/patch_index.hpp"
#include "transfer/smoothed_gradient.hpp"

namespace {

std::vector<std::array<double, 3>> sample_points() {
  std::vector<std::array<double, 3>> pts = {
      {0.0, 0.0, 0.0}, {0.5, 0.5, 0.5}, {0.25, 0.75, 0.125}, {0.999999, 1e-7, 0.5}, {0.1, 0.2, 0.3}};
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 200; ++i) pts.push_back({u(rng), u(rng), u(rng)});
  return pts;
}

}  // namespace

TEST(Shape, PartitionOfUnityAndGradientsSumToZero) {
  const double h = 0.76, inv_h = 1.0 / h;
  for (const auto& lx : sample_points()) {
    double N[8], G[24];
    mpm3d::shape_linear(lx.data(), inv_h, N, G);
    double sum = 0, gs[3] = {0, 0, 0};
    for (int k = 0; k < 8; ++k) {
      EXPECT_GE(N[k], 0.0);
      EXPECT_LE(N[k], 1.0);
      sum += N[k];
      for (int a = 0; a < 3; ++a) gs[a] += G[3 * k + a];
    }
    EXPECT_NEAR(sum, 1.0, 4e-16);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(gs[a], 0.0, 4e-16 * inv_h);
  }
}

TEST(Shape, KroneckerAtTheNodes) {
  // At the position of node j (lx = its offset) N_j = 1 and every other N_k = 0, exactly.
  for (int j = 0; j < 8; ++j) {
    const double lx[3] = {double(j & 1), double((j >> 1) & 1), double((j >> 2) & 1)};
    double N[8], G[24];
    mpm3d::shape_linear(lx, 2.0, N, G);
    for (int k = 0; k < 8; ++k) EXPECT_EQ(N[k], k == j ? 1.0 : 0.0) << "node " << k << " at node " << j;
  }
}

TEST(Shape, ValuesAndGradientsByHand) {
  // lx = (0.25, 0.5, 0.75), h = 2: wx = (0.75, 0.25), wy = (0.5, 0.5), wz = (0.25, 0.75).
  // N_0 = 0.75 * 0.5 * 0.25 = 0.09375; N_7 = 0.25 * 0.5 * 0.75 = 0.09375;
  // N_1 = 0.25 * 0.5 * 0.25 = 0.03125; N_6 (a=0,b=1,c=1) = 0.75 * 0.5 * 0.75 = 0.28125.
  // dN_0/dx = -0.5 * 0.5 * 0.25 = -0.0625, dN_0/dz = 0.75 * 0.5 * -0.5 = -0.1875.
  const double lx[3] = {0.25, 0.5, 0.75};
  double N[8], G[24];
  mpm3d::shape_linear(lx, 0.5, N, G);
  EXPECT_EQ(N[0], 0.09375);
  EXPECT_EQ(N[7], 0.09375);
  EXPECT_EQ(N[1], 0.03125);
  EXPECT_EQ(N[6], 0.28125);
  EXPECT_EQ(G[0], -0.0625);
  EXPECT_EQ(G[1], -0.5 * 0.75 * 0.25);
  EXPECT_EQ(G[2], -0.1875);
  EXPECT_EQ(G[3 * 7 + 0], 0.5 * 0.5 * 0.75);
}

TEST(Shape, ReproducesALinearFieldAndItsGradient) {
  // f(x) = alpha + beta . x at nodes x_k = x0 + h (a, b, c): sum N_k f_k = f(x_p) and
  // sum G_k f_k = beta (linear completeness of the trilinear element).
  const double h = 0.76, inv_h = 1.0 / h;
  const double x0[3] = {-11.4, -3.04, 7.6};
  const double alpha = 2.5, beta[3] = {1.5, -0.75, 3.25};
  auto f = [&](const double* x) { return alpha + beta[0] * x[0] + beta[1] * x[1] + beta[2] * x[2]; };
  for (const auto& lx : sample_points()) {
    double N[8], G[24];
    mpm3d::shape_linear(lx.data(), inv_h, N, G);
    double val = 0, grad[3] = {0, 0, 0};
    for (int k = 0; k < 8; ++k) {
      const double xk[3] = {x0[0] + h * (k & 1), x0[1] + h * ((k >> 1) & 1), x0[2] + h * ((k >> 2) & 1)};
      const double fk = f(xk);
      val += N[k] * fk;
      for (int a = 0; a < 3; ++a) grad[a] += G[3 * k + a] * fk;
    }
    const double xp[3] = {x0[0] + lx[0] * h, x0[1] + lx[1] * h, x0[2] + lx[2] * h};
    // Field values are O(30): a few rounding errors of that size.
    EXPECT_NEAR(val, f(xp), 1e-13);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(grad[a], beta[a], 1e-12);
  }
}

TEST(Shape, TrilinearIsTheProductOfOneDimensionalHats) {
  // A field that varies only along y: f = y^2 at the nodes is interpolated linearly in y,
  // f(lx) = (1 - ly) f(0) + ly f(h); here with f(0) = 0, f(h) = h^2.
  const double h = 2.0;
  const double lx[3] = {0.3, 0.6, 0.9};
  double N[8], G[24];
  mpm3d::shape_linear(lx, 1.0 / h, N, G);
  double val = 0;
  for (int k = 0; k < 8; ++k) val += N[k] * (((k >> 1) & 1) ? h * h : 0.0);
  EXPECT_NEAR(val, 0.6 * 4.0, 1e-15);
}

// ---------------------------------------------------------------- uGIMP (27 nodes)
// 1D weights of a particle of half-size l (in cells) at r = (x_p - x_i)/h from node i:
// 1 - (r^2 + l^2)/(2l) for |r| < l, 1 - |r| up to 1 - l, (1 + l - |r|)^2/(4l) up to 1 + l.

namespace {

// Local coordinates that probe every branch of the 1D weight: cell edges, the middle (where
// the stencil switches), and the breakpoints l, 1 - l of each half-size, plus random ones.
std::vector<double> gimp_coords(double l) {
  std::vector<double> v = {0.0, 1e-12, 0.5 - 1e-12, 0.5, 0.5 + 1e-12, 1.0 - 1e-12, 0.999999,
                           l, l - 1e-9, l + 1e-9, 1.0 - l, 1.0 - l - 1e-9, 1.0 - l + 1e-9, 0.25, 0.75};
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 60; ++i) v.push_back(u(rng));
  std::vector<double> out;
  for (double x : v)
    if (x >= 0.0 && x < 1.0) out.push_back(x);
  return out;
}

const double kHalfSizes[] = {0.25, 0.5, 0.1, 0.4, 0.3333};

// The 27-node weights N and gradients G of a particle at local coordinates lx in the cell
// with base node x0 (cell size h), stencil offsets o: N >= 0, sum N = 1, sum G = 0, and a
// linear field given at the points x_k = x0 + h (o + off_k + shift) reproduced with its
// gradient (shift 0: the nodes, GIMP; 1/2: the cell centres, the current version's B-splines).
void expect_linear_reproduction(const double* N, const double* G, const int* o, const double* x0, const double* lx,
                                double h, double shift) {
  const double inv_h = 1.0 / h;
  double sum = 0, gs[3] = {0, 0, 0}, xr[3] = {0, 0, 0}, J[3][3] = {};
  for (int k = 0; k < 27; ++k) {
    const int off[3] = {k % 3, (k / 3) % 3, k / 9};
    EXPECT_GE(N[k], 0.0);
    sum += N[k];
    double xk[3];
    for (int a = 0; a < 3; ++a) {
      xk[a] = x0[a] + h * (double(o[a] + off[a]) + shift);
      gs[a] += G[3 * k + a];
      xr[a] += N[k] * xk[a];
    }
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) J[a][b] += G[3 * k + b] * xk[a];
  }
  EXPECT_NEAR(sum, 1.0, 1e-15);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(gs[a], 0.0, 4e-15 * inv_h);
    EXPECT_NEAR(xr[a], x0[a] + lx[a] * h, 4e-14) << "lx " << lx[a];
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(J[a][b], a == b ? 1.0 : 0.0, 1e-13);
  }
}

// Central differences of the weights shape(lx, N, G) along each axis against G (cell size
// h; inside one quadratic piece the difference is exact up to rounding).
template <class Shape>
void expect_gradients_are_derivatives(const double* lx, double h, Shape&& shape) {
  double N[27], G[81];
  shape(lx, N, G);
  const double e = 1e-6;
  for (int a = 0; a < 3; ++a) {
    double lp[3] = {lx[0], lx[1], lx[2]}, lm[3] = {lx[0], lx[1], lx[2]};
    lp[a] += e;
    lm[a] -= e;
    double Np[27], Nm[27], Gd[81];
    shape(lp, Np, Gd);
    shape(lm, Nm, Gd);
    for (int k = 0; k < 27; ++k) EXPECT_NEAR((Np[k] - Nm[k]) / (2.0 * e * h), G[3 * k + a], 1e-8);
  }
}

}  // namespace

TEST(ShapeGimp, OneDimensionalWeightsByHand) {
  // l = 1/4, lx = 0.1 in the lower half: stencil o = -1, r = 1.1, 0.1, -0.9.
  // node -1: (1.25 - 1.1)^2 / 1 = 0.0225; node 0: 1 - (0.01 + 0.0625)/0.5 = 0.855;
  // node 1: (1.25 - 0.9)^2 / 1 = 0.1225 (sum 1). Gradients (h = 1): -(0.15)/0.5 = -0.3,
  // -0.1/0.25 = -0.4, +0.35/0.5 = 0.7 (sum 0).
  double w[3], g[3];
  mpm3d::gimp_1d(0.1, -1, 0.25, 1.0, w, g);
  EXPECT_NEAR(w[0], 0.0225, 1e-15);
  EXPECT_NEAR(w[1], 0.855, 1e-15);
  EXPECT_NEAR(w[2], 0.1225, 1e-15);
  EXPECT_NEAR(g[0], -0.3, 1e-15);
  EXPECT_NEAR(g[1], -0.4, 1e-15);
  EXPECT_NEAR(g[2], 0.7, 1e-15);
  // lx = 0.5, upper stencil o = 0: r = 0.5, -0.5, -1.5: linear part 0.5, 0.5, and 0.
  mpm3d::gimp_1d(0.5, 0, 0.25, 2.0, w, g);
  EXPECT_EQ(w[0], 0.5);
  EXPECT_EQ(w[1], 0.5);
  EXPECT_EQ(w[2], 0.0);
  EXPECT_EQ(g[0], -2.0);
  EXPECT_EQ(g[1], 2.0);
  EXPECT_EQ(g[2], 0.0);
}

TEST(ShapeGimp, StencilOffsetsStayInTheGrid) {
  // Lower half of a cell: nodes i-1..i+1; upper half: i..i+2; shifted inwards at the ends.
  EXPECT_EQ(mpm3d::gimp_offset(0.3, 5, 10), -1);
  EXPECT_EQ(mpm3d::gimp_offset(0.7, 5, 10), 0);
  EXPECT_EQ(mpm3d::gimp_offset(0.3, 0, 10), 0);   // no node -1
  EXPECT_EQ(mpm3d::gimp_offset(0.7, 9, 10), -1);  // no node 11
  EXPECT_EQ(mpm3d::gimp_offset(0.2, 0, 2), 0);
  EXPECT_EQ(mpm3d::gimp_offset(0.9, 1, 2), -1);
}

TEST(ShapeGimp, WeightsAreContinuousAcrossTheBreakpoints) {
  // The support of a node is piecewise: the weight is continuous at |r| = l, 1 - l, 1 + l.
  for (double l : kHalfSizes)
    for (double r0 : {l, 1.0 - l, 1.0 + l}) {
      double wa[3], wb[3], g[3];
      // Node 0 of the upper stencil (o = 0) sits at r = lx.
      if (r0 >= 1.0) continue;
      mpm3d::gimp_1d(r0 - 1e-10, 0, l, 1.0, wa, g);
      mpm3d::gimp_1d(r0 + 1e-10, 0, l, 1.0, wb, g);
      EXPECT_NEAR(wa[0], wb[0], 1e-9) << "l " << l << " r " << r0;
    }
  // At |r| = 1 + l (node i-1 seen from lx = l) the weight vanishes.
  for (double l : kHalfSizes) {
    double w[3], g[3];
    mpm3d::gimp_1d(l, -1, l, 1.0, w, g);
    EXPECT_NEAR(w[0], 0.0, 1e-15) << "l " << l;
  }
}

TEST(ShapeGimp, PartitionOfUnityAndLinearReproduction) {
  // At many points of a cell (including its edges, its middle and the breakpoints) and for
  // several particle sizes: sum N = 1, sum G = 0, sum N x_k = x_p, sum G_b x_k,a = delta_ab,
  // with x_k the node positions of the stencil (interior cells: no shift at the grid ends).
  const double h = 0.76, inv_h = 1.0 / h;
  const double x0[3] = {-11.4, -3.04, 7.6};  // base node of the particle's cell
  std::mt19937_64 rng(99);
  for (double l : kHalfSizes) {
    const std::vector<double> c = gimp_coords(l);
    std::uniform_int_distribution<size_t> pick(0, c.size() - 1);
    for (int trial = 0; trial < 400; ++trial) {
      const double lx[3] = {c[pick(rng)], c[pick(rng)], c[pick(rng)]};
      int o[3];
      for (int a = 0; a < 3; ++a) o[a] = mpm3d::gimp_offset(lx[a], 5, 10);
      double N[27], G[81];
      mpm3d::shape_gimp(lx, o, l, inv_h, N, G);
      SCOPED_TRACE(l);
      expect_linear_reproduction(N, G, o, x0, lx, h, 0.0);
    }
  }
}

TEST(ShapeGimp, GradientsAreTheDerivativesOfTheWeights) {
  // Central differences of N along each axis agree with G (away from the breakpoints,
  // where the second derivative jumps; the weights are quadratic, so the difference is
  // exact up to rounding inside one piece).
  const double h = 2.0, l = 0.25;
  const double lx[3] = {0.1, 0.6, 0.85};
  const int o[3] = {-1, 0, 0};
  expect_gradients_are_derivatives(lx, h, [&](const double* x, double* N, double* G) {
    mpm3d::shape_gimp(x, o, l, 1.0 / h, N, G);
  });
}

// The current version's quadratic B-splines ('bimp'): on the nodes base-1, base, base+1 of
// the particle's cell, (1-s)^2/2, 1/2 + s - s^2, s^2/2, each node's spline centred half a
// cell above the node.
TEST(ShapeBspline, OneDimensionalWeightsByHand) {
  double w[3], g[3];
  mpm3d::bspline_1d(0.5, -1, 2.0, w, g);  // the cell's centre: 1/8, 3/4, 1/8
  EXPECT_EQ(w[0], 0.125);
  EXPECT_EQ(w[1], 0.75);
  EXPECT_EQ(w[2], 0.125);
  EXPECT_EQ(g[0], -1.0);  // -(1 - s) / h with h = 1/2
  EXPECT_EQ(g[1], 0.0);
  EXPECT_EQ(g[2], 1.0);
  mpm3d::bspline_1d(0.0, -1, 1.0, w, g);  // the cell's base node: 1/2, 1/2, 0
  EXPECT_EQ(w[0], 0.5);
  EXPECT_EQ(w[1], 0.5);
  EXPECT_EQ(w[2], 0.0);
  EXPECT_EQ(g[0], -1.0);
  EXPECT_EQ(g[1], 1.0);
  EXPECT_EQ(g[2], 0.0);
  // s = 0.2: 0.32, 0.66, 0.02.
  mpm3d::bspline_1d(0.2, -1, 1.0, w, g);
  EXPECT_NEAR(w[0], 0.32, 1e-15);
  EXPECT_NEAR(w[1], 0.66, 1e-15);
  EXPECT_NEAR(w[2], 0.02, 1e-15);
  // The grid's first cell (o = 0): base and base+1 keep their weights, base-1's is dropped,
  // and the third node (base+2) has none.
  mpm3d::bspline_1d(0.2, 0, 1.0, w, g);
  EXPECT_NEAR(w[0], 0.66, 1e-15);
  EXPECT_NEAR(w[1], 0.02, 1e-15);
  EXPECT_EQ(w[2], 0.0);
  EXPECT_EQ(g[2], 0.0);
  EXPECT_EQ(mpm3d::bspline_offset(0), 0);
  EXPECT_EQ(mpm3d::bspline_offset(1), -1);
  EXPECT_EQ(mpm3d::bspline_offset(7), -1);
}

TEST(ShapeBspline, PartitionOfUnityAndLinearReproductionAboutTheCellCentres) {
  // Inside the grid: sum N = 1, sum G = 0, and a linear field given at the points half a
  // cell above the nodes (x_k + h/2) is reproduced with its gradient.
  const double h = 0.76, inv_h = 1.0 / h;
  const double x0[3] = {-11.4, -3.04, 7.6};  // base node of the particle's cell
  for (const auto& lx : sample_points()) {
    const int o[3] = {-1, -1, -1};
    double N[27], G[81];
    mpm3d::shape_bspline(lx.data(), o, inv_h, N, G);
    expect_linear_reproduction(N, G, o, x0, lx.data(), h, 0.5);
  }
}

TEST(ShapeBspline, GradientsAreTheDerivativesOfTheWeights) {
  const double h = 2.0;
  const double lx[3] = {0.1, 0.6, 0.85};
  const int o[3] = {-1, -1, 0};
  expect_gradients_are_derivatives(lx, h, [&](const double* x, double* N, double* G) {
    mpm3d::shape_bspline(x, o, 1.0 / h, N, G);
  });
}

// Rule sg_beyond=drop on a grid one cell thick in y (4 x 1 x 4 cells): the current program
// numbers the centre beyond y as one past the axis's last, which is the first cell of the
// next z row, and skips it only past its last cell. So a particle in the second z row keeps
// every weight (beyond y they go to the nearest centre, as under our rules); one in the top
// z row loses the corners beyond y (their number is past the last cell).
TEST(ShapeSgmp, BeyondAOneCellAxisDroppedOnlyPastTheLastCell) {
  StepContext c{};
  c.grid.nc[0] = 4, c.grid.nc[1] = 1, c.grid.nc[2] = 4;
  c.grid.nn[0] = 5, c.grid.nn[1] = 2, c.grid.nn[2] = 5;
  c.rules.sg_beyond = 1;
  const mpm3d::SgGeometry g(&c);
  const mpm3d::CellDecoder dec(&c);
  const double lx[3] = {0.6, 0.75, 0.6};  // upper halves: the auxiliary cell reaches up along each axis
  auto weights = [&](int cell, bool rules, double w[8]) {
    int lo[3], hi[3];
    double wg[8];
    if (rules)
      mpm3d::sg_corner_weights<true>(g, dec, cell, lx, lo, hi, w, wg);
    else
      mpm3d::sg_corner_weights<false>(g, dec, cell, lx, lo, hi, w, wg);
    for (int k = 0; k < 8; ++k) EXPECT_EQ(w[k], wg[k]);
  };
  double ours[8], rule[8];
  const int second_row = 1 + 4 * (0 + 1 * 1), top_row = 1 + 4 * (0 + 1 * 3);  // cells (1, 0, 1) and (1, 0, 3)
  weights(second_row, false, ours);
  weights(second_row, true, rule);
  double sum = 0.0;
  for (int k = 0; k < 8; ++k) {
    EXPECT_EQ(rule[k], ours[k]) << "corner " << k;
    sum += rule[k];
  }
  EXPECT_NEAR(sum, 1.0, 1e-15);
  weights(top_row, true, rule);
  sum = 0.0;
  for (int k = 0; k < 8; ++k) {
    if (k & 2) EXPECT_EQ(rule[k], 0.0) << "corner " << k;
    sum += rule[k];
  }
  EXPECT_NEAR(sum, 0.75, 1e-15);  // the y factor of the lower centre: (1 - X) / 2, X = 2 (0.75 - 1) = -0.5
}
