// The legacy Taylor bar deck (../shared/decks/Taylor.mpm, not ours: used in place, skipped
// when absent): copper at 190 m/s against a symmetry plane, to 0.08 ms, against the
// original program's results (../shared/reference/README.md):
//   L = 16.58 mm, D = 13.51 mm (particle-centre extents plus dp = 0.38 mm), 604 steps.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "io/analysis.hpp"
#include "input/data_in.hpp"
#include "mpm3d.hpp"

TEST(Taylor, LegacyDeckMatchesTheOriginalProgram) {
  const std::string deck = std::string(MPM3D_SHARED_DECKS) + "/Taylor.mpm";
  if (!std::filesystem::exists(deck)) GTEST_SKIP() << deck << " not present";
  mpm3d::Model model = mpm3d::read_deck(deck);
  ASSERT_EQ(model.particles.np, 21172);
  ASSERT_EQ(model.endtime, 0.08);
  // dt = 0.8 * 0.76 / c with c = sqrt(E (1 - nu) / ((1 + nu)(1 - 2 nu) rho)); the original
  // reports 1.326e-4 ms.
  const double c = std::sqrt(117.0e3 * 0.65 / (1.35 * 0.3 * 8.93e-3));
  EXPECT_NEAR(model.dt, 0.8 * 0.76 / c, 1e-12 * model.dt);
  EXPECT_NEAR(model.dt, 1.326e-4, 0.001e-4);

  mpm3d::Simulation sim(std::move(model));
  // Initial kinetic energy 1/2 M v^2 with M = 21172 particles of the deck's 4.900070e-4 g
  // (= 8.93e-3 * 0.38^3 to 7 digits), v = 190 mm/ms:
  const double mass = 21172.0 * 4.900070e-4;
  const double ke0 = 0.5 * mass * 190.0 * 190.0;
  EXPECT_NEAR(sim.initial_total_energy, ke0, 1e-9 * ke0);  // reference: 1.872e5
  EXPECT_NEAR(ke0, 1.872e5, 0.001e5);
  const double p0 = mass * 190.0;

  // The program's loop: step until t >= endtime (to a relative 1e-9 of dt).
  const double end = sim.model.endtime, eps = 1e-9 * sim.model.dt;
  while (sim.time < end - eps) sim.step();
  EXPECT_EQ(sim.steps, 604);
  EXPECT_EQ(sim.outside, 0);

  const mpm3d::TaylorMeasures t = mpm3d::taylor_measures(sim.model.particles.x, 0.38, 25.4);
  EXPECT_NEAR(t.length, 16.58, 0.2);
  EXPECT_NEAR(t.impact_diameter, 13.51, 0.3);
  // Energy conserved within 1% of the initial total (mostly turned into plastic work).
  const double e1 = sim.kinetic + sim.internal;
  EXPECT_NEAR(e1, sim.initial_total_energy, 0.01 * sim.initial_total_energy);
  EXPECT_GT(sim.internal, 0.9 * e1);
  // Symmetric about the bar axis: no transverse momentum (to rounding of p0 = M v).
  EXPECT_NEAR(sim.momentum[0], 0.0, 1e-10 * p0);
  EXPECT_NEAR(sim.momentum[1], 0.0, 1e-10 * p0);
  // Maximum plastic strain: the original reports 1.61.
  double max_ep = 0;
  for (double e : sim.model.particles.epeff) max_ep = std::max(max_ep, e);
  EXPECT_NEAR(max_ep, 1.61, 0.15);
}
