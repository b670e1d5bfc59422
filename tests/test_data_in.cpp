// DataIn: the deck reader (particle generation, derived material constants, dt).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "input/data_in.hpp"
#include "input/ffi.hpp"

namespace {

std::string deck(const std::string& mate, const std::string& extra = "") {
  return "mpm3d *** reader test\n"
         "nbmp 12\nnbbo 1\nnmat 1\n"
         "spx 0 4\nspy 0 4\nspz 0 4\ndcel 1.0\ndtsc 0.5\nendt 1.0\n"
         "mate\n" + mate + "\n" + extra +
         "part bloc 1 1 2.0 0.5 1.0 1.5 2.0 2 3 2\n"
         "endi\n";
}

}  // namespace

// The message with which the reader refuses a deck text ("" when it accepts it).
static std::string refusal(const std::string& text, const std::string& name) {
  try {
    mpm3d::read_deck_text(text, name);
  } catch (const mpm3d::DeckError& e) {
    return e.what();
  }
  return "";
}

// A card with a number too many: the number is named on its line as the end of a card that
// is too long, not as an unknown keyword.
TEST(DataIn, NumberWhereAKeywordBelongsNamesTheLongCard) {
  const std::string what = refusal(deck("1 elas 2.0 200.0 0.25 7.0"), "long.mpm");
  EXPECT_NE(what.find("long.mpm:12: '7.0' is a number where a card's keyword was expected"), std::string::npos)
      << what;
  EXPECT_NE(what.find("more numbers than it takes"), std::string::npos) << what;
}

// A card a number short: named at its own line, with the number it lacks, not at the next
// card's line.
TEST(DataIn, ShortMaterialCardIsNamedAtItsLine) {
  const std::string what = refusal(deck("1 elas 2.0 200.0"), "short.mpm");
  EXPECT_NE(what.find("short.mpm:12: material 1's 'elas' card ends before Poisson's ratio ('part' on line 13"),
            std::string::npos)
      << what;
}

// gimp on a grid one cell thick along y: refused at the gimp card's line (13), not at the
// end of the deck, with what to change.
TEST(DataIn, GimpOnOneCellIsRefusedAtItsCard) {
  std::string text = deck("1 elas 2.0 200.0 0.25", "gimp\n");
  text.replace(text.find("spy 0 4"), 7, "spy 0 1");
  const std::string what = refusal(text, "thin.mpm");
  EXPECT_NE(what.find("thin.mpm:13: 'gimp' needs at least two cells along each axis"), std::string::npos) << what;
  EXPECT_NE(what.find("the grid has 1 cell along y; make spy span two cells or more"), std::string::npos) << what;
}

// Particles outside the grid are named before the first step (a warning of the deck).
TEST(DataIn, ParticlesOutsideTheGridAreNamed) {
  std::string text = deck("1 elas 2.0 200.0 0.25");
  text.replace(text.find("spy 0 4"), 7, "spy 0 2");  // y = 1.75, 2.25, 2.75: 8 particles beyond y = 2
  const mpm3d::Model m = mpm3d::read_deck_text(text, "out.mpm");
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_EQ(m.warnings[0],
            "8 particles lie outside the grid at the start (the first: particle 3): they stay frozen where they are "
            "for the whole run; widen the box (spx, spy, spz) to hold them");
}

TEST(DataIn, BlockParticlesZFastest) {
  mpm3d::Model m = mpm3d::read_deck_text(deck("1 elas 2.0 200.0 0.25"), "b.mpm");
  EXPECT_EQ(m.title, "*** reader test");
  const auto& P = m.particles;
  ASSERT_EQ(P.np, 12);
  // Particle (i, j, l), 0-based, is number l + 2 (j + 3 i) (z fastest, then y, then x),
  // at o + (index + 1/2) dp = (1.0 + 0.5 (i + 0.5), 1.5 + 0.5 (j + 0.5), 2.0 + 0.5 (l + 0.5)).
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 3; ++j)
      for (int l = 0; l < 2; ++l) {
        const int p = l + 2 * (j + 3 * i);
        EXPECT_EQ(P.x[3 * p + 0], 1.0 + 0.5 * (i + 0.5)) << p;
        EXPECT_EQ(P.x[3 * p + 1], 1.5 + 0.5 * (j + 0.5)) << p;
        EXPECT_EQ(P.x[3 * p + 2], 2.0 + 0.5 * (l + 0.5)) << p;
        // mass = density dp^3 = 2 * 0.125 = 0.25; volume dp^3 = 0.125 (exact in binary).
        EXPECT_EQ(P.mass[p], 0.25);
        EXPECT_EQ(P.vol[p], 0.125);
        EXPECT_EQ(P.mat[p], 0);
        EXPECT_EQ(P.body[p], 0);
      }
  ASSERT_EQ(m.bodies.size(), 1u);
  EXPECT_EQ(m.bodies[0].first, 0);
  EXPECT_EQ(m.bodies[0].count, 12);
}

