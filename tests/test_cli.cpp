// The mpm3d program: bad input is refused with one line on stderr naming the file, the
// line and the problem, with a non-zero exit code and no output files; a good run writes
// the documented summary JSON and HDF5 state (docs/DESIGN.md section 6).
#include <filesystem>
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "io/analysis.hpp"
#include "input/data_in.hpp"
#include "mpm3d.hpp"
#include "test_util.hpp"

using testutil::RunResult;
using testutil::TempDir;

namespace {

const std::string kExe = MPM3D_EXE;
const std::string kDecks = MPM3D_TEST_DECKS;

// A valid deck; each bad-input test changes one thing. Line numbers are given in the
// comments on the right because the tests refer to them.
const char* kGood =
    "mpm3d *** cli test\n"        // 1
    "nbmp 8\n"                    // 2
    "nbbo 1\n"                    // 3
    "nmat 1\n"                    // 4
    "spx 0 4\n"                   // 5
    "spy 0 4\n"                   // 6
    "spz 0 4\n"                   // 7
    "dcel 1.0\n"                  // 8
    "endt 0.05\n"                 // 9
    "mate\n"                      // 10
    "1 elas 1.0 100.0 0.25\n"     // 11
    "part bloc 1 1 1.0 0.5 1 1 1 2 2 2\n"  // 12
    "endi\n";                     // 13

std::string replace_line(const std::string& deck, int line, const std::string& text) {
  auto lines = testutil::split_lines(deck);
  lines.at(size_t(line - 1)) = text;
  std::string r;
  for (const auto& l : lines) r += l + "\n";
  return r;
}

class Cli : public ::testing::Test {
 protected:
  TempDir tmp;
  std::string decks, out, scratch;
  void SetUp() override {
    decks = tmp / "decks";
    out = tmp / "out";
    scratch = tmp / "scratch";
    for (const auto& d : {decks, out, scratch}) testutil::fs::create_directory(d);
  }
  std::string deck_file(const std::string& name, const std::string& text) {
    const std::string p = decks + "/" + name;
    testutil::write_file(p, text);
    return p;
  }
  // Runs with the output directory as both working directory and --out-dir.
  RunResult run(const std::vector<std::string>& args) {
    return testutil::run_program(kExe, args, out, scratch);
  }
  // Expects failure with exactly one stderr line starting "mpm3d: <prefix>" and holding
  // every word, and an untouched (empty) output directory.
  void expect_refused(const RunResult& r, const std::string& prefix, const std::vector<std::string>& words) {
    EXPECT_NE(r.code, 0);
    EXPECT_GT(r.code, 0) << "did not exit normally (crash?)";
    const auto lines = testutil::split_lines(r.err);
    ASSERT_EQ(lines.size(), 1u) << "stderr:\n" << r.err;
    EXPECT_EQ(r.err.back(), '\n');
    const std::string& l = lines[0];
    EXPECT_EQ(l.rfind("mpm3d: " + prefix, 0), 0u) << l;
    for (const auto& w : words) EXPECT_NE(l.find(w), std::string::npos) << "'" << w << "' not in: " << l;
    EXPECT_TRUE(testutil::list_dir(out).empty()) << "output files were written";
  }
};

}  // namespace

TEST_F(Cli, GoodDeckRuns) {
  const std::string d = deck_file("good.mpm", kGood);
  const RunResult r = run({"--quiet", "--out-dir", out, d});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  // Legacy files named after the deck (docs/DESIGN.md section 6).
  for (const char* f : {"good.out", "good_curv.dat", "EnergyPlot.dat", "MomentumPlot.dat"})
    EXPECT_TRUE(testutil::fs::exists(out + "/" + f)) << f;
}

TEST_F(Cli, UnknownKeyword) {
  const std::string d = deck_file("unknown.mpm", replace_line(kGood, 8, "dcel 1.0 foob 3"));
  expect_refused(run({"--quiet", "--out-dir", out, d}), d + ":8: ", {"unknown keyword", "foob"});
}

TEST_F(Cli, NonNumericValue) {
  const std::string d = deck_file("nonnum.mpm", replace_line(kGood, 11, "1 elas 1.0 1O0.0 0.25"));
  expect_refused(run({"--quiet", "--out-dir", out, d}), d + ":11: ", {"1O0.0", "Non Numeric"});
}

TEST_F(Cli, MalformedNumber) {
  const std::string d = deck_file("badnum.mpm", replace_line(kGood, 5, "spx 0 4.0.0"));
  expect_refused(run({"--quiet", "--out-dir", out, d}), d + ":5: ", {"4.0.0"});
}

