// Multi-velocity contact (cont lagr) and GIMP through the whole solver: the deck keywords,
// two elastic spheres colliding (no interpenetration, momentum, separation, no energy
// gain for any step or scheme) and a block
// sliding on a heavy base (Coulomb friction: deceleration mu g).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "input/data_in.hpp"
#include "input/ffi.hpp"
#include "mpm3d.hpp"

namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

// Mass-weighted mean velocity component a of a body.
double body_velocity(const mpm3d::Simulation& sim, int b, int a) {
  const auto& P = sim.model.particles;
  double m = 0, mv = 0;
  for (int p = 0; p < P.np; ++p) {  // the solver's storage order: bodies are not runs
    if (P.body[p] != b) continue;
    m += P.mass[p];
    mv += P.mass[p] * P.v[3 * size_t(p) + a];
  }
  return mv / m;
}

// Smallest distance between a particle of body 0 and a particle of body 1.
double min_gap(const mpm3d::Simulation& sim) {
  const auto& P = sim.model.particles;
  double d2 = INFINITY;
  for (int p = 0; p < P.np; ++p)
    for (int q = 0; q < P.np; ++q) {
      if (P.body[p] != 0 || P.body[q] != 1) continue;
      double s = 0;
      for (int a = 0; a < 3; ++a) {
        const double d = P.x[3 * size_t(p) + a] - P.x[3 * size_t(q) + a];
        s += d * d;
      }
      d2 = std::min(d2, s);
    }
  return std::sqrt(d2);
}

const char* kBlockDeck =
    "mpm3d *** deck test\n"
    "nbco 2\nnbbo 2\nnbmp 10\nnmat 1\n"
    "spx 0 8\nspy 0 8\nspz 0 8\ndcel 1.0\nendt 1\n"
    "mate 1 elas 1.0 100.0 0.25\n"
    "part bloc 1 1 1.0 0.5 1 1 1 2 2 2\n"
    "part poin 2 2\n 9 1 0.027 5 5 5\n 10 1 8.0 6 6 6\n";

}  // namespace

TEST(ContactDeck, GimpHalfSizesFromSpacingAndVolume) {
  // bloc: lp = dp/2 = 0.25; poin: lp = cbrt(m/rho)/2: cbrt(0.027) / 2 = 0.15; the 8.0 mass
  // particle (volume 8, lp 1) is clamped to h/2 = 0.5 with a warning.
  const mpm3d::Model m = mpm3d::read_deck_text(std::string(kBlockDeck) + "gimp\nendi\n", "gimp.mpm");
  ASSERT_TRUE(m.gimp);
  ASSERT_EQ(m.particles.psize.size(), 10u);
  for (int p = 0; p < 8; ++p) EXPECT_EQ(m.particles.psize[p], 0.25);
  EXPECT_NEAR(m.particles.psize[8], 0.15, 1e-15);
  EXPECT_EQ(m.particles.psize[9], 0.5);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("gimp"), std::string::npos);
  // Without gimp no half-sizes are stored.
  EXPECT_TRUE(mpm3d::read_deck_text(std::string(kBlockDeck) + "endi\n", "lin.mpm").particles.psize.empty());
}

