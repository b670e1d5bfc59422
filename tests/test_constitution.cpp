// MaterialModel: stress update of each material, the Jaumann rotation and the EOS,
// against values derived by hand.
//
// Common material: E = 200, nu = 0.25, so G = 200 / 2.5 = 80, lambda = 50 / 0.625 = 80
// (both exact in binary), 2G = 160, 3G = 240, lambda + 2G = 240.
// Uniaxial strain increment de = (e, 0, 0, 0, 0, 0) from zero stress gives the trial
// stress (240 e, 80 e, 80 e), mean 400 e / 3, deviator (320 e / 3, -160 e / 3, -160 e / 3)
// and von Mises stress q = sqrt(3 J2) = |s_xx - s_yy| = 160 e.
// Radial return: deps = (q - sy) / (3G + Ep); the deviator is scaled by (q - 3G deps) / q;
// for this axisymmetric state the stress is then mean + (2/3, -1/3, -1/3) q_new.
#include <gtest/gtest.h>

#include <cmath>

#include "materials/constitution.hpp"
#include "materials/material.hpp"

using mpm3d::StressState;

namespace {

MaterialParams base_material(int type) {
  MaterialParams m{};
  m.type = type;
  m.rho0 = 1.0;
  m.young = 200.0;
  m.poisson = 0.25;
  const std::string err = mpm3d::material_derive(m);
  EXPECT_EQ(err, "");
  return m;
}

struct Particle {
  double sig[6] = {0, 0, 0, 0, 0, 0};
  double epeff = 0.0, ie = 0.0, temp = 0.0;
  StressState state(bool thermal = false) { return StressState{sig, &epeff, &ie, thermal ? &temp : nullptr}; }
};

const double kZeroSpin[3] = {0.0, 0.0, 0.0};

// Relative comparison to a few rounding errors of the largest component involved.
void expect_stress(const double* sig, double xx, double yy, double zz, double yz, double xz, double xy,
                   double scale, double rel = 1e-13) {
  const double e[6] = {xx, yy, zz, yz, xz, xy};
  for (int c = 0; c < 6; ++c) EXPECT_NEAR(sig[c], e[c], rel * scale) << "component " << c;
}

}  // namespace

TEST(Material, DerivedConstants) {
  MaterialParams m = base_material(MAT_ELAS);
  EXPECT_EQ(m.shear, 80.0);
  EXPECT_EQ(m.lambda, 80.0);
  EXPECT_DOUBLE_EQ(m.wave_speed, std::sqrt(240.0));
  MaterialParams bad = m;
  bad.poisson = 0.5;
  EXPECT_NE(mpm3d::material_derive(bad), "");
  bad = m;
  bad.young = -1.0;
  EXPECT_NE(mpm3d::material_derive(bad), "");
}

TEST(Constitution, ElasticUniaxialStrainTwoIncrements) {
  MaterialParams m = base_material(MAT_ELAS);
  Particle p;
  const double e = 1.0e-3;
  const double de[6] = {e, 0, 0, 0, 0, 0};
  // Increment 1: sigma = (lambda + 2G) e = 0.24 along x, lambda e = 0.08 across.
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.001, p.state());
  expect_stress(p.sig, 0.24, 0.08, 0.08, 0, 0, 0, 0.24);
  // Work: 0.5 (0 + 0.24) e * mean volume (1 + 1.001) / 2.
  EXPECT_NEAR(p.ie, 0.5 * 0.24e-3 * 1.0005, 1e-18);
  EXPECT_EQ(p.epeff, 0.0);
  // Increment 2: (0.48, 0.16, 0.16); work 0.5 (0.24 + 0.48) e * (1.001 + 1.002) / 2.
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.001, 1.002, p.state());
  expect_stress(p.sig, 0.48, 0.16, 0.16, 0, 0, 0, 0.48);
  EXPECT_NEAR(p.ie, 0.5 * 0.24e-3 * 1.0005 + 0.5 * 0.72e-3 * 1.0015, 1e-17);
  // Shear increment: sigma_xy += 2 G de_xy = 160 * 1e-3.
  const double ds[6] = {0, 0, 0, 0, 0, 1e-3};
  mpm3d::stress_update(m, ds, kZeroSpin, 1e-3, 1.0, 1.002, 1.002, p.state());
  expect_stress(p.sig, 0.48, 0.16, 0.16, 0, 0, 0.16, 0.48);
}