TEST_F(Cli, TooManyParticles) {
  // 2 x 2 x 2 = 8 particles but nbmp 6.
  const std::string d = deck_file("many.mpm", replace_line(kGood, 2, "nbmp 6"));
  expect_refused(run({"--quiet", "--out-dir", out, d}), d + ":12: ", {"nbmp", "6"});
}

TEST_F(Cli, TooFewParticles) {
  // nbmp 9, only 8 generated: found at 'endi'.
  const std::string d = deck_file("few.mpm", replace_line(kGood, 2, "nbmp 9"));
  expect_refused(run({"--quiet", "--out-dir", out, d}), d + ":13: ", {"nbmp", "9", "8"});
}

TEST_F(Cli, MaterialIdOutOfRangeInParticleCard) {
  const std::string d = deck_file("matid.mpm", replace_line(kGood, 12, "part bloc 1 2 1.0 0.5 1 1 1 2 2 2"));
  expect_refused(run({"--quiet", "--out-dir", out, d}), d + ":12: ", {"material", "2", "out of range"});
}

TEST_F(Cli, MaterialIdOutOfRangeInMaterialCard) {
  const std::string d = deck_file("matid2.mpm", replace_line(kGood, 11, "3 elas 1.0 100.0 0.25"));
  expect_refused(run({"--quiet", "--out-dir", out, d}), d + ":11: ", {"material", "3", "out of range"});
}

TEST_F(Cli, MissingEndi) {
  // Without the last line the file has 12 lines; the error is at its end (line 12).
  std::string text = kGood;
  text.erase(text.rfind("endi"));
  const std::string d = deck_file("noendi.mpm", text);
  expect_refused(run({"--quiet", "--out-dir", out, d}), d + ":12: ", {"endi"});
}

TEST_F(Cli, MissingEndiWithoutFinalNewline) {
  std::string text = kGood;
  text.erase(text.rfind("endi") - 1);  // the file ends with "... 2 2 2" (no newline)
  const std::string d = deck_file("noendi2.mpm", text);
  expect_refused(run({"--quiet", "--out-dir", out, d}), d + ":12: ", {"endi"});
}

TEST_F(Cli, LineTooLong) {
  const std::string d = deck_file("long.mpm", replace_line(kGood, 7, "spz 0 4 !" + std::string(4100, '-')));
  expect_refused(run({"--quiet", "--out-dir", out, d}), d + ":7: ", {"4096"});
}

TEST_F(Cli, MissingFile) {
  const std::string d = decks + "/does_not_exist.mpm";
  expect_refused(run({"--quiet", "--out-dir", out, d}), d + ": ", {"open"});
}

TEST_F(Cli, DeckIsADirectory) {
  // A directory opens as a stream on Linux but cannot be read: the problem is the file
  // itself (no line applies), and the message must say so rather than blame the content.
  const RunResult r = run({"--quiet", "--out-dir", out, decks});
  expect_refused(r, decks + ": ", {});
  EXPECT_TRUE(r.err.find("read") != std::string::npos || r.err.find("open") != std::string::npos ||
              r.err.find("directory") != std::string::npos)
      << r.err;
}

TEST_F(Cli, UnwritableOutputDirectory) {
  // A path under a regular file cannot be a directory, even for root.
  const std::string d = deck_file("good.mpm", kGood);
  const std::string file = tmp / "plainfile";
  testutil::write_file(file, "x");
  const std::string bad = file + "/sub";
  expect_refused(run({"--quiet", "--out-dir", bad, d}), d + ": ", {"cannot create output directory", bad});
}

TEST_F(Cli, MissingOutputDirectoryIsCreated) {
  const std::string d = deck_file("good.mpm", kGood);
  const std::filesystem::path dir = std::filesystem::path(tmp / "new") / "nested";
  ASSERT_FALSE(std::filesystem::exists(tmp / "new"));
  const RunResult r = run({"--quiet", "--out-dir", dir.string(), d});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "EnergyPlot.dat"));
}

TEST_F(Cli, UnwritableSummaryAndStateFiles) {
  const std::string d = deck_file("good.mpm", kGood);
  const std::string file = tmp / "plainfile";
  testutil::write_file(file, "x");
  expect_refused(run({"--quiet", "--out-dir", out, "--summary", file + "/s.json", d}), d + ": ",
                 {file + "/s.json"});
  expect_refused(run({"--quiet", "--out-dir", out, "--state", file + "/s.h5", d}), d + ": ", {file + "/s.h5"});
}