TEST(ContactDeck, ContCardIsReadAndChecked) {
  const mpm3d::Model m = mpm3d::read_deck_text(std::string(kBlockDeck) + "cont lagr 0.3 2\nendi\n", "c.mpm");
  EXPECT_TRUE(m.contact);
  EXPECT_EQ(m.contact_mu, 0.3);
  EXPECT_EQ(m.contact_normbody, 2);
  EXPECT_EQ(m.bodies[0].component, 1);
  EXPECT_EQ(m.bodies[1].component, 2);
  auto refused = [](const std::string& deck, const std::string& what) {
    try {
      mpm3d::read_deck_text(deck, "bad.mpm");
      ADD_FAILURE() << "accepted: " << what;
    } catch (const mpm3d::DeckError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  // The cont card is on line 16 of these decks.
  refused(std::string(kBlockDeck) + "cont lagr -0.1 0\nendi\n", "bad.mpm:16: 'cont': friction");
  refused(std::string(kBlockDeck) + "cont lagr 0.1 3\nendi\n", "bad.mpm:16: 'cont': normal body");
  refused(std::string(kBlockDeck) + "cont pena 0.1 0\nendi\n", "bad.mpm:16: 'cont': only 'lagr'");
  std::string one = replace(kBlockDeck, "nbco 2", "nbco 1");
  one = replace(one, "part poin 2 2", "part poin 1 2");
  refused(one + "cont lagr 0.1 0\nendi\n", "bad.mpm:16: 'cont' needs two components");
  refused(replace(kBlockDeck, "spz 0 8", "spz 0 1") + "gimp\nendi\n", "at least two cells");
}

TEST(Contact, CollidingSpheresDoNotInterpenetrateConserveMomentumAndSeparate) {
  // inputs/contact/spheres.mpm: two equal elastic spheres (R = 2, dp = 0.5, h = 1) at
  // +-20 m/s along x, frictionless contact. Checks every 10 steps: the particles of the two
  // spheres never come closer than dp; the total momentum (zero at the start) stays at
  // round-off level relative to one sphere's momentum M v0 (the corrections move momentum
  // between the two grids, d and -d); at the end the spheres fly apart (x velocities
  // reversed) and their gap grows.
  mpm3d::Simulation sim(mpm3d::read_deck(MPM3D_INPUTS "/contact/spheres.mpm"));
  const double dp = 0.5, v0 = 20.0;
  double M = 0;
  for (int p = 0; p < sim.model.particles.np; ++p) M += sim.model.particles.body[p] == 0 ? sim.model.particles.mass[p] : 0.0;
  const double scale = M * v0;
  double gap_min = INFINITY, mom_max = 0.0, force_max = 0.0;
  double gap_late = 0.0;
  const double E0 = M * v0 * v0;  // two spheres of kinetic energy M v0^2 / 2 each
  double e_max = 0.0;
  const double t_end = sim.model.endtime;
  while (sim.time < t_end - 1e-9) {
    sim.step();
    e_max = std::max(e_max, sim.kinetic + sim.internal);
    force_max = std::max(force_max, std::fabs(sim.contact_force[0]));
    for (double m : sim.momentum) mom_max = std::max(mom_max, std::fabs(m));
    if (sim.steps % 10 == 0) {
      const double g = min_gap(sim);
      gap_min = std::min(gap_min, g);
      if (sim.time < 0.75 * t_end) gap_late = g;
    }
  }
  EXPECT_GT(force_max, 0.0);  // the spheres did touch
  EXPECT_GT(gap_min, dp) << "interpenetration";  // measured: 1.37 (the grid contact acts about a cell early)
  EXPECT_LT(mom_max, 1e-13 * scale) << "momentum " << mom_max << " of scale " << scale;
  EXPECT_LT(body_velocity(sim, 0, 0), -0.5 * v0);
  EXPECT_GT(body_velocity(sim, 1, 0), 0.5 * v0);
  const double gap_end = min_gap(sim);
  EXPECT_GT(gap_end, gap_late + 1.0) << "the spheres do not fly apart";
  EXPECT_EQ(sim.outside, 0);
  // Frictionless contact of elastic bodies creates no energy: the total (kinetic plus
  // internal) never exceeds the initial M v0^2 by more than 1%; the grid contact (an
  // inelastic collision of the nodal masses) dissipates some (measured: peak 0.984 E0,
  // end 0.943 E0; before the recontact stage the rebound gained 21%, end 1.21 E0).
  EXPECT_LT(e_max, 1.01 * E0) << "energy gain";
  EXPECT_LT(sim.kinetic + sim.internal, 1.01 * E0);
  EXPECT_GT(sim.kinetic + sim.internal, 0.85 * E0) << "too much dissipation";
}

TEST(Contact, PatchStatisticsCountBothComponents) {
  // The summary's patch figures (Simulation::stats) over both components' lists: the
  // non-empty patches' mean times their number is every particle of the two spheres.
  mpm3d::Simulation sim(mpm3d::read_deck(MPM3D_INPUTS "/contact/spheres.mpm"));
  sim.step();
  EXPECT_DOUBLE_EQ(sim.stats.mean * sim.stats.nonempty, double(sim.model.particles.np));
  EXPECT_GE(sim.stats.max, sim.stats.mean);
}

TEST(Contact, SpheresGainNoEnergyWithLargerStepsOrUsf) {
  // The spheres deck with other steps and schemes. Before the recontact stage the rebound
  // gained energy in proportion to the step (MUSL: end 1.09 E0 at dtscale 0.1, 1.21 at 0.2,
  // 1.67 at 0.5; USF 1.21 at 0.2). Measured now (peak, end): USF at 0.2: 0.996, 0.981;
  // MUSL at 0.5: 1.005, 0.959; USF at 0.5: 1.021, 0.999. At dtscale 0.5 the schemes
  // themselves are off by a few percent (one velocity field, where the spheres stick
  // instead of rebounding, peaks at 1.044 E0 with MUSL and 1.055 E0 with USF), hence the 3%.
  struct Case {
    const char* scheme;
    const char* dtscale;
    double gain;
  };
  for (const Case& k : {Case{"usf on", "dtscale 0.2", 1.01}, Case{"musl on", "dtscale 0.5", 1.03},
                        Case{"usf on", "dtscale 0.5", 1.03}}) {
    std::string deck = slurp(MPM3D_INPUTS "/contact/spheres.mpm");
    deck = replace(deck, "dtscale 0.2", k.dtscale);
    deck = replace(deck, "musl on", k.scheme);
    mpm3d::Simulation sim(mpm3d::read_deck_text(deck, "spheres.mpm"));
    double M = 0;
    for (int p = 0; p < sim.model.particles.np; ++p) M += sim.model.particles.body[p] == 0 ? sim.model.particles.mass[p] : 0.0;
    const double v0 = 20.0, E0 = M * v0 * v0;
    double e_max = 0.0;
    while (sim.time < sim.model.endtime - 1e-9) {
      sim.step();
      e_max = std::max(e_max, sim.kinetic + sim.internal);
    }
    const std::string what = std::string(k.scheme) + ", " + k.dtscale;
    EXPECT_LT(e_max, k.gain * E0) << what;
    EXPECT_GT(sim.kinetic + sim.internal, 0.85 * E0) << what;
    EXPECT_LT(body_velocity(sim, 0, 0), -0.5 * v0) << what;
    EXPECT_GT(body_velocity(sim, 1, 0), 0.5 * v0) << what;
  }
}

namespace {

// Block (body 1, component 1) sliding on the heavy base of inputs/contact/sliding_block.mpm
// with friction mu: least-squares slope of the block's mean x velocity over [t0, t1].
double sliding_deceleration(const std::string& mu, double t0, double t1, double* v_end) {
  std::string deck = slurp(MPM3D_INPUTS "/contact/sliding_block.mpm");
  deck = replace(deck, "cont lagr 0.5 2", "cont lagr " + mu + " 2");
  mpm3d::Simulation sim(mpm3d::read_deck_text(deck, "sliding_block.mpm"));
  double st = 0, sv = 0, stt = 0, stv = 0;
  int n = 0;
  while (sim.time < t1) {
    sim.step();
    if (sim.time < t0) continue;
    const double v = body_velocity(sim, 1, 0);
    st += sim.time;
    sv += v;
    stt += sim.time * sim.time;
    stv += sim.time * v;
    ++n;
  }
  *v_end = body_velocity(sim, 1, 0);
  return -(n * stv - st * sv) / (n * stt - st * st);
}

}  // namespace

TEST(Contact, SlidingBlockDeceleratesAtMuG) {
  // g = 10 mm/ms^2, v0 = 2 m/s. Coulomb friction with mu = 0.5: a = mu g = 5 mm/ms^2 while
  // the block slides (it stops at t = 0.4 ms); the slope is fitted over [0.03, 0.33] ms,
  // after the block has settled on the base. Tolerance 3% (measured: 0.5%); the grid
  // contact sees the normal force through the block's rocking, which adds noise.
  double v_end = 0;
  const double a = sliding_deceleration("0.5", 0.03, 0.33, &v_end);
  EXPECT_NEAR(a, 5.0, 0.15);
  EXPECT_NEAR(v_end, 2.0 - 5.0 * 0.33, 0.1);
  // Frictionless: the block keeps its speed (deceleration near zero, |a| < 1% of mu g).
  const double a0 = sliding_deceleration("0.0", 0.03, 0.33, &v_end);
  EXPECT_NEAR(a0, 0.0, 0.05);
  EXPECT_NEAR(v_end, 2.0, 0.02);
}

TEST(Gimp, UniformMotionStaysStressFree) {
  // With GIMP weights that sum to one and gradients that sum to zero, a block moving
  // uniformly has a uniform grid velocity: no strain, no stress, x = x0 + v t (to rounding),
  // over 40 steps in which the particles cross cell edges and cell middles (stencil shifts).
  const std::string deck =
      "mpm3d *** gimp translation\n"
      "nbbo 1\nnbmp 64\nnmat 1\n"
      "spx 0 8\nspy 0 8\nspz 0 8\ndcel 1.0\nendt 100\ngimp\n"
      "mate 1 elas 1.0 100.0 0.25\n"
      "part bloc 1 1 1.0 0.5 2.2 2.7 3.1 4 4 4\n"
      "velo body 1 0.3 -0.2 0.1 endv\n"
      "endi\n";
  // Nodes lighter than the small-mass cut-off are skipped where velocities are formed, and
  // GIMP's quadratic tails give nodes tiny masses with sizeable gradients: without the
  // cut-off the weights are complete.
  mpm3d::Model m = mpm3d::read_deck_text(deck, "t.mpm");
  m.mass_cutoff = 0.0;
  mpm3d::Simulation sim(std::move(m));
  const std::vector<double> x0 = sim.model.particles.x;
  for (int s = 0; s < 40; ++s) sim.step();
  const auto& P = sim.model.particles;
  const double v[3] = {0.3, -0.2, 0.1};
  double smax = 0, dmax = 0, vmax = 0;
  for (int p = 0; p < P.np; ++p) {
    for (int i = 0; i < 6; ++i) smax = std::max(smax, std::fabs(P.sig[6 * size_t(p) + i]));
    for (int a = 0; a < 3; ++a) {
      dmax = std::max(dmax, std::fabs(P.x[3 * size_t(p) + a] - (x0[3 * size_t(p) + a] + v[a] * sim.time)));
      vmax = std::max(vmax, std::fabs(P.v[3 * size_t(p) + a] - v[a]));
    }
  }
  EXPECT_LT(smax, 1e-10);  // E = 100: strains below 1e-12
  EXPECT_LT(dmax, 1e-13);
  EXPECT_LT(vmax, 1e-13);
}