TEST(Constitution, Pla1RadialReturn) {
  MaterialParams m = base_material(MAT_PLA1);
  m.yield0 = 0.1;
  Particle p;
  // Small increment, e = 1e-4: q = 0.016 < 0.1, elastic: (0.024, 0.008, 0.008).
  const double small[6] = {1e-4, 0, 0, 0, 0, 0};
  mpm3d::stress_update(m, small, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, p.state());
  expect_stress(p.sig, 0.024, 0.008, 0.008, 0, 0, 0, 0.024);
  EXPECT_EQ(p.epeff, 0.0);
  // From zero again, e = 1e-3: trial q = 0.16 > 0.1; deps = (0.16 - 0.1) / 240 = 2.5e-4;
  // q_new = 0.1; mean 0.4 / 3: sigma = 0.4/3 + (2/3, -1/3, -1/3) 0.1 = (0.2, 0.1, 0.1).
  Particle r;
  const double de[6] = {1e-3, 0, 0, 0, 0, 0};
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, r.state());
  expect_stress(r.sig, 0.2, 0.1, 0.1, 0, 0, 0, 0.2);
  EXPECT_NEAR(r.epeff, 2.5e-4, 1e-18);
  // Second increment: trial (0.44, 0.18, 0.18), q = 0.26, deps = 0.16 / 240; q_new = 0.1;
  // mean 0.8 / 3: sigma = (0.8/3 + 0.2/3, 0.8/3 - 0.1/3, ...) = (1/3, 0.7/3, 0.7/3).
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, r.state());
  expect_stress(r.sig, 1.0 / 3.0, 0.7 / 3.0, 0.7 / 3.0, 0, 0, 0, 0.4);
  EXPECT_NEAR(r.epeff, 2.5e-4 + 0.16 / 240.0, 1e-18);
}

TEST(Constitution, Pla1ReturnOfAPureShearTrial) {
  // Shear increment de_xy = g: trial s_xy = 2G g, q = sqrt(3) 2G g. g = 1e-3: q = 0.16 sqrt(3).
  // Return to sy = 0.1: s_xy = 0.1 / sqrt(3); deps = (0.16 sqrt(3) - 0.1) / 240; no mean stress.
  MaterialParams m = base_material(MAT_PLA1);
  m.yield0 = 0.1;
  Particle p;
  const double de[6] = {0, 0, 0, 0, 0, 1e-3};
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, p.state());
  expect_stress(p.sig, 0, 0, 0, 0, 0, 0.1 / std::sqrt(3.0), 0.1);
  EXPECT_NEAR(p.epeff, (0.16 * std::sqrt(3.0) - 0.1) / 240.0, 1e-17);
}

TEST(Constitution, Pla2LinearHardeningTwoIncrements) {
  MaterialParams m = base_material(MAT_PLA2);
  m.yield0 = 0.1;
  m.hardening = 60.0;  // Ep (the deck reader forms it as E Et / (E - Et)); 3G + Ep = 300
  Particle p;
  const double de[6] = {1e-3, 0, 0, 0, 0, 0};
  // 1: q = 0.16, deps = (0.16 - 0.1) / 300 = 2e-4, q_new = 0.16 - 240 * 2e-4 = 0.112
  //    (= sy + Ep deps). sigma = 0.4/3 + (2/3, -1/3, -1/3) 0.112 = (0.208, 0.096, 0.096).
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, p.state());
  expect_stress(p.sig, 0.208, 0.096, 0.096, 0, 0, 0, 0.208);
  EXPECT_NEAR(p.epeff, 2e-4, 1e-18);
  // 2: trial (0.448, 0.176, 0.176), q = 0.272, sy = 0.1 + 60 * 2e-4 = 0.112,
  //    deps = 0.16 / 300, q_new = 0.272 - 0.128 = 0.144, mean 0.8/3:
  //    sigma = (0.8/3 + 0.096, 0.8/3 - 0.048, 0.8/3 - 0.048).
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, p.state());
  expect_stress(p.sig, 0.8 / 3.0 + 0.096, 0.8 / 3.0 - 0.048, 0.8 / 3.0 - 0.048, 0, 0, 0, 0.4);
  EXPECT_NEAR(p.epeff, 2e-4 + 0.16 / 300.0, 1e-17);
}

