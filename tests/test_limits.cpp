// Deck limits and holes closed by the fuzzing work (docs/RELIABILITY.md): every error names
// the deck and the line; no deck allocates beyond the memory budget or loops for long.
#include <gtest/gtest.h>

#include <string>

#include "input/data_in.hpp"
#include "input/ffi.hpp"

namespace {

// Line 2 nbmp, 5-7 box, 8 dcel, 11 the particle card.
std::string deck(const std::string& nbmp, const std::string& box, const std::string& part,
                 const std::string& dcel = "1.0") {
  return "mpm3d *** limits\n"
         "nbmp " + nbmp + "\nnbbo 1\nnmat 1\n" + box + "\ndcel " + dcel +
         "\nendt 1.0\nmate 1 elas 1.0 100.0 0.25\n" + part + "\nendi\n";
}
const std::string kBox = "spx 0 4\nspy 0 4\nspz 0 4";

// The DeckError's line, or -1 when the deck was read.
int error_line(const std::string& text, std::string* what = nullptr) {
  try {
    mpm3d::read_deck_text(text, "l.mpm");
  } catch (const mpm3d::DeckError& e) {
    if (what) *what = e.what();
    return e.line();
  }
  return -1;
}

}  // namespace

TEST(Limits, ParticleCountBeyondTheMemoryBudgetIsRefusedAtNbmp) {
  mpm3d::set_deck_memory_budget(1.0e6);  // 1e6 bytes: 3906 particles of 256 bytes
  std::string what;
  EXPECT_EQ(error_line(deck("4000", kBox, "part bloc 1 1 1.0 0.25 0 0 0 10 20 20"), &what), 2);
  EXPECT_NE(what.find("l.mpm:2: 'nbmp' = 4000 particles need about 1 MB"), std::string::npos) << what;
  EXPECT_EQ(error_line(deck("3000", kBox, "part bloc 1 1 1.0 0.25 0 0 0 10 15 20")), -1);
  mpm3d::set_deck_memory_budget(0.0);
  EXPECT_GT(mpm3d::deck_memory_budget(), 1.0e8);  // the machine's memory
  EXPECT_EQ(error_line(deck("1000000000000", kBox, "")), 2);  // above the hard limit 2e8
}

TEST(Limits, GridBeyondTheNodeLimitOrShorterThanHalfACellIsRefused) {
  std::string what;
  // (1e6 + 1)^3 nodes: refused at the last card that set the box or the cell size (dcel, line 8).
  EXPECT_EQ(error_line(deck("8", "spx 0 1e6\nspy 0 1e6\nspz 0 1e6", "part bloc 1 1 1.0 0.5 1 1 1 2 2 2"), &what), 8);
  EXPECT_NE(what.find("nodes exceeds the limit"), std::string::npos) << what;
  EXPECT_EQ(error_line(deck("8", kBox, "part bloc 1 1 1.0 0.5 1 1 1 2 2 2", "1e-300"), &what), 8);
  EXPECT_NE(what.find("more than 1000000 cells"), std::string::npos) << what;
  EXPECT_EQ(error_line(deck("8", kBox, "part bloc 1 1 1.0 0.5 1 1 1 2 2 2", "9"), &what), 8);
  EXPECT_NE(what.find("shorter than half a cell"), std::string::npos) << what;
}

TEST(Limits, GridCardNeedsMaximumAboveMinimum) {
  std::string what;
  EXPECT_EQ(error_line(deck("8", "grid 0 4 0 4 4 0\n\n", "part bloc 1 1 1.0 0.5 1 1 1 2 2 2"), &what), 5);
  EXPECT_NE(what.find("'grid': maximum must exceed minimum along z"), std::string::npos) << what;
}

TEST(Limits, LoadOnAParticleNotYetDefinedIsRefused) {
  std::string what;
  EXPECT_EQ(error_line(deck("8", kBox, "load\nnode 3 1 0 0\nendl\npart bloc 1 1 1.0 0.5 1 1 1 2 2 2"), &what), 12);
  EXPECT_NE(what.find("load on particle 3 before it is defined"), std::string::npos) << what;
}

TEST(Limits, OversizedParticleCardsAreRefusedBeforeGenerating) {
  // Each would loop over ~1e12 lattice points before the count check of each particle.
  EXPECT_EQ(error_line(deck("8", kBox, "part sphe 1 1 1.0 0.5 2 2 2 10000")), 11);
  EXPECT_EQ(error_line(deck("8", kBox, "part cyli 1 1 1.0 1e-5 2 2 0 1 3")), 11);
  EXPECT_EQ(error_line(deck("8", kBox, "part cyli 1 1 1.0 0.5 2 2 0 1 0.1")), 11);  // no layer
  // Spacing whose cube underflows or overflows.
  EXPECT_EQ(error_line(deck("8", kBox, "part bloc 1 1 1.0 1e-200 1 1 1 2 2 2")), 11);
  EXPECT_EQ(error_line(deck("8", kBox, "part bloc 1 1 1.0 1e200 1 1 1 2 2 2")), 11);
}

TEST(Limits, WaveSpeedMustBeFinite) {
  // c = sqrt((lambda + 2 G) / rho) overflows: the time step would be 0.
  std::string d = deck("8", kBox, "part bloc 1 1 1.0 0.5 1 1 1 2 2 2");
  d.replace(d.find("1 elas 1.0 100.0"), 16, "1 elas 1e-300 1e308");
  EXPECT_EQ(error_line(d), 10);
}

TEST(Limits, ParticleArraysGrowAcrossCardsAndKeepLoads) {
  // 3000 particles in two cards (the arrays grow 1024 -> 2048 -> 3000), a load on particle 1
  // between them: every array ends at nbmp entries and the load stays on particle 1.
  const std::string text =
      "mpm3d *** growth\nnbmp 3000\nnbbo 2\nnmat 1\nspx 0 20\nspy 0 20\nspz 0 20\ndcel 1.0\nendt 1.0\n"
      "mate 1 elas 1.0 100.0 0.25\n"
      "part bloc 1 1 1.0 0.5 0 0 0 10 10 10\n"
      "load\nnode 1 1.0 2.0 3.0\nendl\n"
      "part bloc 1 1 1.0 0.5 6 0 0 10 10 20\n"
      "endi\n";
  mpm3d::Model m = mpm3d::read_deck_text(text, "g.mpm");
  const auto& P = m.particles;
  ASSERT_EQ(P.np, 3000);
  EXPECT_EQ(P.x.size(), 9000u);
  EXPECT_EQ(P.sig.size(), 18000u);
  EXPECT_EQ(P.mass.size(), 3000u);
  ASSERT_EQ(P.fext.size(), 9000u);
  EXPECT_EQ(P.fext[0], 1.0);
  EXPECT_EQ(P.fext[2], 3.0);
  EXPECT_EQ(P.fext[3], 0.0);
  EXPECT_EQ(P.fext[8999], 0.0);
  // Last particle: second block (i, j, l) = (9, 9, 19) at 6 + 9.5 * 0.5, 9.5 * 0.5, 19.5 * 0.5.
  EXPECT_EQ(P.x[8997], 10.75);
  EXPECT_EQ(P.x[8998], 4.75);
  EXPECT_EQ(P.x[8999], 9.75);
  EXPECT_EQ(P.body[2999], 1);
  EXPECT_EQ(P.mass[2999], 0.125);
}
