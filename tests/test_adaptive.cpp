// The adaptive background grid, the patch statistics and the patch loops
// (issue 4: OpenMP parallel MPM as in MPM3DMP). Bit-for-bit checks across thread counts
// and languages with the adaptive grid on are in tests/threads.cmake and
// fortran_ref/tests.cmake; these tests check the rules and the hand-derived figures.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>
#include <cstring>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "input/data_in.hpp"
#include "input/ffi.hpp"
#include "mpm3d.hpp"
#include "test_util.hpp"
#include "core/patch_loops.hpp"

using testutil::RunResult;
using testutil::same_bits;
using testutil::TempDir;

namespace {

const std::string kExe = MPM3D_EXE;
const std::string kDecks = MPM3D_TEST_DECKS;
const std::string kInputs = std::string(MPM3D_TEST_DECKS) + "/../../inputs";

// Window rules after every step: inside the deck's box, boundary-condition faces at the
// box, lower end on the deck's patch lattice, and every particle inside the box inside it.
void check_window(const mpm3d::Simulation& s, const std::string& what) {
  const mpm3d::Grid& g = s.grid;
  for (int a = 0; a < 3; ++a) {
    EXPECT_GE(g.off[a], 0) << what;
    EXPECT_GE(g.nc[a], 1) << what;
    EXPECT_LE(g.off[a] + g.nc[a], g.deck_nc[a]) << what;
    EXPECT_EQ(g.off[a] % g.patch_cells, 0) << what;
    if (g.fix[2 * a] != 0) EXPECT_EQ(g.off[a], 0) << what << " axis " << a;
    if (g.fix[2 * a + 1] != 0) EXPECT_EQ(g.off[a] + g.nc[a], g.deck_nc[a]) << what << " axis " << a;
  }
  EXPECT_EQ(s.outside, 0) << what << ": particles outside the window";
}

}  // namespace

TEST(Adaptive, DeckKeywordAndRefusal) {
  const std::string head =
      "mpm3d *** adgr\nnbmp 8\nnbbo 1\nnmat 1\nspx 0 4\nspy 0 4\nspz 0 4\ndcel 1.0\nendt 0.05\n";
  const std::string tail = "mate\n1 elas 1.0 100.0 0.25\npart bloc 1 1 1.0 0.5 1 1 1 2 2 2\nendi\n";
  EXPECT_EQ(mpm3d::read_deck_text(head + tail, "a.mpm").regrid_every, 0);  // off by default
  EXPECT_EQ(mpm3d::read_deck_text(head + "AdGrid 7\n" + tail, "a.mpm").regrid_every, 7);  // first 4 chars
  EXPECT_EQ(mpm3d::read_deck_text(head + "adgr 0\n" + tail, "a.mpm").regrid_every, 0);
  try {
    mpm3d::read_deck_text(head + "adgr -1\n" + tail, "a.mpm");
    FAIL() << "adgr -1 accepted";
  } catch (const mpm3d::DeckError& e) {
    EXPECT_NE(std::string(e.what()).find("a.mpm:10:"), std::string::npos) << e.what();
  }
}

// Hand-checked patch statistics (tests/decks/patch_balance.mpm): 64 and 8 particles in two
// of 3 x 3 x 1 patches of 4^3 cells.
TEST(Adaptive, PatchStatisticsOfAHandCheckedDeck) {
  TempDir tmp;
  const std::string d = kDecks + "/patch_balance.mpm";
  for (const char* every : {"0", "10"}) {
    const std::string json = tmp / (std::string("s") + every + ".json");
    const RunResult r = testutil::run_program(
        kExe, {"--threads", "1", "--steps", "1", "--patch-cells", "4", "--regrid-every", every, "--out-dir",
               tmp.path(), "--summary", json, d},
        tmp.path(), tmp.path());
    ASSERT_EQ(r.code, 0) << r.err;
    const testutil::Json j = testutil::parse_json(testutil::read_file(json));
    const bool adaptive = std::string(every) == "10";
    EXPECT_EQ(j["patches"].num, adaptive ? 3.0 : 9.0);
    EXPECT_EQ(j["patches_empty"].num, adaptive ? 1.0 : 7.0);
    EXPECT_EQ(j["patch_max_particles"].num, 64.0);
    EXPECT_EQ(j["patch_mean_particles"].num, 36.0);
    EXPECT_EQ(j["patch_imbalance"].num, 64.0 / 36.0);
    EXPECT_EQ(j["regrid_every"].num, adaptive ? 10.0 : 0.0);
    EXPECT_EQ(j["regrids"].num, adaptive ? 1.0 : 0.0);
    EXPECT_EQ(j["regrids_forced"].num, 0.0);
    // Window: cells x 0..9 (particles in cells 0..8, margin 1), y and z 0..2.
    ASSERT_EQ(j["grid_window_cells"].arr.size(), 3u);
    EXPECT_EQ(j["grid_window_cells"].arr[0].num, adaptive ? 10.0 : 12.0);
    EXPECT_EQ(j["grid_window_cells"].arr[1].num, adaptive ? 3.0 : 12.0);
    EXPECT_EQ(j["grid_window_cells"].arr[2].num, adaptive ? 3.0 : 4.0);
    const std::string log = testutil::read_file(tmp / "patch_balance.out");
    const std::string line =
        "regrid step 0 window 0 10 0 3 0 3 cells 10 x 3 x 3, patches 3, empty 1, particles per patch max 64 "
        "mean 36.0, imbalance 1.778";
    EXPECT_EQ(log.find(line) != std::string::npos, adaptive) << log;
  }
}