TEST(Constitution, Pla2PlasticWorkGoesToInternalEnergy) {
  // Increment 1 of the test above with volumes 1 -> 1: ie = 0.5 (0 + sigma_xx) e = 0.104e-3.
  MaterialParams m = base_material(MAT_PLA2);
  m.yield0 = 0.1;
  m.hardening = 60.0;
  Particle p;
  const double de[6] = {1e-3, 0, 0, 0, 0, 0};
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, p.state());
  EXPECT_NEAR(p.ie, 0.5 * 0.208e-3, 1e-17);
}

TEST(Constitution, SimplifiedJohnsonCookLinearHardening) {
  // sjc with n = 1, C = 0: sy = A + B epeff, slope B. A = 0.1, B = 60 is pla2 above.
  MaterialParams m = base_material(MAT_SJC);
  m.yield0 = 0.1;
  m.hardening = 60.0;
  m.jc_n = 1.0;
  m.jc_c = 0.0;
  m.eps0dot = 1.0;
  Particle p;
  const double de[6] = {1e-3, 0, 0, 0, 0, 0};
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, p.state());
  expect_stress(p.sig, 0.208, 0.096, 0.096, 0, 0, 0, 0.208);
  EXPECT_NEAR(p.epeff, 2e-4, 1e-18);
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, p.state());
  expect_stress(p.sig, 0.8 / 3.0 + 0.096, 0.8 / 3.0 - 0.048, 0.8 / 3.0 - 0.048, 0, 0, 0, 0.4);
  EXPECT_NEAR(p.epeff, 2e-4 + 0.16 / 300.0, 1e-17);
}

TEST(Constitution, SimplifiedJohnsonCookSquareRootAfterPriorPlasticStrain) {
  // n = 0.5, A = 0.1, B = 0.5, prior epeff = 0.04 (stress relaxed to zero):
  // sy = 0.1 + 0.5 sqrt(0.04) = 0.2; slope n B epeff^(n-1) = 0.25 / 0.2 = 1.25.
  // e = 2e-3: q = 0.32, deps = (0.32 - 0.2) / (240 + 1.25) = 0.12 / 241.25,
  // q_new = 0.32 - 240 deps; mean 0.8 / 3.
  MaterialParams m = base_material(MAT_SJC);
  m.yield0 = 0.1;
  m.hardening = 0.5;
  m.jc_n = 0.5;
  m.jc_c = 0.0;
  m.eps0dot = 1.0;
  double sy = 0, ep = 0;
  mpm3d::yield_stress(m, 0.04, 0.0, 0.0, &sy, &ep);
  EXPECT_NEAR(sy, 0.2, 1e-15);
  EXPECT_NEAR(ep, 1.25, 1e-14);
  Particle p;
  p.epeff = 0.04;
  const double de[6] = {2e-3, 0, 0, 0, 0, 0};
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, p.state());
  const double deps = 0.12 / 241.25;
  const double q_new = 0.32 - 240.0 * deps;
  const double mean = 0.8 / 3.0;
  expect_stress(p.sig, mean + (2.0 / 3.0) * q_new, mean - q_new / 3.0, mean - q_new / 3.0, 0, 0, 0, 0.4);
  EXPECT_NEAR(p.epeff, 0.04 + deps, 1e-16);
}

