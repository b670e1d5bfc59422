// The vector stress update (stress_block, kStressLanes particles at once) against the
// scalar one (stress_update, one particle): the same bits in every lane, for every
// material, EOS, failure, heating, burn and bulk-viscosity path, with lanes that take
// different branches (elastic and yielding, compressed and stretched, failed and intact)
// side by side. A lane must never see its neighbours' branch.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "materials/constitution.hpp"
#include "materials/material.hpp"
#include "materials/drucker_prager_lanes.hpp"

namespace {

struct Case {
  std::string name;
  MaterialParams m;
  bool thermal, bulk;
  double rate;  // scale of the velocity gradient (1/time)
};

MaterialParams solid(int type, int eos_type) {
  MaterialParams m{};
  m.type = type;
  m.rho0 = 8.93e-3;
  m.young = 117.0e3;
  m.poisson = 0.35;
  m.yield0 = 90.0;
  m.hardening = 292.0;
  m.jc_n = 0.31;
  m.jc_c = 0.025;
  m.jc_m = 1.09;
  m.t_room = 20.0;
  m.t_melt = 1083.0;
  m.heat_cap = 385.0e6;
  m.eps0dot = 1.0e-3;
  if (type == MAT_SJCF || type == MAT_JCF) m.fail_strain = 0.4;
  if (type == MAT_PLA1 || type == MAT_PLA2) m.yield0 = 157.0;
  if (type == MAT_PLA2) m.hardening = 423.5;
  if (type == MAT_CLAY) {  // softening from 157 to 40 (steepest slope 936, 3G = 130,000)
    m.clay_peak = 157.0;
    m.clay_residual = 40.0;
    m.clay_softening = 8.0;
  }
  if (type == MAT_DPM) {
    m.young = 50.0;
    m.poisson = 0.3;
    m.dp_qphi = 0.6;
    m.dp_kphi = 0.02;
    m.dp_qpsi = 0.1;
    m.dp_tension = 0.01;
  }
  m.eos_type = eos_type;
  if (eos_type == EOS_MIE_GRUNEISEN) {
    m.eos[0] = 3940.0, m.eos[1] = 1.49, m.eos[2] = 1.96;
  } else if (eos_type == EOS_LINEAR) {
    const double c[7] = {0.0, 1.4e5, 2.0e5, 3.0e5, 1.5, 0.5, 0.25};
    for (int i = 0; i < 7; ++i) m.eos[i] = c[i];
  }
  EXPECT_EQ(mpm3d::material_derive(m), "");
  return m;
}

MaterialParams tnt() {
  MaterialParams m{};
  m.type = MAT_HIEX;
  m.rho0 = 1.63e-3;
  m.wave_speed = m.det_vel = 6930.0;
  m.eos_type = EOS_JWL;
  const double jwl[5] = {3.712e5, 3.21e3, 4.15, 0.95, 0.3};
  for (int i = 0; i < 5; ++i) m.eos[i] = jwl[i];
  EXPECT_EQ(mpm3d::material_derive(m), "");
  m.burn_width = 0.075;
  return m;
}

MaterialParams gas() {
  MaterialParams m{};
  m.type = MAT_NULL;
  m.rho0 = 1.0;
  m.wave_speed = 1.2;
  m.eos_type = EOS_LINEAR;
  m.eos[4] = m.eos[5] = 0.4;
  EXPECT_EQ(mpm3d::material_derive(m), "");
  return m;
}

std::vector<Case> cases() {
  std::vector<Case> v;
  const int types[] = {MAT_ELAS, MAT_PLA1, MAT_PLA2, MAT_JOHN, MAT_SJC, MAT_SJCF, MAT_JCF};
  const int eoses[] = {EOS_NONE, EOS_LINEAR, EOS_MIE_GRUNEISEN};
  for (int t : types)
    for (int e : eoses)
      for (int bulk = 0; bulk < 2; ++bulk) {
        const bool thermal = t == MAT_JOHN || t == MAT_JCF;
        v.push_back({std::string(mpm3d::material_keyword(t)) + "_eos" + std::to_string(e) +
                         (bulk ? "_bulk" : ""),
                     solid(t, e), thermal, bulk == 1, 30.0});
      }
  MaterialParams sjc_linear = solid(MAT_SJC, EOS_MIE_GRUNEISEN);  // Taylor.mpm's: n 1, C 0
  sjc_linear.jc_n = 1.0;
  sjc_linear.jc_c = 0.0;
  v.push_back({"sjc_n1_c0", sjc_linear, false, false, 30.0});
  v.push_back({"clay", solid(MAT_CLAY, EOS_NONE), false, false, 30.0});
  v.push_back({"clay_bulk", solid(MAT_CLAY, EOS_NONE), false, true, 30.0});
  v.push_back({"dpm", solid(MAT_DPM, EOS_NONE), false, false, 0.5});
  v.push_back({"dpm_bulk", solid(MAT_DPM, EOS_NONE), false, true, 0.5});
  v.push_back({"hiex_jwl", tnt(), false, false, 30.0});
  v.push_back({"hiex_jwl_bulk", tnt(), false, true, 30.0});
  v.push_back({"null_gas_bulk", gas(), false, true, 2.0});
  return v;
}

// A random batch: velocity gradients of either sign (compression and tension, yielding
// and elastic lanes), prior stresses, plastic strains on both sides of the failure strain.
mpm3d::StressBlock random_block(std::mt19937_64& rng, const Case& k) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  mpm3d::StressBlock b{};
  const double scale = 2.0 * k.m.yield0 + 1.0;
  for (int i = 0; i < mpm3d::kStressLanes; ++i) {
    for (int r = 0; r < 9; ++r) b.L[r][i] = k.rate * u(rng);
    b.mass[i] = k.m.rho0 * (1.0 + 0.1 * u(rng));
    b.vol[i] = 1.0 + 0.2 * u(rng);
    for (int c = 0; c < 6; ++c) b.sig[c][i] = scale * u(rng);
    b.epeff[i] = 0.8 * pos(rng);
    b.ie[i] = 10.0 * pos(rng);
    b.temp[i] = k.thermal ? 20.0 + 1500.0 * pos(rng) : 0.0;
    b.qv[i] = k.bulk ? pos(rng) : 0.0;
    b.burn[i] = k.m.type == MAT_HIEX ? (i % 2 ? 1.0 : pos(rng)) : 1.0;
  }
  return b;
}

}  // namespace