TEST(DataIn, ElasticConstantsTimeStepAndCutoff) {
  mpm3d::Model m = mpm3d::read_deck_text(deck("1 elas 2.0 200.0 0.25"), "e.mpm");
  const MaterialParams& mp = m.mats[0];
  // G = E / (2 (1 + nu)) = 200 / 2.5 = 80; lambda = E nu / ((1 + nu)(1 - 2 nu)) = 50 / 0.625 = 80.
  EXPECT_EQ(mp.shear, 80.0);
  EXPECT_EQ(mp.lambda, 80.0);
  // c = sqrt((lambda + 2 G) / rho) = sqrt(240 / 2) = sqrt(120).
  EXPECT_DOUBLE_EQ(mp.wave_speed, std::sqrt(120.0));
  // dt = dtscale h / c = 0.5 / sqrt(120).
  EXPECT_NEAR(m.dt, 0.5 / std::sqrt(120.0), 1e-15);
  // cut-off = 1e-5 * mean density * h^3 = 2e-5.
  EXPECT_NEAR(m.mass_cutoff, 2.0e-5, 1e-20);
  EXPECT_EQ(m.scheme, SCHEME_MUSL);  // MUSL when none is switched on
}

TEST(DataIn, Pla2PlasticModulusFromTangentModulus) {
  // Ep = E Et / (E - Et) = 200 * 50 / 150 = 66.666...
  mpm3d::Model m = mpm3d::read_deck_text(deck("1 pla2 2.0 200.0 0.25 0.1 50.0"), "p.mpm");
  EXPECT_EQ(m.mats[0].type, MAT_PLA2);
  EXPECT_EQ(m.mats[0].yield0, 0.1);
  EXPECT_NEAR(m.mats[0].hardening, 200.0 / 3.0, 1e-13);
}

TEST(DataIn, EosInitialEnergyPerInitialVolume) {
  // seos 1 2 c0 s gamma E0: E0 = 3 per unit initial volume; each particle's volume is
  // mass / rho0 = 0.25 / 2 = 0.125, so its internal energy is 0.375.
  mpm3d::Model m = mpm3d::read_deck_text(
      deck("1 sjc 2.0 200.0 0.25 0.1 0.2 1.0 0.0 1.0", "seos 1 2 3.0 1.5 1.0 3.0\n"), "s.mpm");
  EXPECT_EQ(m.mats[0].eos_type, EOS_MIE_GRUNEISEN);
  EXPECT_EQ(m.mats[0].eos[0], 3.0);
  EXPECT_EQ(m.mats[0].eos[1], 1.5);
  EXPECT_EQ(m.mats[0].eos[2], 1.0);
  for (int p = 0; p < m.particles.np; ++p) EXPECT_EQ(m.particles.ie[p], 0.375);
}

TEST(DataIn, VelocitiesByBodyAndNode) {
  mpm3d::Model m = mpm3d::read_deck_text(
      "nbmp 3 nbbo 2 nmat 1 spx 0 4 spy 0 4 spz 0 4 dcel 1 endt 1\n"
      "mate 1 elas 1 100 0.25\n"
      "part poin 1 2\n 1 1 0.5 1.0 1.0 1.0\n 2 1 0.5 2.0 1.0 1.0\n"
      "part bloc 1 1 1.0 0.5 3 3 3 1 1 1\n"
      "velo body 1 1.0 2.0 3.0 node 2 -4 -5 -6 body 2 7 8 9 endv\n"
      "endi\n",
      "v.mpm");
  const auto& v = m.particles.v;
  const double expect[9] = {1, 2, 3, -4, -5, -6, 7, 8, 9};
  for (int i = 0; i < 9; ++i) EXPECT_EQ(v[i], expect[i]) << i;
  EXPECT_EQ(m.particles.vol[0], 0.5);  // point particle volume = mass / rho0
  EXPECT_EQ(m.particles.body[2], 1);
}

