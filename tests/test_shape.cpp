// GridData: trilinear shape functions of the 8 nodes of a cell.
// Local node k = a + 2 b + 4 c sits at offset (a, b, c) h from the cell's base node;
// N_k = wx_a wy_b wz_c with w_0 = 1 - l, w_1 = l; dN_k/dx = (+-1/h) wy_b wz_c, etc.
#include <gtest/gtest.h>

#include <cmath>
#include <array>
#include <random>
#include <vector>

#include "grid.hpp"

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