TEST(StressLanes, EveryLaneEqualsTheScalarUpdateBitForBit) {
  std::mt19937_64 rng(20261123);
  const double dt = 1.0e-3;
  int yielded = 0, elastic = 0;
  for (const Case& k : cases()) {
    const mpm3d::StressBlockArgs args{dt, k.thermal, k.bulk, 1.5, 0.06, 0.5};
    for (int trial = 0; trial < 200; ++trial) {
      const mpm3d::StressBlock in = random_block(rng, k);
      mpm3d::StressBlock vec = in, lane = in;
      mpm3d::stress_block(k.m, vec, args);
      for (int i = 0; i < mpm3d::kStressLanes; ++i) mpm3d::stress_block_lane(k.m, lane, i, args);
      // The scalar API, as the stage called it before the vector code.
      for (int i = 0; i < mpm3d::kStressLanes; ++i) {
        double L[9];
        for (int r = 0; r < 9; ++r) L[r] = in.L[r][i];
        const double de[6] = {L[0] * dt, L[4] * dt, L[8] * dt, (0.5 * (L[5] + L[7])) * dt,
                              (0.5 * (L[2] + L[6])) * dt, (0.5 * (L[1] + L[3])) * dt};
        const double dw[3] = {(0.5 * (L[5] - L[7])) * dt, (0.5 * (L[2] - L[6])) * dt,
                              (0.5 * (L[1] - L[3])) * dt};
        const double vol_old = in.vol[i];
        double vol_new = vol_old * (1.0 + ((de[0] + de[1]) + de[2]));
        double sig[6], epeff = in.epeff[i], ie = in.ie[i], temp = in.temp[i], qv = in.qv[i];
        for (int c = 0; c < 6; ++c) sig[c] = in.sig[c][i];
        mpm3d::StressState st{sig, &epeff, &ie, k.thermal ? &temp : nullptr, k.bulk ? &qv : nullptr, &vol_new};
        mpm3d::stress_update(k.m, de, dw, dt, in.mass[i], vol_old, vol_new, st, in.burn[i], args.q1,
                             args.q2, args.qlen);
        const double got[] = {vec.vol[i], vec.sig[0][i], vec.sig[1][i], vec.sig[2][i], vec.sig[3][i],
                              vec.sig[4][i], vec.sig[5][i], vec.epeff[i], vec.ie[i], vec.temp[i], vec.qv[i]};
        const double one[] = {lane.vol[i], lane.sig[0][i], lane.sig[1][i], lane.sig[2][i], lane.sig[3][i],
                              lane.sig[4][i], lane.sig[5][i], lane.epeff[i], lane.ie[i], lane.temp[i],
                              lane.qv[i]};
        const double want[] = {vol_new, sig[0], sig[1], sig[2], sig[3], sig[4], sig[5], epeff, ie, temp, qv};
        ASSERT_EQ(std::memcmp(got, want, sizeof want), 0) << k.name << " trial " << trial << " lane " << i;
        ASSERT_EQ(std::memcmp(one, want, sizeof want), 0) << k.name << " trial " << trial << " lane " << i;
        (epeff > in.epeff[i] ? yielded : elastic)++;
      }
    }
  }
  // The batches mixed both kinds of lanes (otherwise the selects were not exercised).
  EXPECT_GT(yielded, 1000);
  EXPECT_GT(elastic, 1000);
}