TEST(DataIn, BaseNameIsTheFileNameUpToItsFirstDot) {
  mpm3d::Model m = mpm3d::read_deck_text(deck("1 elas 2.0 200.0 0.25"), "/some/dir/Taylor.v2.mpm");
  EXPECT_EQ(m.base_name, "Taylor");
}

TEST(DataIn, InputErrorsNameTheLine) {
  struct Case {
    std::string text;
    int line;
    const char* word;
  } cases[] = {
      {"nbmp 1\nfoob 3\n", 2, "foob"},
      {"nbmp 1\nnmat 1\nmate\n  2 elas 1 100 0.25\n", 4, "out of range"},
      {"nbmp 1\ndtsc 3.0\n", 2, "time-step scale"},
      {"nbmp x1\n", 1, "x1"},
      {"nbmp 1\nnmat 1\nmate 1 elas 1 100 0.5\n", 3, "Poisson"},
  };
  for (const auto& c : cases) {
    try {
      mpm3d::read_deck_text(c.text, "err.mpm");
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const mpm3d::DeckError& e) {
      EXPECT_EQ(e.line(), c.line) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.word), std::string::npos) << e.what();
    }
  }
}

// The current MPM3D-F90's cards: a neoh material (F - I per particle, volume from det F),
// the vsin velocity field, 'part' loads, and the displacement variables (initial positions
// kept).
TEST(DataIn, CurrentVersionNeoHookeanVsinPartLoadDisplacements) {
  mpm3d::Model m = mpm3d::read_deck_text(
      "nbmp 12 nbbo 1 nmat 1 spx 0 4 spy 0 4 spz 0 4 dcel 1 endt 1\n"
      "outr disx\ncurv disy 3\n"
      "mate 1 neoh 1100 17e6 0.3\n"
      "part bloc 1 1 2.0 0.5 1.0 1.5 2.0 2 3 2\n"
      "velo vsin 2.0 endv\n"
      "load part 3 1 2 3 endl\n"
      "endi\n",
      "n.mpm");
  const auto& P = m.particles;
  ASSERT_EQ(m.mats.size(), 1u);
  EXPECT_EQ(m.mats[0].type, MAT_NEOH);
  EXPECT_TRUE(m.uvf);
  // A deck of the current version: its block order, x fastest (particle i + 2 (j + 3 l)),
  // and its time step.
  EXPECT_TRUE(m.current_version);
  EXPECT_TRUE(m.dt_per_step);
  for (int l = 0; l < 2; ++l)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 2; ++i) {
        const int p = i + 2 * (j + 3 * l);
        EXPECT_EQ(P.x[3 * p + 0], 1.0 + 0.5 * (i + 0.5)) << p;
        EXPECT_EQ(P.x[3 * p + 1], 1.5 + 0.5 * (j + 0.5)) << p;
        EXPECT_EQ(P.x[3 * p + 2], 2.0 + 0.5 * (l + 0.5)) << p;
      }
  ASSERT_EQ(P.defgrad.size(), 9u * 12u);
  for (double h : P.defgrad) EXPECT_EQ(h, 0.0);
  ASSERT_EQ(P.x0.size(), P.x.size());
  for (size_t i = 0; i < P.x.size(); ++i) EXPECT_EQ(P.x0[i], P.x[i]);
  for (int p = 0; p < P.np; ++p) {
    // pi as the original's single-precision constant
    EXPECT_EQ(P.v[3 * p], 2.0 * std::sin((double(3.1415926535f) * P.x[3 * p + 1]) / 6.0)) << p;
    EXPECT_NE(P.v[3 * p], 0.0);
    EXPECT_EQ(P.v[3 * p + 1], 0.0);
    EXPECT_EQ(P.v[3 * p + 2], 0.0);
  }
  ASSERT_EQ(P.fext.size(), 36u);
  EXPECT_EQ(P.fext[6], 1.0);  // particle 3
  EXPECT_EQ(P.fext[7], 2.0);
  EXPECT_EQ(P.fext[8], 3.0);
  EXPECT_EQ(P.fext[9], 0.0);
  EXPECT_TRUE(mpm3d::is_output_variable("stsx"));
  // UVFp alone: the volume update of any model, no deformation gradient carried.
  mpm3d::Model u = mpm3d::read_deck_text(deck("1 elas 2.0 200.0 0.25", "UVFp\n"), "u.mpm");
  EXPECT_TRUE(u.uvf);
  EXPECT_TRUE(u.current_version);
  EXPECT_TRUE(u.particles.defgrad.empty());
  EXPECT_TRUE(u.particles.x0.empty());
  const mpm3d::Model book = mpm3d::read_deck_text(deck("1 elas 2.0 200.0 0.25"), "e.mpm");
  EXPECT_FALSE(book.uvf);
  EXPECT_FALSE(book.current_version);
  EXPECT_FALSE(book.dt_per_step);
  // A title is free text: a keyword in it does not make a current deck.
  EXPECT_FALSE(mpm3d::read_deck_text("mpm3d neoh Damp test\n" + deck("1 elas 2.0 200.0 0.25"), "t.mpm").current_version);
}