// The window is on the deck's patch lattice, so every node sum keeps its operands and
// order: a regridded run is bit-identical to the run on the whole box, including a forced
// regrid (the block outruns its first window) and particles frozen on leaving the box.
TEST(Adaptive, RegriddedRunIsBitIdenticalToTheBoxRun) {
  mpm3d::Model m = mpm3d::read_deck(kDecks + "/rising_block.mpm");
  ASSERT_EQ(m.regrid_every, 50);
  mpm3d::Model m0 = m;
  m0.regrid_every = 0;
  mpm3d::Simulation a(std::move(m0)), b(std::move(m));
  for (int s = 0; s < 100; ++s) {
    a.step();
    b.step();
    ASSERT_EQ(a.outside, b.outside) << "step " << s;
  }
  // z(t) = z0 + g t^2 / 2 with g = 1e4: after 100 steps the block (z0 2.25..3.75) has risen
  // 9.28 mm, above the box top z = 10: every particle was frozen on leaving.
  const double t = 100 * a.model.dt;
  EXPECT_GT(2.25 + 0.5e4 * t * t, 10.0);
  EXPECT_EQ(a.outside, 64);
  EXPECT_EQ(b.regrids, 3);         // steps 0, 50 and the forced one
  EXPECT_EQ(b.regrids_forced, 1);  // margin of 1 cell at rest: outrun before step 50
  EXPECT_EQ(a.regrids, 0);
  const auto& A = a.model.particles;
  const auto& B = b.model.particles;
  EXPECT_TRUE(same_bits(A.x, B.x));
  EXPECT_TRUE(same_bits(A.v, B.v));
  EXPECT_TRUE(same_bits(A.sig, B.sig));
  EXPECT_TRUE(same_bits(A.vol, B.vol));
  EXPECT_TRUE(same_bits(A.ie, B.ie));
  EXPECT_EQ(a.kinetic, b.kinetic);
}

// Window rules on the Taylor bar (free x, y faces and top; symmetry floor) and on the
// multi-body deck (fixed x0 and z0, symmetry y0 and yn).
TEST(Adaptive, WindowRules) {
  for (const std::string deck : {kInputs + "/taylor/taylor_coarse.mpm", kInputs + "/impact/two_blocks.mpm"}) {
    mpm3d::Model m = mpm3d::read_deck(deck);
    m.regrid_every = 5;
    mpm3d::Simulation s(std::move(m));
    check_window(s, deck + " set-up");
    for (int k = 0; k < 20; ++k) {
      s.step();
      check_window(s, deck + " step " + std::to_string(k + 1));
    }
    EXPECT_EQ(s.regrids, 4);  // steps 0, 5, 10, 15
    if (deck.find("taylor") != std::string::npos) {
      // The bar (radius 3.8 mm = 7 cells around the box centre, 15 cells) takes cells
      // 0..26 of 30 along x and y: smaller than the box along the free faces.
      EXPECT_LT(s.grid.nc[0], s.grid.deck_nc[0]);
      EXPECT_LT(s.grid.nc[1], s.grid.deck_nc[1]);
      EXPECT_EQ(s.grid.off[2], 0);  // symmetry floor kept
    }
  }
}

TEST(Adaptive, BadOptions) {
  TempDir tmp;
  const std::string d = kDecks + "/patch_balance.mpm";
  for (const auto& args : std::vector<std::vector<std::string>>{{"--patch-cells", "0", d},
                                                                {"--regrid-every", "-1", d},
                                                                {"--regrid-every", "x", d},
                                                                {"--particle-order", "random", d}}) {
    const RunResult r = testutil::run_program(kExe, args, tmp.path(), tmp.path());
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(testutil::split_lines(r.err).size(), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("mpm3d: ", 0), 0u) << r.err;
  }
}