namespace {

MaterialParams neo_hookean() {
  MaterialParams m{};
  m.type = MAT_NEOH;
  m.rho0 = 1100.0;
  m.young = 17.0e6;
  m.poisson = 0.3;
  EXPECT_EQ(mpm3d::material_derive(m), "");
  return m;
}

// One particle from rest (H = 0, no stress) through one increment L dt.
mpm3d::StressBlock neo_hookean_step(const MaterialParams& m, const double L[9], double dt) {
  mpm3d::StressBlock b{};
  for (int r = 0; r < 9; ++r) b.L[r][0] = L[r];
  b.mass[0] = m.rho0;
  b.vol[0] = 1.0;
  mpm3d::stress_block_lane(m, b, 0, mpm3d::StressBlockArgs{dt, false, false, 0.0, 0.0, 0.0, true});
  return b;
}

}  // namespace

// neoh: sigma = (G (B - I) + lambda ln J I) / J of F = I + L dt, against the closed forms of
// a uniaxial stretch and a simple shear.
TEST(StressLanes, NeoHookeanStretchAndShear) {
  const MaterialParams m = neo_hookean();
  const double G = m.young / (2.0 * (1.0 + m.poisson));
  const double lam = m.young * m.poisson / ((1.0 + m.poisson) * (1.0 - 2.0 * m.poisson));
  const double dt = 1.0e-3, e = 0.05;
  const double stretch[9] = {e / dt, 0, 0, 0, 0, 0, 0, 0, 0};
  mpm3d::StressBlock b = neo_hookean_step(m, stretch, dt);
  const double J = 1.0 + e;
  EXPECT_NEAR(b.sig[0][0], (G * (J * J - 1.0) + lam * std::log(J)) / J, 1e-9 * G);
  EXPECT_NEAR(b.sig[1][0], lam * std::log(J) / J, 1e-9 * G);
  EXPECT_NEAR(b.sig[2][0], lam * std::log(J) / J, 1e-9 * G);
  EXPECT_EQ(b.sig[3][0], 0.0);
  EXPECT_NEAR(b.vol[0], J, 1e-15);
  EXPECT_NEAR(b.H[0][0], e, 1e-15);
  const double g = 0.1;
  const double shear[9] = {0, g / dt, 0, 0, 0, 0, 0, 0, 0};  // dv_x / dy
  b = neo_hookean_step(m, shear, dt);
  EXPECT_NEAR(b.sig[0][0], G * g * g, 1e-9 * G);  // J = 1, B - I = [[g^2, g, 0], [g, 0, 0], 0]
  EXPECT_NEAR(b.sig[5][0], G * g, 1e-9 * G);      // xy
  EXPECT_NEAR(b.sig[1][0], 0.0, 1e-9 * G);
  EXPECT_EQ(b.sig[3][0], 0.0);
  EXPECT_EQ(b.sig[4][0], 0.0);
  EXPECT_NEAR(b.vol[0], 1.0, 1e-15);
  // A second, opposite increment brings F back to I: no stress left (hyperelastic: the
  // stress depends on F only, not on the path).
  mpm3d::StressBlock back = b;
  for (int r = 0; r < 9; ++r) back.L[r][0] = -shear[r];
  mpm3d::stress_block_lane(m, back, 0, mpm3d::StressBlockArgs{dt, false, false, 0.0, 0.0, 0.0, true});
  // F = (I - L dt)(I + L dt) = I - (L dt)^2 = I for this L (L^2 = 0).
  for (int c = 0; c < 6; ++c) EXPECT_NEAR(back.sig[c][0], 0.0, 1e-9 * G) << c;
}