TEST(Constitution, JohnsonCookStrainRateFactor) {
  // Uniaxial strain e: deviatoric increment (2e/3, -e/3, -e/3), equivalent rate
  // sqrt(2/3 de':de') / dt = (2e/3) / dt. e = 1e-3, dt = 1e-3: rate 2/3.
  // eps0dot = (2/3) / exp(1) makes the rate ratio e, so the factor is 1 + C ln(e) = 1 + C.
  // C = 0.5, A = 0.1, B = 60, n = 1: sy = 0.15, slope 90; deps = (0.16 - 0.15) / 330;
  // q_new = 0.16 - 240 deps.
  MaterialParams m = base_material(MAT_SJC);
  m.yield0 = 0.1;
  m.hardening = 60.0;
  m.jc_n = 1.0;
  m.jc_c = 0.5;
  m.eps0dot = (2.0 / 3.0) / std::exp(1.0);
  Particle p;
  const double de[6] = {1e-3, 0, 0, 0, 0, 0};
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, p.state());
  const double deps = 0.01 / 330.0;
  const double q_new = 0.16 - 240.0 * deps;
  const double mean = 0.4 / 3.0;
  expect_stress(p.sig, mean + (2.0 / 3.0) * q_new, mean - q_new / 3.0, mean - q_new / 3.0, 0, 0, 0, 0.2,
                1e-12);
  EXPECT_NEAR(p.epeff, deps, 1e-12 * deps);  // q - sy = 0.01 cancels ~2 digits
  // Rates below eps0dot do not lower the yield stress: factor 1.
  double sy = 0, ep = 0;
  mpm3d::yield_stress(m, 0.0, 0.1 * m.eps0dot, 0.0, &sy, &ep);
  EXPECT_EQ(sy, 0.1);
}

TEST(Constitution, JohnsonCookThermalSofteningAndHeating) {
  // john: A = 0.1, B = 60, n = 1, C = 0, m = 1, T_room = 20, T_melt = 1020.
  MaterialParams m = base_material(MAT_JOHN);
  m.yield0 = 0.1;
  m.hardening = 60.0;
  m.jc_n = 1.0;
  m.jc_c = 0.0;
  m.jc_m = 1.0;
  m.t_room = 20.0;
  m.t_melt = 1020.0;
  m.heat_cap = 0.5;
  m.eps0dot = 1.0;
  const double de[6] = {1e-3, 0, 0, 0, 0, 0};
  // At room temperature T* = 0: no softening, the pla2 result (q_new 0.112, deps 2e-4).
  // Heating: dT = 0.9 q_new deps / (rho c_p), rho = mass / vol_new = 1:
  //   dT = 0.9 * 0.112 * 2e-4 / 0.5 = 4.032e-5.
  Particle cold;
  cold.temp = 20.0;
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, cold.state(true));
  expect_stress(cold.sig, 0.208, 0.096, 0.096, 0, 0, 0, 0.208);
  EXPECT_NEAR(cold.epeff, 2e-4, 1e-18);
  EXPECT_NEAR(cold.temp, 20.0 + 4.032e-5, 1e-13);
  // At T = 520: T* = 0.5, factor 1 - 0.5 = 0.5: sy = 0.05, slope 30;
  // deps = (0.16 - 0.05) / 270 = 11 / 27000; q_new = 0.16 - 240 deps = 56 / 900.
  // dT = 0.9 * (56/900) * (11/27000) / 0.5.
  Particle hot;
  hot.temp = 520.0;
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, hot.state(true));
  const double q_new = 56.0 / 900.0, mean = 0.4 / 3.0;
  expect_stress(hot.sig, mean + (2.0 / 3.0) * q_new, mean - q_new / 3.0, mean - q_new / 3.0, 0, 0, 0, 0.2);
  EXPECT_NEAR(hot.epeff, 11.0 / 27000.0, 1e-17);
  EXPECT_NEAR(hot.temp, 520.0 + 0.9 * (56.0 / 900.0) * (11.0 / 27000.0) / 0.5, 1e-12);
  // Density enters the heating: mass 2 in volume 1 halves the rise.
  Particle dense;
  dense.temp = 520.0;
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 2.0, 1.0, 1.0, dense.state(true));
  EXPECT_NEAR(dense.temp, 520.0 + 0.45 * (56.0 / 900.0) * (11.0 / 27000.0) / 0.5, 1e-12);
  // Above the melting point the yield stress vanishes.
  double sy = 1, ep = 1;
  mpm3d::yield_stress(m, 0.1, 0.0, 2000.0, &sy, &ep);
  EXPECT_EQ(sy, 0.0);
}