// Decks of the current version have artificial bulk viscosity on by default (1.5, 0.06), as
// the current program; a deck's own 'bulk' keeps its coefficients; book decks have none.
TEST(DataIn, CurrentDecksHaveDefaultBulkViscosity) {
  const mpm3d::Model cur = mpm3d::read_deck_text(deck("1 neoh 1100 17e6 0.3"), "c.mpm");
  EXPECT_TRUE(cur.has_bulk);
  EXPECT_EQ(cur.bulk_q1, 1.5);
  EXPECT_EQ(cur.bulk_q2, 0.06);
  EXPECT_EQ(cur.particles.qv.size(), 12u);
  const mpm3d::Model own = mpm3d::read_deck_text(deck("1 neoh 1100 17e6 0.3", "bulk 1.0 0.5\n"), "o.mpm");
  EXPECT_EQ(own.bulk_q1, 1.0);
  EXPECT_EQ(own.bulk_q2, 0.5);
  EXPECT_FALSE(mpm3d::read_deck_text(deck("1 elas 2.0 200.0 0.25"), "b.mpm").has_bulk);
}

// The current version's generators and built-in velocity fields: blod (a block, x fastest,
// without a circular hole), cicl (a disc one particle thick), ksin and nuli.
TEST(DataIn, CurrentVersionGeneratorsAndVelocityFields) {
  mpm3d::Model m = mpm3d::read_deck_text(
      "nbmp 84 nbbo 2 nmat 1 spx -2 6 spy -2 6 spz -2 6 dcel 1 endt 1\n"
      "mate 1 neoh 1000 1e5 0.3\n"
      "part blod 1 1 1000 0.5 0 0 0 8 8 1 2.0 2.0 0.25 2\n"
      "part cicl 1 1 1000 0.5 3.0 3.0 1.0 3\n"
      "endi\n",
      "g.mpm");
  const auto& P = m.particles;
  // blod: 64 lattice points (0.25 + 0.5 i, 0.25 + 0.5 j), those closer than 1.0 to
  // (2, 2) left out: the 12 with |(i, j) - (3.5, 3.5)| < 2 in half-spacings.
  ASSERT_EQ(m.bodies.size(), 2u);
  EXPECT_EQ(m.bodies[0].count, 52);
  for (int p = 0; p < m.bodies[0].count; ++p) {
    const double dx = P.x[3 * p] - 2.0, dy = P.x[3 * p + 1] - 2.0;
    EXPECT_GE(dx * dx + dy * dy, 1.0) << p;
    EXPECT_EQ(P.x[3 * p + 2], 0.25);
  }
  EXPECT_EQ(P.x[0], 0.25);  // x fastest
  EXPECT_EQ(P.x[3], 0.75);
  EXPECT_EQ(P.x[1], 0.25);
  // cicl: the 36 points (3 + 0.5 (i + 1/2), 3 + 0.5 (j + 1/2)), i, j in -3..2, closer than
  // 1.5 to (3, 3): 36 minus the 4 corners... of the 6 x 6, those with (i+1/2)^2 + (j+1/2)^2 < 9.
  int disc = 0;
  for (int i = -3; i < 3; ++i)
    for (int j = -3; j < 3; ++j) disc += (i + 0.5) * (i + 0.5) + (j + 0.5) * (j + 0.5) < 9.0;
  EXPECT_EQ(m.bodies[1].count, disc);
  EXPECT_EQ(P.np, 52 + disc);
  for (int p = m.bodies[1].first; p < P.np; ++p) EXPECT_EQ(P.x[3 * p + 2], 1.25) << p;

  // ksin: rows of 320, v_x = v0 sin(pi (m - 1/2) dc), dc = 0.003125 (single precision).
  mpm3d::Model k = mpm3d::read_deck_text(
      "nbmp 1280 nbbo 1 nmat 1 spx 0 2 spy 0 1 spz 0 1 dcel 0.1 endt 1\n"
      "mate 1 elas 1000 1e5 0.3\npart bloc 1 1 1000 0.003125 0 0 0 320 4 1\n"
      "velo ksin 2.0 1 endv\nendi\n",
      "k.mpm");
  for (int p : {0, 159, 319, 320, 1279}) {
    const int mm = p % 320 + 1;
    const double dc = double(0.003125f);
    EXPECT_EQ(k.particles.v[3 * p], 2.0 * std::sin(double(3.1415926535f) * (double(mm - 1) * dc + dc / 2.0))) << p;
  }
  EXPECT_NEAR(k.particles.v[3 * 159], 2.0, 1e-4);  // the middle of a row: sin(pi/2)
  // nuli: rows of 384; the mode shape of a free-free beam is symmetric about its middle (to
  // 2.4e-4 with the original's rounded eigenvalue q = 78.83).
  mpm3d::Model u = mpm3d::read_deck_text(
      "nbmp 49152 nbbo 1 nmat 1 spx 0 0.1 spy 0 0.03 spz 0 0.01 dcel 0.01 endt 1\n"
      "mate 1 elas 1845 318e9 0.054\npart bloc 1 1 1845 0.00015625 0 0 0 384 128 1\n"
      "velo nuli 0.001 endv\nendi\n",
      "u.mpm");
  const auto& uv = u.particles.v;
  EXPECT_NE(uv[3 * 0 + 1], 0.0);
  EXPECT_NEAR(uv[3 * 0 + 1], uv[3 * 383 + 1], 1e-3 * std::fabs(uv[3 * 0 + 1]));
  // At the beam's end the mode is -2 c2 of its amplitude A = y0 / (2 c2): v = -y0 W, with
  // W = q^2 sqrt(E h^2 / (12 rho (1 - nu^2))) (the first particle sits dc/2 from the end).
  const double w = 78.83 * 78.83 * std::sqrt(318e9 * 0.01 * 0.01 / (12.0 * 1845.0 * (1.0 - 0.054 * 0.054)));
  EXPECT_NEAR(uv[3 * 0 + 1], -0.001 * w, 1e-2 * 0.001 * w);  // 0.6 %: the slope over dc/2
  EXPECT_EQ(uv[3 * 384 + 1], uv[1]);  // every row the same
  EXPECT_EQ(uv[0], 0.0);
}