// The neoh lanes and the UVFp volume of the other models: every lane of the vector update
// equals the lane-by-lane update, bit for bit (the Fortran reference follows the latter).
TEST(StressLanes, NeoHookeanAndUvfLanesEqualOneLaneAtATime) {
  std::mt19937_64 rng(20261125);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double dt = 1.0e-3;
  const MaterialParams models[] = {neo_hookean(), solid(MAT_ELAS, EOS_NONE), solid(MAT_PLA2, EOS_NONE)};
  for (const MaterialParams& m : models) {
    const mpm3d::StressBlockArgs args{dt, false, false, 0.0, 0.0, 0.0, true};
    for (int trial = 0; trial < 500; ++trial) {
      mpm3d::StressBlock in{};
      for (int i = 0; i < mpm3d::kStressLanes; ++i) {
        for (int r = 0; r < 9; ++r) in.L[r][i] = 20.0 * u(rng);
        for (int r = 0; r < 9; ++r) in.H[r][i] = m.type == MAT_NEOH ? 0.2 * u(rng) : 0.0;
        in.mass[i] = m.rho0;
        in.vol[i] = 1.0 + 0.2 * u(rng);
        for (int c = 0; c < 6; ++c) in.sig[c][i] = 1.0e3 * u(rng);
        in.ie[i] = 1.0 + u(rng);
        in.burn[i] = 1.0;
      }
      mpm3d::StressBlock vec = in, lane = in;
      mpm3d::stress_block(m, vec, args);
      for (int i = 0; i < mpm3d::kStressLanes; ++i) mpm3d::stress_block_lane(m, lane, i, args);
      ASSERT_EQ(std::memcmp(&vec, &lane, sizeof vec), 0) << mpm3d::material_keyword(m.type) << " trial " << trial;
      for (int i = 0; i < mpm3d::kStressLanes; ++i) {
        // det(I + L dt) volume, not 1 + tr
        double A[9];
        for (int r = 0; r < 9; ++r) A[r] = in.L[r][i] * dt;
        const double det = (1 + A[0]) * ((1 + A[4]) * (1 + A[8]) - A[5] * A[7]) -
                           A[1] * (A[3] * (1 + A[8]) - A[5] * A[6]) + A[2] * (A[3] * A[7] - (1 + A[4]) * A[6]);
        ASSERT_NEAR(vec.vol[i], in.vol[i] * det, 1e-14);
      }
    }
  }
}