TEST(Constitution, SimplifiedJohnsonCookFailure) {
  // sjcf: A = 0.1, B = 60, n = 1, eps_f = 1e-4. One increment of e = +-1e-3 gives
  // deps = 2e-4 >= eps_f: failed. No deviatoric stress; the pressure -mean is kept in
  // compression and cut to zero in tension.
  MaterialParams m = base_material(MAT_SJCF);
  m.yield0 = 0.1;
  m.hardening = 60.0;
  m.jc_n = 1.0;
  m.eps0dot = 1.0;
  m.fail_strain = 1e-4;
  const double ten[6] = {1e-3, 0, 0, 0, 0, 0};
  Particle t;
  mpm3d::stress_update(m, ten, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, t.state());
  EXPECT_NEAR(t.epeff, 2e-4, 1e-18);
  for (int c = 0; c < 6; ++c) EXPECT_EQ(t.sig[c], 0.0) << c;
  // Compression: mean -0.4/3, pressure 0.4/3 kept: sigma = -0.4/3 I.
  const double com[6] = {-1e-3, 0, 0, 0, 0, 0};
  Particle c;
  mpm3d::stress_update(m, com, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, c.state());
  expect_stress(c.sig, -0.4 / 3.0, -0.4 / 3.0, -0.4 / 3.0, 0, 0, 0, 0.2);
  // A failed particle carries no shear afterwards either.
  const double shear[6] = {0, 0, 0, 0, 0, 1e-3};
  mpm3d::stress_update(m, shear, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, c.state());
  expect_stress(c.sig, -0.4 / 3.0, -0.4 / 3.0, -0.4 / 3.0, 0, 0, 0, 0.2);
  // Below the failure strain the same material behaves as sjc.
  m.fail_strain = 1.0;
  Particle ok;
  mpm3d::stress_update(m, ten, kZeroSpin, 1e-3, 1.0, 1.0, 1.0, ok.state());
  expect_stress(ok.sig, 0.208, 0.096, 0.096, 0, 0, 0, 0.208);
}

TEST(Constitution, JaumannRotationOfUniaxialStressBySimpleSpin) {
  // W = [[0, w, 0], [-w, 0, 0], [0, 0, 0]] (dw = (w_yz, w_xz, w_xy) = (0, 0, w)),
  // sigma = diag(s, 0, 0). W sigma has only (y,x) = -w s; sigma W only (x,y) = w s.
  // W sigma - sigma W: (x,y) = (y,x) = -w s, diagonal unchanged.
  double sig[6] = {2.0, 0, 0, 0, 0, 0};
  const double dw[3] = {0, 0, 0.01};
  mpm3d::jaumann_rotate(sig, dw);
  EXPECT_EQ(sig[0], 2.0);
  EXPECT_EQ(sig[1], 0.0);
  EXPECT_EQ(sig[2], 0.0);
  EXPECT_EQ(sig[3], 0.0);
  EXPECT_EQ(sig[4], 0.0);
  EXPECT_EQ(sig[5], -0.02);
  // Pure shear sigma_xy = t with the same spin: (W sigma)_xx = w t, (sigma W)_xx = -w t,
  // so xx gains 2 w t; yy loses 2 w t.
  double tau[6] = {0, 0, 0, 0, 0, 3.0};
  mpm3d::jaumann_rotate(tau, dw);
  EXPECT_NEAR(tau[0], 0.06, 1e-17);
  EXPECT_NEAR(tau[1], -0.06, 1e-17);
  EXPECT_EQ(tau[2], 0.0);
  EXPECT_EQ(tau[5], 3.0);
  // A hydrostatic stress is not changed by any spin.
  double hyd[6] = {-5.0, -5.0, -5.0, 0, 0, 0};
  const double any[3] = {0.3, -0.2, 0.7};
  mpm3d::jaumann_rotate(hyd, any);
  expect_stress(hyd, -5, -5, -5, 0, 0, 0, 5.0, 1e-15);
}

