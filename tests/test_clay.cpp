// clay (material 12, the newest version's undrained clay): J2 plasticity with the yield
// stress softening exponentially, sigma_y(e) = kr + (kp - kr) exp(-eta e), against its
// closed form on two proportional strain paths, for both returns (rule clay_return).
//
// On a path whose deviatoric strain keeps its direction, from zero stress, the exact
// response is: q = q_trial - 3G epeff and q = sigma_y(epeff), where q_trial is the von Mises
// stress of the whole strain taken elastically. Simple shear (tensor shear e_xy = g):
// q_trial = 2 sqrt(3) G g. Uniaxial strain e_xx = e: q_trial = 2G e, the mean stress
// K e elastic throughout (K = lambda + 2G/3). epeff solves f(e) = q_trial - 3G e - sigma_y(e)
// = 0, a decreasing function (3G > eta (kp - kr)): bisection here, to the last bits.
#include <gtest/gtest.h>

#include <cmath>

#include "materials/constitution.hpp"
#include "materials/material.hpp"

namespace {

// E = 240, nu = 0.2: G = 100, 3G = 300, lambda = 200/3, K = 400/3. Peak 1, residual 0.25,
// eta 40: the steepest softening slope 30 < 3G.
MaterialParams clay() {
  MaterialParams m{};
  m.type = MAT_CLAY;
  m.rho0 = 1.0;
  m.young = 240.0;
  m.poisson = 0.2;
  m.clay_peak = 1.0;
  m.clay_residual = 0.25;
  m.clay_softening = 40.0;
  EXPECT_EQ(mpm3d::material_derive(m), "");
  return m;
}

double sigma_y(const MaterialParams& m, double e) {
  return m.clay_residual + (m.clay_peak - m.clay_residual) * std::exp(-m.clay_softening * e);
}

// The closed-form epeff for a trial von Mises stress q_trial (0 where elastic).
double exact_epeff(const MaterialParams& m, double q_trial) {
  if (q_trial <= m.clay_peak) return 0.0;
  const double g3 = 3.0 * m.shear;
  double lo = 0.0, hi = q_trial / g3;  // f(lo) > 0 >= f(hi) since sigma_y > 0
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (q_trial - g3 * mid - sigma_y(m, mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double von_mises(const double s[6]) {
  const double mean = (s[0] + s[1] + s[2]) / 3.0;
  const double d[3] = {s[0] - mean, s[1] - mean, s[2] - mean};
  return std::sqrt(1.5 * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

struct Path {
  int component;  // Voigt component of the strain increment (0: uniaxial strain, 5: shear)
  double q_trial_per_strain;
};

// Drives n equal increments of size inc along the path; returns the largest relative errors
// of epeff and of q against the closed form, and of q against sigma_y(epeff) (the stress on
// the softening curve). Checks the mean stress (uniaxial strain) on the way.
struct Errors {
  double epeff = 0.0, q = 0.0, curve = 0.0;
  int plastic_steps = 0;
};

Errors drive(const MaterialParams& m, const Path& path, int n, double inc, bool original) {
  StepRules rules{};
  rules.clay_return = original ? 1 : 0;
  double sig[6] = {0, 0, 0, 0, 0, 0}, epeff = 0.0, ie = 0.0;
  const double dw[3] = {0, 0, 0};
  Errors err;
  for (int k = 1; k <= n; ++k) {
    double de[6] = {0, 0, 0, 0, 0, 0};
    de[path.component] = inc;
    const double vol_old = 1.0, vol_new = path.component < 3 ? 1.0 + inc : 1.0;
    const double before = epeff;
    mpm3d::stress_update(m, de, dw, 1e-3, 1.0, vol_old, vol_new, mpm3d::StressState{sig, &epeff, &ie, nullptr, nullptr},
                         1.0, 0.0, 0.0, 0.0, rules);
    if (epeff > before) ++err.plastic_steps;
    const double strain = k * inc, q_trial = path.q_trial_per_strain * strain;
    const double e_exact = exact_epeff(m, q_trial), q_exact = q_trial - 3.0 * m.shear * e_exact;
    const double q = von_mises(sig);
    err.epeff = std::fmax(err.epeff, std::fabs(epeff - e_exact) / std::fmax(e_exact, 1e-3));
    err.q = std::fmax(err.q, std::fabs(q - q_exact) / m.clay_peak);
    if (epeff > 0.0) err.curve = std::fmax(err.curve, std::fabs(q - sigma_y(m, epeff)) / m.clay_peak);
    if (path.component == 0) {
      const double K = m.lambda + 2.0 * m.shear / 3.0;
      EXPECT_NEAR((sig[0] + sig[1] + sig[2]) / 3.0, K * strain, 1e-11) << "step " << k;
    }
  }
  return err;
}

const Path kShear{5, 2.0 * std::sqrt(3.0) * 100.0};
const Path kUniaxial{0, 2.0 * 100.0};

}  // namespace

// Our return lands on the closed form whatever the step: 400 small steps and 8 large ones
// both follow the softening curve to the residual strength (epeff up to 0.15).
static void expect_closed_form(const Path& path, double total_strain) {
  const MaterialParams m = clay();
  for (int n : {400, 8}) {
    const Errors e = drive(m, path, n, total_strain / n, false);
    EXPECT_GT(e.plastic_steps, n / 2) << n;
    EXPECT_LT(e.epeff, 1e-11) << n;
    EXPECT_LT(e.q, 1e-11) << n;
    EXPECT_LT(e.curve, 1e-11) << n;
  }
}

TEST(Clay, SolvedReturnFollowsTheClosedFormInShear) { expect_closed_form(kShear, 0.2); }

TEST(Clay, SolvedReturnFollowsTheClosedFormInUniaxialStrain) { expect_closed_form(kUniaxial, 0.3); }

// The newest program's return (rule clay_return=linear) puts the stress on the softening
// curve at its new epeff, but its epeff, from one linearised step with the slope at the start,
// lags the closed form: by under 1 % with small steps, by far more with large ones.
TEST(Clay, LinearReturnStaysOnTheCurveButDriftsWithTheStep) {
  const MaterialParams m = clay();
  const Errors fine = drive(m, kShear, 400, 0.2 / 400, true);
  const Errors coarse = drive(m, kShear, 8, 0.2 / 8, true);
  EXPECT_LT(fine.curve, 1e-12);
  EXPECT_LT(coarse.curve, 1e-12);
  EXPECT_LT(fine.q, 1e-2);
  EXPECT_GT(coarse.q, 1e-2);
  EXPECT_GT(coarse.epeff, 10.0 * fine.epeff);
}

// Elastic below the peak: the trial stress is kept exactly and epeff stays 0.
TEST(Clay, ElasticBelowThePeak) {
  const MaterialParams m = clay();
  const Errors e = drive(m, kShear, 10, 0.9 / kShear.q_trial_per_strain / 10, false);
  EXPECT_EQ(e.plastic_steps, 0);
  EXPECT_LT(e.q, 1e-14);
}

TEST(Clay, CardChecks) {
  MaterialParams m = clay();
  m.clay_softening = 400.0;  // slope 300 = 3G: no unique return
  EXPECT_NE(mpm3d::material_derive(m).find("below 3G"), std::string::npos);
  m = clay();
  m.clay_residual = 2.0;  // above the peak
  EXPECT_NE(mpm3d::material_derive(m), "");
  m = clay();
  m.clay_softening = -1.0;
  EXPECT_NE(mpm3d::material_derive(m), "");
}