// The elastic benchmark twin has the Taylor scene's geometry, grid, time step and boundary
// conditions, and no EOS or plasticity.
TEST(Adaptive, ElasticBenchDeckIsTheTaylorGeometry) {
  const mpm3d::Model t = mpm3d::read_deck(kInputs + "/taylor/taylor_coarse.mpm");
  const mpm3d::Model e = mpm3d::read_deck(kInputs + "/taylor/taylor_coarse_elastic.mpm");
  EXPECT_TRUE(same_bits(t.particles.x, e.particles.x));
  EXPECT_TRUE(same_bits(t.particles.v, e.particles.v));
  EXPECT_TRUE(same_bits(t.particles.mass, e.particles.mass));
  EXPECT_EQ(t.dt, e.dt);  // dt from the same E, nu, rho
  EXPECT_EQ(t.dcell, e.dcell);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(t.box_lo[a], e.box_lo[a]);
    EXPECT_EQ(t.box_hi[a], e.box_hi[a]);
  }
  for (int f = 0; f < 6; ++f) EXPECT_EQ(t.fix[f], e.fix[f]);
  ASSERT_EQ(e.mats.size(), 1u);
  EXPECT_EQ(e.mats[0].type, MAT_ELAS);
  EXPECT_EQ(e.mats[0].eos_type, EOS_NONE);
  EXPECT_NE(t.mats[0].eos_type, EOS_NONE);
}

// The patch runs of the trilinear loops (thread_patches), hand-derived: patches of 100, 0,
// 30, 1, 100, 100, 100, 100, 30 and 40 particles (601). Two threads split at particle 300:
// the first list starting at or after it is patch 6 (at 331). Three threads split at 200
// and 400: patches 5 (231) and 7 (431). Every patch in exactly one run.
TEST(Adaptive, PatchRunsHoldEqualParticleShares) {
  std::vector<int> start = {0, 100, 100, 130, 131, 231, 331, 431, 531, 561, 601};
  StepContext c{};
  c.patch.npatch = int(start.size()) - 1;
  c.patch.patch_start = start.data();
  int lo, hi;
  mpm3d::thread_patches(&c, 0, 2, lo, hi);
  EXPECT_EQ(lo, 0);
  EXPECT_EQ(hi, 6);
  mpm3d::thread_patches(&c, 1, 2, lo, hi);
  EXPECT_EQ(lo, 6);
  EXPECT_EQ(hi, 10);
  const int expect3[4] = {0, 5, 7, 10};
  for (int t = 0; t < 3; ++t) {
    mpm3d::thread_patches(&c, t, 3, lo, hi);
    EXPECT_EQ(lo, expect3[t]) << "thread " << t;
    EXPECT_EQ(hi, expect3[t + 1]) << "thread " << t;
  }
  mpm3d::thread_patches(&c, 0, 1, lo, hi);
  EXPECT_EQ(lo, 0);
  EXPECT_EQ(hi, 10);
}

// The stress loop's chunks of the patch lists (for_list_chunks): patches of 100, 30 and 1
// particles (601 list entries), 3 threads. The chunks are 64 entries from the start of the
// lists whatever the patch ends (the tenth one 25 long), each done exactly once per loop.
TEST(Adaptive, ListChunksCoverEveryEntryOnce) {
#ifndef _OPENMP
  GTEST_SKIP() << "built without OpenMP";
#else
  const int threads_before = omp_get_max_threads();
  omp_set_num_threads(3);
  std::vector<int> start = {0, 100, 100, 130, 131, 231, 331, 431, 531, 561, 601};
  StepContext c{};
  c.patch.npatch = int(start.size()) - 1;
  c.patch.patch_start = start.data();
  ASSERT_EQ(mpm3d::kListChunk, 64);
  std::vector<int> hits(601);
  for (int rep = 0; rep < 50; ++rep) {
    std::fill(hits.begin(), hits.end(), 0);
    mpm3d::for_list_chunks(&c, [&](int first, int count) {
      EXPECT_EQ(first % 64, 0);
      EXPECT_EQ(count, first == 576 ? 25 : 64);
      for (int i = first; i < first + count; ++i) __atomic_add_fetch(&hits[size_t(i)], 1, __ATOMIC_RELAXED);
    });
    for (int i = 0; i < 601; ++i) ASSERT_EQ(hits[size_t(i)], 1) << "entry " << i << " in loop " << rep;
  }
  omp_set_num_threads(threads_before);
#endif
}