TEST(Constitution, JaumannRotationGeneralAgainstMatrixProduct) {
  // sigma (symmetric) and W (skew): W_xy = wxy, W_xz = wxz, W_yz = wyz, W_ji = -W_ij.
  const double s6[6] = {1.0, -2.0, 3.0, 0.5, -0.25, 0.75};  // xx yy zz yz xz xy
  const double dw[3] = {0.03, -0.02, 0.05};                  // wyz wxz wxy
  const double S[3][3] = {{s6[0], s6[5], s6[4]}, {s6[5], s6[1], s6[3]}, {s6[4], s6[3], s6[2]}};
  const double W[3][3] = {{0, dw[2], dw[1]}, {-dw[2], 0, dw[0]}, {-dw[1], -dw[0], 0}};
  double R[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double ws = 0, sw = 0;
      for (int k = 0; k < 3; ++k) {
        ws += W[i][k] * S[k][j];
        sw += S[i][k] * W[k][j];
      }
      R[i][j] = S[i][j] + (ws - sw);
    }
  // The result is symmetric (W sigma - sigma W is symmetric for skew W, symmetric sigma).
  EXPECT_NEAR(R[0][1], R[1][0], 1e-15);
  double sig[6];
  for (int c = 0; c < 6; ++c) sig[c] = s6[c];
  mpm3d::jaumann_rotate(sig, dw);
  expect_stress(sig, R[0][0], R[1][1], R[2][2], R[1][2], R[0][2], R[0][1], 3.0, 1e-15);
  // By hand for xx: 2 (wxy sxy + wxz sxz) = 2 (0.05 * 0.75 + (-0.02)(-0.25)) = 0.085.
  EXPECT_NEAR(sig[0], 1.085, 1e-15);
  // The trace is invariant.
  EXPECT_NEAR((sig[0] + sig[1]) + sig[2], 2.0, 1e-15);
}

TEST(Constitution, StressUpdateRotatesBeforeTheIncrement) {
  // Elastic, sigma = diag(2, 0, 0), pure spin w_xy = 0.01 and no strain: sigma_xy = -0.02,
  // normal components unchanged.
  MaterialParams m = base_material(MAT_ELAS);
  Particle p;
  p.sig[0] = 2.0;
  const double zero[6] = {0, 0, 0, 0, 0, 0};
  const double dw[3] = {0, 0, 0.01};
  mpm3d::stress_update(m, zero, dw, 1e-3, 1.0, 1.0, 1.0, p.state());
  expect_stress(p.sig, 2.0, 0, 0, 0, 0, -0.02, 2.0, 1e-15);
}

TEST(Eos, LinearPolynomial) {
  // p = C0 + C1 mu + C2 mu^2 + C3 mu^3 + (C4 + C5 mu + C6 mu^2) e with C = 1..7;
  // C2 mu^2 and C6 mu^2 vanish in tension.
  MaterialParams m = base_material(MAT_SJC);
  m.eos_type = EOS_LINEAR;
  for (int i = 0; i < 7; ++i) m.eos[i] = double(i + 1);
  double a = 0, b = 0;
  // mu = 0.1: a = 1 + 0.2 + 0.03 + 0.004 = 1.234, b = 5 + 0.6 + 0.07 = 5.67.
  mpm3d::eos_coefficients(m, 0.1, &a, &b);
  EXPECT_NEAR(a, 1.234, 1e-15);
  EXPECT_NEAR(b, 5.67, 1e-15);
  // mu = -0.1: a = 1 - 0.2 + 0 - 0.004 = 0.796, b = 5 - 0.6 = 4.4.
  mpm3d::eos_coefficients(m, -0.1, &a, &b);
  EXPECT_NEAR(a, 0.796, 1e-15);
  EXPECT_NEAR(b, 4.4, 1e-15);
  // mu = 0: a = C0, b = C4.
  mpm3d::eos_coefficients(m, 0.0, &a, &b);
  EXPECT_EQ(a, 1.0);
  EXPECT_EQ(b, 5.0);
}