TEST_F(Cli, BadOptions) {
  const std::string d = deck_file("good.mpm", kGood);
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"--bogus", d}, {"--steps", "x", d}, {"--threads", "0", d}, {"--end-time", "-1", d},
           {"--rebalance-above", "0.9", d}, {}}) {
    const RunResult r = run(args);
    EXPECT_NE(r.code, 0);
    EXPECT_EQ(testutil::split_lines(r.err).size(), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("mpm3d: ", 0), 0u) << r.err;
    EXPECT_TRUE(testutil::list_dir(out).empty());
  }
}

// An adaptive grid asked of a method whose grid cannot move: one line naming the deck once.
TEST_F(Cli, RegridRefusedWhereTheGridCannotMove) {
  for (const auto& [deck, method] : {std::pair<std::string, std::string>{"null_sgmp.mpm", "'sgmp'"},
                                     {"neoh_TLmp.mpm", "'TLmp'"}}) {
    const std::string d = std::string(MPM3D_INPUTS) + "/methods/" + deck;
    const RunResult r = run({"--quiet", "--regrid-every", "3", "--out-dir", out, d});
    expect_refused(r, d + ": --regrid-every with " + method, {"grid"});
    EXPECT_EQ(r.err.find(d), r.err.rfind(d)) << "the deck named twice: " << r.err;
  }
}

// ------------------------------------------------------------ summary JSON and state file

namespace {

struct H5Reader {
  hid_t f;
  explicit H5Reader(const std::string& path) : f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~H5Reader() {
    if (f >= 0) H5Fclose(f);
  }
  // Dimensions of /particles/<name>; empty when missing.
  std::vector<hsize_t> dims(const std::string& name) const {
    std::vector<hsize_t> r;
    if (H5Lexists(f, "/particles", H5P_DEFAULT) <= 0) return r;
    if (H5Lexists(f, ("/particles/" + name).c_str(), H5P_DEFAULT) <= 0) return r;
    hid_t d = H5Dopen2(f, ("/particles/" + name).c_str(), H5P_DEFAULT);
    hid_t s = H5Dget_space(d);
    const int rank = H5Sget_simple_extent_ndims(s);
    r.resize(size_t(rank));
    H5Sget_simple_extent_dims(s, r.data(), nullptr);
    H5Sclose(s);
    H5Dclose(d);
    return r;
  }
  bool attr(const char* name, hid_t type, void* out) const {
    if (H5Aexists_by_name(f, "/particles", name, H5P_DEFAULT) <= 0) return false;
    hid_t a = H5Aopen_by_name(f, "/particles", name, H5P_DEFAULT, H5P_DEFAULT);
    const herr_t st = H5Aread(a, type, out);
    H5Aclose(a);
    return st >= 0;
  }
};

}  // namespace