// TLmp: what the current version's total Lagrangian MPM does not have is refused, naming
// both keywords; a neoh deck with TLmp carries the reference positions and V0 P.
TEST(DataIn, TotalLagrangianCombinationsAreRefused) {
  const mpm3d::Model tl = mpm3d::read_deck_text(deck("1 neoh 1100 17e6 0.3", "TLmp\n"), "tl.mpm");
  EXPECT_TRUE(tl.tl);
  EXPECT_EQ(tl.particles.pk1.size(), 9u * 12u);
  ASSERT_EQ(tl.particles.x0.size(), tl.particles.x.size());
  struct Case {
    std::string mate, extra;
    const char* word;
  } cases[] = {{"1 elas 2.0 200.0 0.25", "TLmp\n", "'TLmp' with a elas material"},
               {"1 neoh 1100 17e6 0.3", "TLmp\ngimp\n", "'TLmp' with 'gimp'"},
               {"1 neoh 1100 17e6 0.3", "TLmp\nbimp\n", "'TLmp' with 'bimp'"},
               {"1 neoh 1100 17e6 0.3", "gimp\nbimp\n", "'gimp' with 'bimp'"},
               {"1 neoh 1100 17e6 0.3", "TLmp\nadgr 5\n", "'TLmp' with 'adgr'"}};
  for (const auto& c : cases) {
    try {
      mpm3d::read_deck_text(deck(c.mate, c.extra), "tlr.mpm");
      ADD_FAILURE() << "accepted: " << c.extra;
    } catch (const mpm3d::DeckError& e) {
      EXPECT_NE(std::string(e.what()).find(c.word), std::string::npos) << e.what();
    }
  }
}