TEST(Eos, MieGruneisen) {
  // The book's form. rho0 = 2, c0 = 3, s = 1.5, gamma0 = 1: C1 = rho0 c0^2 = 18,
  // C2 = C1 (2s - 1) = 36, C3 = C1 (s - 1)(3s - 1) = 31.5.
  // Compression mu = 0.1: Hugoniot 1.8 + 0.36 + 0.0315 = 2.1915, times
  // 1 - gamma0 mu / (2 (1 + mu)) = 1 - 0.05 / 1.1 = 21/22; b = gamma0 = 1.
  MaterialParams m = base_material(MAT_SJC);
  m.rho0 = 2.0;
  m.eos_type = EOS_MIE_GRUNEISEN;
  m.eos[0] = 3.0;
  m.eos[1] = 1.5;
  m.eos[2] = 1.0;
  double a = 0, b = 0;
  mpm3d::eos_coefficients(m, 0.1, &a, &b);
  EXPECT_NEAR(a, 2.1915 * 21.0 / 22.0, 1e-14);
  EXPECT_EQ(b, 1.0);
  // Tension mu = -0.1: a = C1 mu = -1.8 and no energy term, b = 0.
  mpm3d::eos_coefficients(m, -0.1, &a, &b);
  EXPECT_NEAR(a, -1.8, 1e-15);
  EXPECT_EQ(b, 0.0);
  // Copper of the Taylor deck: rho0 8.93e-3, c0 3940, s 1.49, gamma0 1.96, mu = 0.05:
  // C1 = 8.93e-3 * 3940^2, C2 = 1.98 C1, C3 = 0.49 * 3.47 C1 = 1.7003 C1;
  // a = C1 (0.05 + 1.98 * 0.0025 + 1.7003 * 0.000125) (1 - 0.049 / 1.05).
  m.rho0 = 8.93e-3;
  m.eos[0] = 3940.0;
  m.eos[1] = 1.49;
  m.eos[2] = 1.96;
  mpm3d::eos_coefficients(m, 0.05, &a, &b);
  const double expect = 8.93e-3 * 15523600.0 * 0.0551625375 * (1.0 - 0.049 / 1.05);
  EXPECT_NEAR(a, expect, 1e-13 * expect);
  EXPECT_EQ(b, 1.96);
  // Lead of the public hypervelocity deck (rho0 11.35e-3, c0 2092, s 1.45, gamma0 2) at
  // mu = 0.9, about the compression of its 6.58 km/s impact: C1 = 49672.8664,
  // Hugoniot C1 (0.9 + 1.9 * 0.81 + 0.45 * 3.35 * 0.729) = 3.5379675 C1, times
  // 1 - 0.9 / 1.9 (the Hugoniot of the linear Us-up fit itself is 4.83 C1 there).
  m.rho0 = 11.35e-3;
  m.eos[0] = 2092.0;
  m.eos[1] = 1.45;
  m.eos[2] = 2.0;
  mpm3d::eos_coefficients(m, 0.9, &a, &b);
  const double lead = 49672.8664 * 3.5379675 * (1.0 - 0.9 / 1.9);
  EXPECT_NEAR(a, lead, 1e-9 * lead);
  EXPECT_EQ(b, 2.0);
}

TEST(Eos, StressUpdateWithLinearBulkEos) {
  // sjc with a large A (stays elastic) and a linear EOS p = K mu (C1 = K = 1000 only):
  // rho0 = 1, mass 1, vol0 = 1, volume 1 -> 0.999 under de = (-1e-3, 0, 0).
  // mu = 1 / 0.999 - 1 = 1 / 999; p = 1000 / 999.
  // Deviator: 2G dev = 160 (-2e-3/3, 1e-3/3, 1e-3/3) = (-0.32/3, 0.16/3, 0.16/3).
  // Energy (per initial volume, b = 0): e1 = dwork - p1 dv / 2 with dv = -1e-3 and
  //   dwork = 0.5 (0 + s:de) vavg = 0.5 (0.32e-3 / 3) 0.9995.
  MaterialParams m = base_material(MAT_SJC);
  m.yield0 = 1e6;
  m.jc_n = 1.0;
  m.eos_type = EOS_LINEAR;
  m.eos[1] = 1000.0;
  Particle p;
  const double de[6] = {-1e-3, 0, 0, 0, 0, 0};
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 1.0, 1.0, 0.999, p.state());
  const double pres = 1000.0 / 999.0;
  expect_stress(p.sig, -0.32 / 3.0 - pres, 0.16 / 3.0 - pres, 0.16 / 3.0 - pres, 0, 0, 0, 1.2, 1e-12);
  const double dwork = 0.5 * (0.32e-3 / 3.0) * 0.9995;
  EXPECT_NEAR(p.ie, dwork + 0.5 * pres * 1e-3, 1e-15);
  EXPECT_EQ(p.epeff, 0.0);
}