TEST_F(Cli, SummaryAndStateHoldTheDocumentedContents) {
  const std::string d = kDecks + "/small.mpm";
  const std::string summary = tmp / "run.json", state = tmp / "run.h5";
  const RunResult r = run({"--quiet", "--no-output", "--steps", "5", "--threads", "1", "--summary", summary,
                           "--state", state, "--out-dir", out, d});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(testutil::list_dir(out).empty()) << "--no-output wrote files";

  // The same run in-process, for the expected values.
  mpm3d::Simulation sim(mpm3d::read_deck(d));
  const double dt = sim.model.dt;
  const double e0 = sim.initial_total_energy;
  for (int s = 0; s < 5; ++s) sim.step();

  const testutil::Json j = testutil::parse_json(testutil::read_file(summary));
  for (const char* k : {"deck", "title", "particles", "steps", "time", "dt_min", "dt_max", "threads", "wall_seconds",
                        "ns_per_particle_step", "kinetic_energy", "internal_energy", "initial_total_energy",
                        "external_work", "momentum", "bbox_min", "bbox_max", "max_epeff", "particles_outside_grid", "warnings"})
    EXPECT_TRUE(j.has(k)) << "summary lacks " << k;
  EXPECT_EQ(j["deck"].str, d);
  EXPECT_EQ(j["title"].str, "*** small test deck: two blocks moving toward each other");
  EXPECT_EQ(j["particles"].num, 128.0);
  EXPECT_EQ(j["steps"].num, 5.0);
  EXPECT_EQ(j["threads"].num, 1.0);
  // dt = 0.5 h / c, c = sqrt(120) for both materials; values written with 17 digits.
  EXPECT_NEAR(dt, 0.5 / std::sqrt(120.0), 1e-15);
  EXPECT_EQ(j["dt_min"].num, dt);
  EXPECT_EQ(j["dt_max"].num, dt);
  EXPECT_NEAR(j["time"].num, 5 * dt, 1e-14);
  // Initial energy: 1/2 (8 (0.01 + 0.0004) + 16 (0.0025 + 0.0001)) = 0.0624.
  EXPECT_NEAR(j["initial_total_energy"].num, 0.0624, 1e-15);
  EXPECT_EQ(j["initial_total_energy"].num, e0);
  EXPECT_EQ(j["kinetic_energy"].num, sim.kinetic);
  EXPECT_EQ(j["internal_energy"].num, sim.internal);
  EXPECT_EQ(j["external_work"].num, sim.external_work);
  ASSERT_EQ(j["momentum"].arr.size(), 3u);
  ASSERT_EQ(j["bbox_min"].arr.size(), 3u);
  ASSERT_EQ(j["bbox_max"].arr.size(), 3u);
  // Momentum (0.8 - 0.8, 0.16, 0.16) is conserved.
  EXPECT_NEAR(j["momentum"].arr[0].num, 0.0, 1e-13);
  EXPECT_NEAR(j["momentum"].arr[1].num, 0.16, 1e-13);
  EXPECT_NEAR(j["momentum"].arr[2].num, 0.16, 1e-13);
  // Particle centres started in x 2.25..5.75, y and z 1.25..2.75; after 5 small steps
  // (displacements < 0.05) they are still within 0.05 of that box.
  const double lo[3] = {2.25, 1.25, 1.25}, hi[3] = {5.75, 2.75, 2.75};
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(j["bbox_min"].arr[size_t(a)].num, lo[a], 0.05);
    EXPECT_NEAR(j["bbox_max"].arr[size_t(a)].num, hi[a], 0.05);
  }
  EXPECT_EQ(j["particles_outside_grid"].num, 0.0);
  EXPECT_EQ(j["warnings"].kind, testutil::Json::Array);
  EXPECT_TRUE(j["warnings"].arr.empty());
  EXPECT_GE(j["max_epeff"].num, 0.0);
  EXPECT_GE(j["wall_seconds"].num, 0.0);

  // State file: /particles datasets with the documented shapes and attributes.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  {
    H5Reader h(state);
    ASSERT_GE(h.f, 0) << "cannot open " << state;
    struct {
      const char* name;
      std::vector<hsize_t> dims;
    } expect[] = {{"position", {128, 3}}, {"velocity", {128, 3}}, {"stress", {128, 6}}, {"mass", {128}},
                  {"volume", {128}},      {"density", {128}},     {"epeff", {128}},     {"internal_energy", {128}},
                  {"material", {128}},    {"body", {128}}};
    for (const auto& e : expect) EXPECT_EQ(h.dims(e.name), e.dims) << e.name;
    double t = -1, hdt = -1;
    long step = -1;
    EXPECT_TRUE(h.attr("time", H5T_NATIVE_DOUBLE, &t));
    EXPECT_TRUE(h.attr("step", H5T_NATIVE_LONG, &step));
    EXPECT_TRUE(h.attr("dt", H5T_NATIVE_DOUBLE, &hdt));
    EXPECT_EQ(step, 5);
    EXPECT_EQ(hdt, dt);
    EXPECT_EQ(t, sim.time);
  }
  const auto& P = sim.model.particles;
  const auto pos = mpm3d::read_state_dataset(state, "position");
  const auto mass = mpm3d::read_state_dataset(state, "mass");
  const auto mat = mpm3d::read_state_dataset(state, "material");
  const auto body = mpm3d::read_state_dataset(state, "body");
  const auto rho = mpm3d::read_state_dataset(state, "density");
  ASSERT_EQ(pos.size(), 384u);
  // The program's final positions are those of the in-process run, bit for bit.
  EXPECT_EQ(std::memcmp(pos.data(), P.x.data(), pos.size() * sizeof(double)), 0);
  for (int p = 0; p < 128; ++p) {
    // Body 1: density 1, mass 0.125, material 1; body 2: density 2, mass 0.25, material 2
    // (ids 1-based in the file).
    const bool first = p < 64;
    EXPECT_EQ(mass[size_t(p)], first ? 0.125 : 0.25);
    EXPECT_EQ(mat[size_t(p)], first ? 1.0 : 2.0);
    EXPECT_EQ(body[size_t(p)], first ? 1.0 : 2.0);
    EXPECT_NEAR(rho[size_t(p)], first ? 1.0 : 2.0, 0.05);
  }
}