// TLmp: the total Lagrangian neo-Hookean update. From rest through one reference increment
// dF the Cauchy stress is that of the updated Lagrangian form for the same F (uniaxial
// stretch), V0 P = V0 (G (F - F^-T) + lambda ln J F^-T) is kept, the volume is V0 J; and
// every lane of the vector update equals the lane-by-lane one, bit for bit.
TEST(StressLanes, TotalLagrangianNeoHookean) {
  const MaterialParams m = neo_hookean();
  const double G = m.young / (2.0 * (1.0 + m.poisson));
  const double lam = m.young * m.poisson / ((1.0 + m.poisson) * (1.0 - 2.0 * m.poisson));
  const double dt = 1.0e-3, e = 0.05, v0 = 1.0;
  mpm3d::StressBlock b{};
  b.L[0][0] = e / dt;
  b.mass[0] = m.rho0 * v0;
  b.vol[0] = v0;
  const mpm3d::StressBlockArgs tl{dt, false, false, 0.0, 0.0, 0.0, true, true};
  mpm3d::stress_block_lane(m, b, 0, tl);
  const double J = 1.0 + e;
  EXPECT_NEAR(b.sig[0][0], (G * (J * J - 1.0) + lam * std::log(J)) / J, 1e-9 * G);
  EXPECT_NEAR(b.sig[1][0], lam * std::log(J) / J, 1e-9 * G);
  EXPECT_NEAR(b.pk1[0][0], v0 * (G * (J - 1.0 / J) + lam * std::log(J) / J), 1e-9 * G);
  EXPECT_NEAR(b.pk1[4][0], v0 * lam * std::log(J), 1e-9 * G);
  EXPECT_EQ(b.pk1[1][0], 0.0);
  EXPECT_NEAR(b.vol[0], v0 * J, 1e-15);
  EXPECT_NEAR(b.H[0][0], e, 1e-15);
  // The work of the step: the trapezoid of V0 P on dF, from zero.
  EXPECT_NEAR(b.ie[0], 0.5 * b.pk1[0][0] * e, 1e-12 * G);

  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    mpm3d::StressBlock in{};
    for (int i = 0; i < mpm3d::kStressLanes; ++i) {
      for (int r = 0; r < 9; ++r) in.L[r][i] = 20.0 * u(rng);
      for (int r = 0; r < 9; ++r) in.H[r][i] = 0.2 * u(rng);
      for (int r = 0; r < 9; ++r) in.pk1[r][i] = 1.0e3 * u(rng);
      in.mass[i] = m.rho0 * (1.0 + 0.1 * u(rng));
      in.vol[i] = 1.0 + 0.2 * u(rng);
      in.ie[i] = 1.0 + u(rng);
      in.burn[i] = 1.0;
    }
    mpm3d::StressBlock vec = in, lane = in;
    mpm3d::stress_block(m, vec, tl);
    for (int i = 0; i < mpm3d::kStressLanes; ++i) mpm3d::stress_block_lane(m, lane, i, tl);
    ASSERT_EQ(std::memcmp(&vec, &lane, sizeof vec), 0) << "trial " << trial;
  }
}

// The Drucker-Prager material of both return tests below (cohesion, a tension cut-off).
static MaterialParams dp_test_material() {
  MaterialParams m{};
  m.dp_qphi = 0.6;
  m.dp_kphi = 0.02;
  m.dp_qpsi = 0.1;
  m.dp_tension = 0.01;
  return m;
}

// The Drucker-Prager return in lanes (selects over its four arms) against the scalar
// dp_return with its branches (constitution.cpp), bit for bit, on stress states that reach
// every arm: elastic, shear, shear landing beyond the cut-off (then tension), tension
// below and at the corner.
TEST(StressLanes, DruckerPragerReturnInLanesEqualsTheBranches) {
  using VL = mpm3d::VectorLane<4>;
  using V = VL::D;
  const MaterialParams m = dp_test_material();
  const double K = 40.0, G = 20.0, tau_p = m.dp_kphi - m.dp_qphi * m.dp_tension;
  std::mt19937_64 rng(20261127);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int elastic = 0, shear = 0, tension_below = 0, tension_corner = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    double s[4][6], sm[4];
    V sv[6], smv;
    for (int i = 0; i < 4; ++i) {
      const double scale = 0.05 * std::pow(10.0, u(rng));  // around the surface and far out
      for (int c = 0; c < 6; ++c) s[i][c] = (c < 3 ? 1.0 : 0.5) * scale * u(rng);
      const double dev_mean = (s[i][0] + s[i][1] + s[i][2]) / 3.0;
      for (int c = 0; c < 3; ++c) s[i][c] -= dev_mean;
      sm[i] = 0.04 * u(rng);
      for (int c = 0; c < 6; ++c) sv[c][i] = s[i][c];
      smv[i] = sm[i];
    }
    double sd[6], smd;
    for (int c = 0; c < 6; ++c) sd[c] = s[1][c];
    smd = sm[1];
    const V dv = mpm3d::DruckerPragerLanes<V, VL>::dp_return(m, sv, smv, K, G);
    const double dd = mpm3d::DruckerPragerLanes<double, mpm3d::ScalarLane>::dp_return(m, sd, smd, K, G);
    for (int i = 0; i < 4; ++i) {
      const double tau = std::sqrt(0.5 * ((s[i][0] * s[i][0] + s[i][1] * s[i][1]) + s[i][2] * s[i][2]) +
                                   ((s[i][3] * s[i][3] + s[i][4] * s[i][4]) + s[i][5] * s[i][5]));
      double ref_s[6], ref_sm = sm[i];
      for (int c = 0; c < 6; ++c) ref_s[c] = s[i][c];
      const double ref = mpm3d::dp_return(m, ref_s, &ref_sm, K, G);
      EXPECT_EQ(std::memcmp(&ref, &dv[i], sizeof ref), 0) << "trial " << trial << " lane " << i;
      EXPECT_EQ(std::memcmp(&ref_sm, &smv[i], sizeof ref_sm), 0) << "trial " << trial << " lane " << i;
      for (int c = 0; c < 6; ++c) EXPECT_EQ(std::memcmp(&ref_s[c], &sv[c][i], sizeof(double)), 0) << trial;
      if (i == 1) {
        EXPECT_EQ(std::memcmp(&ref, &dd, sizeof ref), 0) << "trial " << trial;
        EXPECT_EQ(std::memcmp(&ref_sm, &smd, sizeof ref_sm), 0) << "trial " << trial;
      }
      if (ref == 0.0 && ref_sm == sm[i]) ++elastic;
      else if (ref_sm != m.dp_tension) ++shear;
      else if (tau > tau_p) ++tension_corner;
      else ++tension_below;
    }
  }
  // Every arm was taken by a tenth of the lanes or more.
  EXPECT_GT(elastic, 1600);
  EXPECT_GT(shear, 1600);
  EXPECT_GT(tension_below, 1600);
  EXPECT_GT(tension_corner, 1600);
}