TEST(Eos, StressUpdateWithMieGruneisenEnergyCoupling) {
  // Hydrostatic compression of a Mie-Gruneisen material from e = 0, p = 0:
  // rho0 = 2, mass 2 (vol0 = 1), volume 1 -> 1/1.1 so mu = 0.1 and dv = 1/1.1 - 1.
  // The energy equation e1 = -(p0 + p1) dv / 2 with p1 = a + b e1 (b = gamma0 = 1) gives
  // p1 = a / (1 + b dv / 2), a = 2.1915 * 21/22 (Eos.MieGruneisen), e1 = -p1 dv / 2.
  MaterialParams m = base_material(MAT_SJC);
  m.rho0 = 2.0;
  m.yield0 = 1e6;
  m.jc_n = 1.0;
  m.eos_type = EOS_MIE_GRUNEISEN;
  m.eos[0] = 3.0;
  m.eos[1] = 1.5;
  m.eos[2] = 1.0;
  Particle p;
  const double vnew = 1.0 / 1.1;
  const double d = (vnew - 1.0) / 3.0;
  const double de[6] = {d, d, d, 0, 0, 0};
  mpm3d::stress_update(m, de, kZeroSpin, 1e-3, 2.0, 1.0, vnew, p.state());
  const double dv = vnew - 1.0;
  const double a = 2.1915 * 21.0 / 22.0;
  const double p1 = a / (1.0 + 0.5 * dv);
  expect_stress(p.sig, -p1, -p1, -p1, 0, 0, 0, p1, 1e-12);
  EXPECT_NEAR(p.ie, -0.5 * p1 * dv, 1e-12);
  // Tension from rest: volume 1 -> 1.1: mu = 1/1.1 - 1, p1 = a = 18 mu (b = 0 in
  // tension), negative; e1 = -p1 dv / 2 with dv = 0.1.
  Particle t;
  const double dt3 = 0.1 / 3.0;
  const double det[6] = {dt3, dt3, dt3, 0, 0, 0};
  mpm3d::stress_update(m, det, kZeroSpin, 1e-3, 2.0, 1.0, 1.1, t.state());
  const double mu = 1.0 / 1.1 - 1.0;
  const double pt = 18.0 * mu;
  expect_stress(t.sig, -pt, -pt, -pt, 0, 0, 0, 2.0, 1e-12);
  EXPECT_NEAR(t.ie, -0.5 * pt * 0.1, 1e-12);
}

// The current version's null water: the weakly compressible EOS p = c0^2 (rho - rho0)
// (independent of the internal energy) and the viscous deviator 2 mu dev(D), D = de / dt.
// rho0 = 1000, c0 = 10: compressed from V 1 to 0.998 (mass 1000: rho = 1002.004...),
// p = 100 (1000 / 0.998 - 1000); shear rate D_xy = 0.5 de_xy... here de = (e, 0, 0, 0, 0, g)
// with dt = 1e-3: dev D = (2e/3, -e/3, -e/3) / dt, s_xy = 2 mu g / dt.
TEST(Constitution, CurrentNullViscousFluidWithWeaklyCompressibleEos) {
  MaterialParams m{};
  m.type = MAT_NULL;
  m.rho0 = 1000.0;
  m.bulk_modulus = 1.0e5;
  m.viscosity = 0.5;
  m.wave_speed = 10.0;
  m.eos_type = EOS_WEAK;
  m.eos[0] = 10.0;
  ASSERT_EQ(mpm3d::material_derive(m), "");
  Particle p;
  const double e = -0.002, g = 1e-4, dt = 1e-3;
  const double de[6] = {e, 0, 0, 0, 0, g};
  mpm3d::stress_update(m, de, kZeroSpin, dt, 1000.0, 1.0, 0.998, p.state());
  const double pres = 100.0 * (1000.0 / 0.998 - 1000.0);
  const double two_mu = 2.0 * 0.5 / dt;
  expect_stress(p.sig, two_mu * (2.0 * e / 3.0) - pres, two_mu * (-e / 3.0) - pres, two_mu * (-e / 3.0) - pres, 0.0,
                0.0, two_mu * g, pres, 1e-12);
  // Without viscosity: the pressure alone.
  MaterialParams inviscid = m;
  inviscid.viscosity = 0.0;
  Particle q;
  mpm3d::stress_update(inviscid, de, kZeroSpin, dt, 1000.0, 1.0, 0.998, q.state());
  expect_stress(q.sig, -pres, -pres, -pres, 0.0, 0.0, 0.0, pres, 1e-12);
}