TEST_F(Cli, ResultsDoNotDependOnTheThreadCount) {
  const std::string d = kDecks + "/layout_a.mpm";
  for (const char* n : {"1", "2", "3"}) {
    const RunResult r = run({"--quiet", "--no-output", "--steps", "40", "--threads", n, "--state",
                             tmp / (std::string("t") + n + ".h5"), "--out-dir", out, d});
    ASSERT_EQ(r.code, 0) << r.err;
  }
  for (const char* ds : {"position", "velocity", "stress", "volume", "epeff", "internal_energy"}) {
    const auto a = mpm3d::read_state_dataset(tmp / "t1.h5", ds);
    for (const char* n : {"2", "3"}) {
      const auto b = mpm3d::read_state_dataset(tmp / (std::string("t") + n + ".h5"), ds);
      ASSERT_EQ(a.size(), b.size());
      EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << ds << " with " << n << " threads";
    }
  }
}

TEST_F(Cli, AnimationFilesWhenAsked) {
  // tecp and para: name_anim.dat, name_anim_<k>.vtu, name_anim.pvd and the grid
  // name_Grid.vtu; outt 0.25 of endt 0.5 gives frames at t = 0, 0.25, 0.5, numbered from 1
  // as the original's.
  std::string text = testutil::read_file(kDecks + "/small.mpm");
  text.insert(text.rfind("endi"), "tecp\npara\noutr seqv\n");
  const std::string d = deck_file("anim.mpm", text);
  const RunResult r = run({"--quiet", "--out-dir", out, d});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"anim.out", "anim_curv.dat", "EnergyPlot.dat", "MomentumPlot.dat", "anim_anim.dat",
                        "anim_anim.pvd", "anim_anim_1.vtu", "anim_anim_2.vtu", "anim_anim_3.vtu", "anim_Grid.vtu"})
    EXPECT_TRUE(testutil::fs::exists(out + "/" + f)) << f;
  EXPECT_FALSE(testutil::fs::exists(out + "/anim_anim_0.vtu"));
  EXPECT_FALSE(testutil::fs::exists(out + "/anim_anim_4.vtu"));
  // The collection lists the three files at their times: frame 1 the initial state.
  const std::string pvd = testutil::read_file(out + "/anim_anim.pvd");
  EXPECT_NE(pvd.find("timestep=\"0\" part=\"0\" file=\"anim_anim_1.vtu\""), std::string::npos) << pvd;
  const size_t f3 = pvd.find("file=\"anim_anim_3.vtu\"");
  ASSERT_NE(f3, std::string::npos) << pvd;
  const size_t ts = pvd.rfind("timestep=\"", f3) + 10;
  const double t3 = std::stod(pvd.substr(ts, pvd.find('"', ts) - ts));
  EXPECT_GE(t3, 0.5 - 1e-12);
  EXPECT_LT(t3, 0.5 + 0.5 / std::sqrt(120.0));
  // Frame 1: the book version's fields (small.mpm has no current-version keyword), the outr
  // variable (seqv is one of them: written once); vz the initial velocities (body 1: 0.02).
  const std::string vtu = testutil::read_file(out + "/anim_anim_1.vtu");
  for (const char* n : {"seqv", "epeff", "pressure", "vx", "vy", "vz", "vol", "celsius_t", "damage"})
    EXPECT_NE(vtu.find(std::string("Name=\"") + n + "\""), std::string::npos) << n;
  EXPECT_EQ(vtu.find("Name=\"seqv\""), vtu.rfind("Name=\"seqv\""));
  EXPECT_EQ(vtu.find("Name=\"disx\""), std::string::npos);  // current version only
  const size_t vz = vtu.find("Name=\"vz\" format=\"ascii\">\n");
  ASSERT_NE(vz, std::string::npos);
  EXPECT_EQ(std::stod(vtu.substr(vtu.find('\n', vz) + 1, 20)), 0.02);
  // The grid: small.mpm's box 8 x 4 x 4 in cells of 1: 9 * 5 * 5 nodes, 8 * 4 * 4 voxels.
  const std::string grid = testutil::read_file(out + "/anim_Grid.vtu");
  EXPECT_NE(grid.find("<Piece NumberOfPoints=\"225\" NumberOfCells=\"128\">"), std::string::npos) << grid.substr(0, 300);
  // One EnergyPlot line per step: steps = ceil(0.5 / dt) with dt = 0.5 / sqrt(120).
  const auto lines = testutil::split_lines(testutil::read_file(out + "/EnergyPlot.dat"));
  EXPECT_EQ(lines.size(), size_t(std::ceil(std::sqrt(120.0) - 1e-9)));
}