// An output variable asked for twice is written once, with a warning (an HDF5 frame cannot
// hold two datasets of one name: the series failed on such a deck).
TEST(DataIn, RepeatedOutrIsWrittenOnce) {
  const mpm3d::Model m = mpm3d::read_deck_text(deck("1 elas 2.0 200.0 0.25", "outr pres\noutr seqv\noutr pres\n"), "r.mpm");
  ASSERT_EQ(m.anim_vars.size(), 2u);
  EXPECT_EQ(m.anim_vars[0], "pres");
  EXPECT_EQ(m.anim_vars[1], "seqv");
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("'outr pres' given again"), std::string::npos) << m.warnings[0];
}

// sgmp: smoothed-gradient MPM through the cell centres, two fixed node layers, also total
// Lagrangian (TLmp); what it does not combine with is refused naming both keywords.
TEST(DataIn, SmoothedGradientDeckAndItsRefusals) {
  const mpm3d::Model sg = mpm3d::read_deck_text(deck("1 neoh 1100 17e6 0.3", "sgmp\n"), "s.mpm");
  EXPECT_TRUE(sg.sg);
  EXPECT_EQ(sg.shape(), 0);
  EXPECT_EQ(sg.fix_layers(), 2);
  const mpm3d::Model sgtl = mpm3d::read_deck_text(deck("1 neoh 1100 17e6 0.3", "TLmp\nsgmp\n"), "st.mpm");
  EXPECT_TRUE(sgtl.sg);
  EXPECT_TRUE(sgtl.tl);
  struct Case {
    const char* extra;
    const char* word;
  } cases[] = {{"sgmp\ngimp\n", "'sgmp' with 'gimp'"},
               {"bimp\nsgmp\n", "'sgmp' with 'bimp'"},
               {"sgmp\nadgr 5\n", "'sgmp' with 'adgr'"}};
  for (const auto& c : cases) {
    try {
      mpm3d::read_deck_text(deck("1 neoh 1100 17e6 0.3", c.extra), "sr.mpm");
      ADD_FAILURE() << "accepted: " << c.extra;
    } catch (const mpm3d::DeckError& e) {
      EXPECT_NE(std::string(e.what()).find(c.word), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find("unknown keyword"), std::string::npos) << e.what();
    }
  }
}

// bimp: the current version's B-spline shape functions (shape 2) and, with the 27-node
// stencils of a current deck, two node layers held on the fixed faces; a book deck with
// gimp keeps one layer.
TEST(DataIn, BsplineDeckSetsShapeAndTwoFixedLayers) {
  const mpm3d::Model b = mpm3d::read_deck_text(deck("1 neoh 1100 17e6 0.3", "bimp\n"), "b.mpm");
  EXPECT_TRUE(b.bspline);
  EXPECT_EQ(b.shape(), 2);
  EXPECT_EQ(b.fix_layers(), 2);
  EXPECT_TRUE(b.particles.psize.empty());
  const mpm3d::Model g = mpm3d::read_deck_text(deck("1 neoh 1100 17e6 0.3", "gimp\n"), "g.mpm");
  EXPECT_EQ(g.shape(), 1);
  EXPECT_EQ(g.fix_layers(), 2);
  const mpm3d::Model book = mpm3d::read_deck_text(deck("1 elas 2.0 200.0 0.25", "gimp\n"), "k.mpm");
  EXPECT_EQ(book.shape(), 1);
  EXPECT_EQ(book.fix_layers(), 1);
  const mpm3d::Model lin = mpm3d::read_deck_text(deck("1 neoh 1100 17e6 0.3"), "l.mpm");
  EXPECT_EQ(lin.shape(), 0);
  EXPECT_EQ(lin.fix_layers(), 1);
}