// The original programs' Drucker-Prager return (rule dp_return=original) in lanes against
// the same function on one double, bit for bit, on states that reach each of its arms:
// elastic, shear below the cut-off, shear at or beyond it (sm' may stay beyond), and the
// tension return that sets sm' = sigma_t and keeps the deviator.
TEST(StressLanes, DruckerPragerOriginalReturnInLanesEqualsOneLane) {
  using VL = mpm3d::VectorLane<4>;
  using V = VL::D;
  const MaterialParams m = dp_test_material();
  const double K = 40.0, G = 20.0;
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int elastic = 0, shear_below = 0, shear_beyond = 0, tension = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    double s[4][6], sm[4];
    V sv[6], smv;
    for (int i = 0; i < 4; ++i) {
      const double scale = 0.05 * std::pow(10.0, u(rng));
      for (int c = 0; c < 6; ++c) s[i][c] = (c < 3 ? 1.0 : 0.5) * scale * u(rng);
      const double dev_mean = (s[i][0] + s[i][1] + s[i][2]) / 3.0;
      for (int c = 0; c < 3; ++c) s[i][c] -= dev_mean;
      sm[i] = 0.04 * u(rng);
      for (int c = 0; c < 6; ++c) sv[c][i] = s[i][c];
      smv[i] = sm[i];
    }
    const V dv = mpm3d::DruckerPragerLanes<V, VL>::dp_return_original(m, sv, smv, K, G);
    for (int i = 0; i < 4; ++i) {
      double sd[6], smd = sm[i];
      for (int c = 0; c < 6; ++c) sd[c] = s[i][c];
      const double dd = mpm3d::DruckerPragerLanes<double, mpm3d::ScalarLane>::dp_return_original(m, sd, smd, K, G);
      EXPECT_EQ(std::memcmp(&dd, &dv[i], sizeof dd), 0) << "trial " << trial << " lane " << i;
      EXPECT_EQ(std::memcmp(&smd, &smv[i], sizeof smd), 0) << "trial " << trial << " lane " << i;
      for (int c = 0; c < 6; ++c) EXPECT_EQ(std::memcmp(&sd[c], &sv[c][i], sizeof(double)), 0) << trial;
      const bool kept = std::memcmp(sd, s[i], sizeof sd) == 0;
      if (kept && smd == sm[i]) ++elastic;
      else if (kept && smd == m.dp_tension) ++tension;
      else if (sm[i] < m.dp_tension) ++shear_below;
      else ++shear_beyond;
    }
  }
  EXPECT_GT(elastic, 1000);
  EXPECT_GT(shear_below, 1000);
  EXPECT_GT(shear_beyond, 1000);
  EXPECT_GT(tension, 1000);
}
