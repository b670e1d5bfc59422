// Reliability (docs/RELIABILITY.md): the per-step health check, checkpoint files and their
// errors, the HDF5 + XDMF animation series read back with the HDF5 C API, and the output
// variables of outr/curv/curx with pt2d. Restart equality and signals are script tests
// (tests/restart_equality.sh, tests/signal_restart.sh, tests/reliability.cmake).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "io/analysis.hpp"
#include "solver/checkpoint.hpp"
#include "input/data_in.hpp"
#include "io/data_out.hpp"
#include "mpm3d.hpp"
#include "test_util.hpp"

using testutil::RunResult;
using testutil::TempDir;

namespace {

const std::string kExe = MPM3D_EXE;
const std::string kDecks = MPM3D_TEST_DECKS;

class Reliability : public ::testing::Test {
 protected:
  TempDir tmp;
  std::string out, scratch;
  void SetUp() override {
    out = tmp / "out";
    scratch = tmp / "scratch";
    for (const auto& d : {out, scratch}) testutil::fs::create_directory(d);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  RunResult run(const std::vector<std::string>& args) { return testutil::run_program(kExe, args, out, scratch); }
  std::string deck_with(const std::string& base, const std::string& name, const std::string& extra) {
    std::string text = testutil::read_file(kDecks + "/" + base);
    text.insert(text.rfind("endi"), extra);
    const std::string p = tmp / name;
    testutil::write_file(p, text);
    return p;
  }
};

// Reads a whole dataset as doubles; empty when missing.
std::vector<double> read_doubles(hid_t f, const std::string& name, std::vector<hsize_t>* dims = nullptr) {
  std::vector<double> v;
  if (H5Lexists(f, name.c_str(), H5P_DEFAULT) <= 0) return v;
  hid_t d = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
  hid_t s = H5Dget_space(d);
  if (dims) {
    dims->assign(size_t(H5Sget_simple_extent_ndims(s)), 0);
    H5Sget_simple_extent_dims(s, dims->data(), nullptr);
  }
  v.resize(size_t(H5Sget_simple_extent_npoints(s)));
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(s);
  H5Dclose(d);
  return v;
}

template <class T>
T read_attr(hid_t f, const std::string& obj, const char* name, hid_t type) {
  T v{};
  hid_t a = H5Aopen_by_name(f, obj.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(a, 0) << obj << " " << name;
  if (a >= 0) {
    H5Aread(a, type, &v);
    H5Aclose(a);
  }
  return v;
}

}  // namespace

// ---------------------------------------------------------------- health check

TEST_F(Reliability, HealthCheckStopsACrushedBlockAndKeepsTheLastCheckpoint) {
  // crush.mpm: an elastic block (c = sqrt(120)) at 20 per unit time, dt = 0.9 h / c: it
  // reaches the fixed wall z = 0 at step 3, where one step's compression exceeds the
  // particles' volume.
  const std::string ck = tmp / "ck.h5";
  const RunResult r = run({"--quiet", "--no-output", "--checkpoint-every", "1", "--checkpoint", ck, "--summary",
                           tmp / "s.json", kDecks + "/crush.mpm"});
  EXPECT_EQ(r.code, 3) << r.err;
  const auto lines = testutil::split_lines(r.err);
  ASSERT_EQ(lines.size(), 1u) << r.err;
  for (const char* w : {"mpm3d: numerical breakdown at step 3", "particle 1 (body 1)", "non-positive volume",
                        "the last checkpoint (step 2) is kept in"})
    EXPECT_NE(lines[0].find(w), std::string::npos) << w << " not in " << lines[0];
  // The checkpoint of step 2 is intact (not overwritten by the broken state) and restores.
  hid_t f = H5Fopen(ck.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(read_attr<long>(f, "/simulation", "step", H5T_NATIVE_LONG), 2);
  const auto vol = read_doubles(f, "/particles/volume");
  H5Fclose(f);
  ASSERT_EQ(vol.size(), 64u);
  for (double v : vol) EXPECT_GT(v, 0.0);
  EXPECT_FALSE(testutil::fs::exists(ck + ".tmp"));
  const auto js = testutil::parse_json(testutil::read_file(tmp / "s.json"));
  EXPECT_EQ(js["steps"].num, 3.0);
  // Without checkpointing: the same stop, exit status 3.
  const RunResult r2 = run({"--quiet", "--no-output", kDecks + "/crush.mpm"});
  EXPECT_EQ(r2.code, 3);
  EXPECT_NE(r2.err.find("particle 1 (body 1) has a non-positive volume"), std::string::npos) << r2.err;
}

TEST(Health, DensityOutsideTheBoundsStopsTheRun) {
  for (const double factor : {1.0e-4, 2.0e3}) {
    mpm3d::Simulation sim(mpm3d::read_deck(kDecks + "/small.mpm"));
    // Particle 70 (body 2, rho0 = 2): volume scaled so rho = 2e4 rho0 or 5e-4 rho0, far
    // outside [1e-3, 1e3] rho0 whatever one step changes.
    sim.model.particles.vol[69] *= factor;
    try {
      sim.step();
      ADD_FAILURE() << "no health error for factor " << factor;
    } catch (const mpm3d::HealthError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("at step 1"), std::string::npos) << m;
      EXPECT_NE(m.find("particle 70 (body 2) has density"), std::string::npos) << m;
      EXPECT_NE(m.find("outside the bounds [0.001, 1000] rho0"), std::string::npos) << m;
    }
  }
  // Within the bounds (rho = 500 rho0): no error.
  mpm3d::Simulation sim(mpm3d::read_deck(kDecks + "/small.mpm"));
  sim.model.particles.vol[69] *= 2.0e-3;
  EXPECT_NO_THROW(sim.step());
}

TEST_F(Reliability, EnergyWarningsNameTheStepTheBodyAndTheFigures) {
  // prestressed.mpm: body 2 starts at rest under its EOS's C0 = 1 and expands; body 1 flies
  // freely (E0 = 4). By step 2 body 2's internal energy is about -0.036 (bound -0.004) and
  // the kinetic energy 4.10 (bound 4.004); the total stays near 4, far from the runaway
  // stop at twice E0.
  const std::string deck = kDecks + "/prestressed.mpm";
  const RunResult r = run({"--no-output", "--summary", tmp / "s.json", deck});  // warnings print unless --quiet
  EXPECT_EQ(r.code, 0) << r.err;
  const auto lines = testutil::split_lines(r.err);
  ASSERT_EQ(lines.size(), 2u) << r.err;
  for (const char* w : {"mpm3d: warning: energy: the internal energy of body 2 is -0.03", "at step 2 (t = ",
                        "below -0.1% of the initial total energy 4 plus the external work 0"})
    EXPECT_NE(lines[0].find(w), std::string::npos) << w << " not in " << lines[0];
  for (const char* w : {"mpm3d: warning: energy: the kinetic energy 4.1", "at step 2",
                        "exceeds the initial total energy 4 plus the external work 0 by 0.1"})
    EXPECT_NE(lines[1].find(w), std::string::npos) << w << " not in " << lines[1];
  EXPECT_EQ(r.err.find("body 1"), std::string::npos) << r.err;  // the free body is left alone
  // Raised once: the run goes on to its end (3 steps) without repeating them.
  const auto js = testutil::parse_json(testutil::read_file(tmp / "s.json"));
  EXPECT_EQ(js["steps"].num, 3.0);
  ASSERT_EQ(js["warnings"].arr.size(), 2u);
  EXPECT_EQ("mpm3d: warning: " + js["warnings"].arr[0].str, lines[0]);
  // --strict-energy: the first warning stops the run, exit status 3.
  const RunResult s = run({"--quiet", "--no-output", "--strict-energy", deck});
  EXPECT_EQ(s.code, 3);
  const auto sl = testutil::split_lines(s.err);
  ASSERT_EQ(sl.size(), 1u) << s.err;
  EXPECT_NE(sl[0].find("mpm3d: energy: the internal energy of body 2"), std::string::npos) << sl[0];
  EXPECT_NE(sl[0].find("(stopped: --strict-energy)"), std::string::npos) << sl[0];
  // In process: the same stop at step 2 as a HealthError.
  mpm3d::Simulation sim(mpm3d::read_deck(deck));
  sim.strict_energy = true;
  EXPECT_NO_THROW(sim.step());
  EXPECT_THROW(sim.step(), mpm3d::HealthError);
}

// ---------------------------------------------------------------- checkpoint files

TEST_F(Reliability, CheckpointHoldsEveryParticleArrayAndRestoresInProcess) {
  // mixed_thermal.mpm allocates a temperature array: it must be stored and restored.
  const std::string deck = kDecks + "/mixed_thermal.mpm";
  mpm3d::Simulation a(mpm3d::read_deck(deck));
  for (int s = 0; s < 7; ++s) a.step();
  mpm3d::OutputSchedule o;
  o.next_out = 1.5;
  o.next_rpt = 2.5;
  o.frame_times = {0.0, 0.5};
  o.files = {{"x_curv.dat", 1234}, {"EnergyPlot.dat", 99}};
  const std::string ck = tmp / "a.h5";
  mpm3d::write_checkpoint(ck, a, o);
  EXPECT_FALSE(testutil::fs::exists(ck + ".tmp"));
  mpm3d::Simulation b(mpm3d::read_deck(deck));
  mpm3d::OutputSchedule ob;
  mpm3d::read_checkpoint(ck, b, ob);
  EXPECT_EQ(b.steps, 7);
  EXPECT_EQ(b.time, a.time);
  EXPECT_EQ(b.external_work, a.external_work);
  EXPECT_EQ(b.load_work, a.load_work);
  EXPECT_EQ(b.initial_total_energy, a.initial_total_energy);
  EXPECT_EQ(ob.next_out, 1.5);
  EXPECT_EQ(ob.next_rpt, 2.5);
  EXPECT_EQ(ob.frame_times, o.frame_times);
  EXPECT_EQ(ob.files, o.files);
  auto fa = mpm3d::particle_fields(a.model.particles), fb = mpm3d::particle_fields(b.model.particles);
  ASSERT_EQ(fa.size(), fb.size());
  int compared = 0;
  for (size_t k = 0; k < fa.size(); ++k) {
    if (fa[k].d) EXPECT_TRUE(*fa[k].d == *fb[k].d) << fa[k].name;
    if (fa[k].i) EXPECT_TRUE(*fa[k].i == *fb[k].i) << fa[k].name;
    compared += fa[k].d ? !fa[k].d->empty() : !fa[k].i->empty();
  }
  EXPECT_EQ(compared, 11);  // all but external_force, temperature and deck_id included
  ASSERT_FALSE(b.model.particles.temp.empty());
  // Both continue to the same bits.
  for (int s = 0; s < 5; ++s) {
    a.step();
    b.step();
  }
  EXPECT_TRUE(a.model.particles.x == b.model.particles.x);
  EXPECT_TRUE(a.model.particles.temp == b.model.particles.temp);
  EXPECT_EQ(a.kinetic, b.kinetic);
}

TEST_F(Reliability, BadRestartsAreRefusedWithOneLine) {
  // A missing file, a file that is not a checkpoint, a checkpoint of another deck.
  const std::string small = kDecks + "/small.mpm";
  RunResult r = run({"--quiet", "--no-output", "--restart", tmp / "none.h5", small});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("none.h5: cannot open"), std::string::npos) << r.err;
  r = run({"--quiet", "--no-output", "--steps", "2", "--state", tmp / "state.h5", small});
  ASSERT_EQ(r.code, 0) << r.err;
  r = run({"--quiet", "--no-output", "--restart", tmp / "state.h5", small});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("not an mpm3d checkpoint"), std::string::npos) << r.err;
  r = run({"--quiet", "--no-output", "--steps", "2", "--checkpoint", tmp / "ck.h5", kDecks + "/crush.mpm"});
  ASSERT_EQ(r.code, 0) << r.err;
  r = run({"--quiet", "--no-output", "--restart", tmp / "ck.h5", small});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("written for a model of 64 particles, the deck has 128"), std::string::npos) << r.err;
  EXPECT_EQ(testutil::split_lines(r.err).size(), 1u) << r.err;
  r = run({"--checkpoint-every", "0", small});
  EXPECT_EQ(r.code, 2);
  // A restart at or past --steps does nothing more (steps count from the start).
  r = run({"--quiet", "--no-output", "--steps", "1", "--restart", tmp / "ck.h5", "--state", tmp / "s2.h5",
           kDecks + "/crush.mpm"});
  ASSERT_EQ(r.code, 0) << r.err;
  hid_t f = H5Fopen((tmp / "s2.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(read_attr<long>(f, "/particles", "step", H5T_NATIVE_LONG), 2);
  H5Fclose(f);
}

// ---------------------------------------------------------------- HDF5 series

TEST_F(Reliability, Hdf5SeriesReadsBackWithTheRightShapesAndTimes) {
  // small.mpm: endt 0.5, outt 0.25, dt = 0.5 / sqrt(120): frames at steps 0, 6 and 11
  // (the first step with t >= 0.25 and the last); the deck keyword 'hdf5' asks for them.
  const std::string d = deck_with("small.mpm", "series.mpm", "hdf5\noutr mat\noutr velz\noutr pres\n");
  const RunResult r = run({"--quiet", "--out-dir", out, "--state", tmp / "final.h5", d});
  ASSERT_EQ(r.code, 0) << r.err;
  const double dt = 0.5 / std::sqrt(120.0);
  hid_t f = H5Fopen((out + "/series_anim.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const long want_steps[3] = {0, 6, 11};
  for (int k = 0; k < 3; ++k) {
    const std::string g = "/frames/" + std::to_string(k);
    ASSERT_GT(H5Lexists(f, g.c_str(), H5P_DEFAULT), 0) << g;
    const long step = read_attr<long>(f, g, "step", H5T_NATIVE_LONG);
    const double t = read_attr<double>(f, g, "time", H5T_NATIVE_DOUBLE);
    EXPECT_EQ(step, want_steps[k]);
    EXPECT_NEAR(t, double(step) * dt, 1e-14);
    std::vector<hsize_t> dims;
    EXPECT_EQ(read_doubles(f, g + "/position", &dims).size(), 384u);
    EXPECT_EQ(dims, (std::vector<hsize_t>{128, 3}));
    for (const char* v : {"mat", "velz", "pres"}) {
      read_doubles(f, g + "/" + v, &dims);
      EXPECT_EQ(dims, (std::vector<hsize_t>{128})) << v;
    }
    const auto mat = read_doubles(f, g + "/mat");
    ASSERT_EQ(mat.size(), 128u);
    for (int p = 0; p < 128; ++p) EXPECT_EQ(mat[size_t(p)], p < 64 ? 1.0 : 2.0);
  }
  EXPECT_EQ(H5Lexists(f, "/frames/3", H5P_DEFAULT), 0);
  // Frame 0: the initial velocities (body 1: vz 0.02, body 2: 0); last frame = final state.
  const auto vz0 = read_doubles(f, "/frames/0/velz");
  EXPECT_EQ(vz0[0], 0.02);
  EXPECT_EQ(vz0[127], 0.0);
  const auto last = read_doubles(f, "/frames/2/position");
  H5Fclose(f);
  const auto fin = mpm3d::read_state_dataset(tmp / "final.h5", "position");
  ASSERT_EQ(last.size(), fin.size());
  EXPECT_EQ(std::memcmp(last.data(), fin.data(), fin.size() * sizeof(double)), 0);
  // The XDMF names the three frames in time order.
  const std::string x = testutil::read_file(out + "/series_anim.xdmf");
  EXPECT_NE(x.find("CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_NE(x.find("series_anim.h5:/frames/2/velz"), std::string::npos);
  EXPECT_EQ(x.find("/frames/3/"), std::string::npos);
}

// ---------------------------------------------------------------- output variables

TEST(OutputVariables, OneFunctionPerNameForAll) {
  // The book's fourteen and the current version's stsx, disx, disy, disz and (smoo) spre.
  const char* names[] = {"seqv", "epef", "mat",  "pres", "volu", "engk", "engi", "velx", "vely", "velz",
                         "cels", "fail", "sspd", "damg", "stsx", "disx", "disy", "disz", "spre"};
  ASSERT_EQ(mpm3d::output_variables().size(), 19u);
  for (const char* n : names) {
    EXPECT_TRUE(mpm3d::is_output_variable(n)) << n;  // the deck reader accepts it
    EXPECT_NE(mpm3d::output_variable(n), nullptr) << n;
  }
  for (const auto& v : mpm3d::output_variables()) EXPECT_TRUE(mpm3d::is_output_variable(v.name)) << v.name;
  EXPECT_EQ(mpm3d::output_variable("disw"), nullptr);
  EXPECT_FALSE(mpm3d::is_output_variable("disw"));
}

TEST(OutputVariables, TemperatureAndEosWaveSpeed) {
  // Material 1 john (thermal, room temperature 20), material 2 sjcf + Mie-Gruneisen
  // (c0 = 3, rho0 = 2), material 3 elas (no EOS).
  mpm3d::Model m = mpm3d::read_deck_text(
      "nbmp 3 nbbo 1 nmat 3 spx 0 4 spy 0 4 spz 0 4 dcel 1 endt 1\n"
      "mate 1 john 1.0 100.0 0.25 0.1 0.2 1.0 0.0 1.0 20.0 1000.0 1.0 1.0\n"
      " 2 sjcf 2.0 30.0 0.25 0.1 0.2 1.0 0.0 1.0 0.5\n"
      " 3 elas 1.0 100.0 0.25\n"
      "seos 2 2 3.0 1.5 2.0 0.0\n"
      "part poin 1 3\n 1 1 1.0 1 1 1\n 2 2 1.0 2 1 1\n 3 3 1.0 3 1 1\nendi\n",
      "vars.mpm");
  EXPECT_EQ(mpm3d::particle_variable(m, "cels", 0), 20.0);
  m.particles.temp[0] = 345.5;
  EXPECT_EQ(mpm3d::particle_variable(m, "cels", 0), 345.5);
  // Mie-Gruneisen: K = rho0 c0^2 = 18, G = 30 / 2.5 = 12: sqrt((18 + 16) / rho) at
  // rho = mass / vol = 2 (vol = mass / rho0 = 0.5): sqrt(17); at half the volume sqrt(8.5).
  EXPECT_NEAR(mpm3d::particle_variable(m, "sspd", 1), std::sqrt(17.0), 1e-14);
  m.particles.vol[1] = 0.25;
  EXPECT_NEAR(mpm3d::particle_variable(m, "sspd", 1), std::sqrt(8.5), 1e-14);
  // No EOS: sqrt((lambda + 2G) / rho) = sqrt(120) at rho = rho0 = 1.
  EXPECT_NEAR(mpm3d::particle_variable(m, "sspd", 2), std::sqrt(120.0), 1e-13);
  // No failure strain: fail and damg are 0 whatever the plastic strain.
  m.particles.epeff[2] = 5.0;
  EXPECT_EQ(mpm3d::particle_variable(m, "fail", 2), 0.0);
  EXPECT_EQ(mpm3d::particle_variable(m, "damg", 2), 0.0);
  m.particles.epeff[1] = 0.5;  // exactly eps_f: failed, damage 1
  EXPECT_EQ(mpm3d::particle_variable(m, "fail", 1), 1.0);
  EXPECT_EQ(mpm3d::particle_variable(m, "damg", 1), 1.0);
  // Without a thermal material there is no temperature: cels is 0.
  EXPECT_EQ(mpm3d::particle_variable(mpm3d::read_deck(kDecks + "/small.mpm"), "cels", 0), 0.0);
}

TEST_F(Reliability, AllVariablesInEveryOutputAndPt2dAndCurx) {
  // Every variable in outr (TecPlot, ParaView, HDF5) and in curv; curx at (2.75, 1.25,
  // 1.25): body 1 is a bloc from (2, 1, 1), spacing 0.5, z index fastest, so the particle at
  // i = 1, j = 0, l = 0 is number 1*16 + 1 = 17; pt2d keeps the particles initially in
  // x <= 3 (i = 0, 1 of body 1: 32 particles).
  std::string extra = "tecp\npara\nhdf5\npt2d 0 3 0 4 0 4\ncurx sspd 2.75 1.25 1.25\n";
  const char* names[] = {"seqv", "epef", "mat", "pres", "volu", "engk", "engi",
                         "velx", "vely", "velz", "cels", "fail", "sspd", "damg"};
  for (const char* n : names) extra += std::string("outr ") + n + "\ncurv " + n + " 70\n";
  const std::string d = deck_with("small.mpm", "all.mpm", extra);
  const RunResult r = run({"--quiet", "--out-dir", out, d});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto tec = testutil::split_lines(testutil::read_file(out + "/all_anim.dat"));
  ASSERT_GE(tec.size(), 3u);
  std::string header = tec[1];
  for (const char* n : names) EXPECT_NE(header.find(std::string("\"") + n + "\""), std::string::npos) << n;
  EXPECT_EQ(tec[2].rfind("ZONE", 0), 0u);
  EXPECT_NE(tec[2].find(" I=32 "), std::string::npos) << tec[2];
  // Each TecPlot row: x y z and 14 values.
  std::istringstream row(tec[3]);
  int values = 0;
  for (std::string w; row >> w;) ++values;
  EXPECT_EQ(values, 17);
  const std::string vtu = testutil::read_file(out + "/all_anim_1.vtu");  // frames from 1, as the original
  for (const char* n : names) EXPECT_NE(vtu.find(std::string("Name=\"") + n + "\""), std::string::npos) << n;
  const auto curv = testutil::split_lines(testutil::read_file(out + "/all_curv.dat"));
  ASSERT_GE(curv.size(), 2u);
  EXPECT_NE(curv[0].find("sspd17"), std::string::npos) << curv[0];
  for (const char* n : names) EXPECT_NE(curv[0].find(std::string(n) + "70"), std::string::npos) << n;
  EXPECT_EQ(curv[1].size(), size_t(12 * (3 + 1 + 14)));  // time, engk, engi, curx, 14 curves
  hid_t f = H5Fopen((out + "/all_anim.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  for (const char* n : names) EXPECT_EQ(read_doubles(f, std::string("/frames/0/") + n).size(), 128u) << n;
  H5Fclose(f);
}