// GIMP's particle half-size: a current-version deck (neoh) gives every particle a quarter
// cell, as the current program does whatever the particles' size; a book deck takes half
// the block's spacing (here 0.4 in cells of 1) or half the cube root of a poin volume.
TEST(DataIn, GimpParticleSizeFollowsTheDecksVersion) {
  auto gimp_deck = [](const std::string& mate) {
    return "mpm3d *** gimp size\nnbmp 13\nnbbo 2\nnmat 1\n"
           "spx 0 4\nspy 0 4\nspz 0 4\ndcel 1.0\ndtsc 0.5\nendt 1.0\ngimp\n"
           "mate\n" + mate + "\n"
           "part bloc 1 1 2.0 0.4 1.0 1.5 2.0 2 3 2\n"
           "part poin 1 1\n13 1 0.128 2.5 2.5 2.5\n"
           "endi\n";
  };
  const mpm3d::Model cur = mpm3d::read_deck_text(gimp_deck("1 neoh 2.0 200.0 0.25"), "c.mpm");
  ASSERT_TRUE(cur.current_version);
  ASSERT_EQ(cur.particles.psize.size(), 13u);
  for (int p = 0; p < 13; ++p) EXPECT_EQ(cur.particles.psize[p], 0.25) << p;
  const mpm3d::Model book = mpm3d::read_deck_text(gimp_deck("1 elas 2.0 200.0 0.25"), "k.mpm");
  ASSERT_FALSE(book.current_version);
  ASSERT_EQ(book.particles.psize.size(), 13u);
  for (int p = 0; p < 12; ++p) EXPECT_DOUBLE_EQ(book.particles.psize[p], 0.2) << p;
  EXPECT_DOUBLE_EQ(book.particles.psize[12], 0.5 * std::cbrt(0.128 / 2.0));  // 0.2
}

// The current version's null is a viscous fluid: density, bulk modulus, viscosity (wave
// speed sqrt(K / rho)); with the weakly compressible EOS (seos type 4, c0 only). A book
// deck's null keeps its card (density, wave speed).
TEST(DataIn, CurrentNullFluidAndWeaklyCompressibleEos) {
  const mpm3d::Model cur = mpm3d::read_deck_text(deck("1 null 1000 2.25e9 0.001", "seos 1 4 1500\nsgmp\n"), "w.mpm");
  const MaterialParams& w = cur.mats[0];
  EXPECT_EQ(w.type, MAT_NULL);
  EXPECT_EQ(w.bulk_modulus, 2.25e9);
  EXPECT_EQ(w.viscosity, 0.001);
  EXPECT_EQ(w.wave_speed, std::sqrt(2.25e9 / 1000.0));
  EXPECT_EQ(w.eos_type, EOS_WEAK);
  EXPECT_EQ(w.eos[0], 1500.0);
  const mpm3d::Model book = mpm3d::read_deck_text(deck("1 null 1000 1500", "seos 1 3 1 1 4 1 0.3 0\n"), "b.mpm");
  EXPECT_EQ(book.mats[0].wave_speed, 1500.0);
  EXPECT_EQ(book.mats[0].viscosity, 0.0);
  for (const char* bad : {"seos 1 4 0\nsgmp\n", "seos 1 4 -3\nsgmp\n"}) {
    try {
      mpm3d::read_deck_text(deck("1 null 1000 2.25e9 0.001", bad), "x.mpm");
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const mpm3d::DeckError& e) {
      EXPECT_NE(std::string(e.what()).find("c0 must be positive"), std::string::npos) << e.what();
    }
  }
}
