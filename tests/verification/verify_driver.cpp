// mpm3d_verify: the driver of the verification and stability suite (tools/report.py,
// tests/verification/check.py). It runs a deck through the library (read_deck +
// Simulation, the same path as the mpm3d program), records the energies and momentum of
// every step, and writes what the analysis needs:
//   PREFIX.json          status (ok | stopped | refused), message, counts, energies, mass,
//                        momentum, energy error, wall time of the time loop, Taylor measures
//   PREFIX_series.csv    step, t, kinetic, internal, px, py, pz, external work
//   PREFIX_snap_K.bin    particle state at the K-th --snap time (raw float64, see below)
// Options:
//   --threads N      OpenMP threads
//   --out PREFIX     output prefix (default: the deck's base name)
//   --snap T1,T2,..  write snapshots at these times (after the first step reaching them)
//   --end-time T     run to T instead of the deck's end time;  --steps N: at most N steps
//   --mms A,C[,K]    Wallstedt & Guilkey (2008) axis-aligned manufactured solution:
//                    u_a = A sin(2 pi X_a)^K sin(C pi t) for each axis a (K = 1, the
//                    paper's, by default; K = 3 vanishes with its slope and curvature at
//                    the faces, for the 27-node stencils whose fixed node layers lie
//                    inside the body, see docs/VERIFICATION.md). Sets the initial
//                    velocities and, before every step, the body force of the hypoelastic
//                    (Jaumann) material of material 1, through the particle external-force
//                    array (the deck must allocate it with a 'load' card, e.g. a zero load)
//   --keep-going     when the health check's runaway-energy test trips (total energy above
//                    twice the initial energy plus the external work), record the first
//                    trip (step, message) and go on stepping: it is thrown after the step
//                    is complete, so the state is whole; a non-finite value still stops.
//                    For the dt-scale sweep, which looks for growth rather than a heuristic.
//   --taylor DP,BIN  Taylor bar measures (cxx/analysis) with spacing DP and the radius
//                    profile in bins of width BIN from the impact end
// Snapshot layout: np, t, then X0(3,np), x(3,np), v(3,np), sig(6,np), mass, vol, ie,
// epeff (np each), all float64 in machine order.
// Exit status: 0 ok, 3 stopped by the health check, 4 deck refused, 2 usage, 1 other error.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "io/analysis.hpp"
#include "input/data_in.hpp"
#include "input/ffi.hpp"
#include "io/json_text.hpp"
#include "mpm3d.hpp"

using namespace mpm3d;

namespace {

std::vector<double> split_reals(const std::string& s) {
  std::vector<double> r;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) r.push_back(std::atof(item.c_str()));
  return r;
}

void write_json(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
}

constexpr double kPi = 3.14159265358979323846;

// Manufactured solution: body force per unit mass on axis a at material point X, time t.
// Diagonal F = diag(1 + u_a,a): no spin, so the hypoelastic Jaumann update integrates to
// the Hencky law sigma = lambda ln J I + 2 G ln V exactly in time-continuous form, and
// rho0 u_tt = Div P + rho0 b with P_aa = (prod_{b != a} F_bb) sigma_aa gives
// b_a = u_a,tt - (1/rho0) (prod_{b != a} F_bb) (lambda + 2 G) F_aa,a / F_aa.
struct Mms {
  double A = 0, C = 0, rho0 = 1, lam = 0, G = 0;
  int K = 1;  // profile g(X) = sin(2 pi X)^K
  double g(double X) const { return std::pow(std::sin(2 * kPi * X), K); }
  double u(double X, double t) const { return A * g(X) * std::sin(C * kPi * t); }
  double v(double X, double t) const { return A * g(X) * C * kPi * std::cos(C * kPi * t); }
  void force(const double* X, double t, double* b) const {
    const double s = std::sin(C * kPi * t), w = 2 * kPi;
    double F[3], dF[3], acc[3];
    for (int a = 0; a < 3; ++a) {
      const double sx = std::sin(w * X[a]), cx = std::cos(w * X[a]);
      if (K == 1) {
        F[a] = 1.0 + w * A * cx * s;
        dF[a] = -w * w * A * sx * s;
        acc[a] = -A * (C * kPi) * (C * kPi) * sx * s;
      } else {  // g = sx^3: g' = 3 w sx^2 cx, g'' = w^2 (6 sx cx^2 - 3 sx^3)
        F[a] = 1.0 + A * 3 * w * sx * sx * cx * s;
        dF[a] = A * w * w * (6 * sx * cx * cx - 3 * sx * sx * sx) * s;
        acc[a] = -A * (C * kPi) * (C * kPi) * sx * sx * sx * s;
      }
    }
    for (int a = 0; a < 3; ++a) {
      const double other = F[(a + 1) % 3] * F[(a + 2) % 3];
      b[a] = acc[a] - other * (lam + 2 * G) * dF[a] / (F[a] * rho0);
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  std::string deck, prefix;
  std::vector<double> snaps, mms_args, taylor_args;
  double end_time = -1;
  long max_steps = -1;
  int threads = 0;
  bool keep_going = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto val = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "mpm3d_verify: " << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--threads") threads = std::atoi(val().c_str());
    else if (a == "--out") prefix = val();
    else if (a == "--snap") snaps = split_reals(val());
    else if (a == "--end-time") end_time = std::atof(val().c_str());
    else if (a == "--steps") max_steps = std::atol(val().c_str());
    else if (a == "--mms") mms_args = split_reals(val());
    else if (a == "--taylor") taylor_args = split_reals(val());
    else if (a == "--keep-going") keep_going = true;
    else if (!a.empty() && a[0] == '-') {
      std::cerr << "mpm3d_verify: unknown option " << a << "\n";
      return 2;
    } else deck = a;
  }
  if (deck.empty()) {
    std::cerr << "usage: mpm3d_verify DECK [--threads N] [--out PREFIX] [--snap T,..] [--end-time T] "
                 "[--steps N] [--mms A,C[,K]] [--taylor DP,BIN]\n";
    return 2;
  }
  if (prefix.empty()) prefix = deck.substr(0, deck.find_last_of('.'));
#ifdef _OPENMP
  if (threads > 0) omp_set_num_threads(threads);
  threads = omp_get_max_threads();
#else
  threads = 1;
#endif
  Model model;
  try {
    model = read_deck(deck);
  } catch (const std::exception& e) {
    write_json(prefix + ".json", "{\n  \"status\": \"refused\",\n  \"message\": \"" + json_escape(e.what()) + "\"\n}\n");
    std::cerr << "mpm3d_verify: deck refused: " << e.what() << "\n";
    return 4;
  }
  try {
    const auto t_setup = std::chrono::steady_clock::now();
    Simulation sim(std::move(model));
    Particles& P = sim.model.particles;
    const int np = P.np;
    const std::vector<double> X0 = P.x;
    Mms mms;
    const bool use_mms = mms_args.size() == 2 || mms_args.size() == 3;
    if (use_mms) {
      if (P.fext.empty()) throw std::runtime_error("--mms needs a deck with a 'load' card (external-force array)");
      const MaterialParams& m = sim.model.mats[0];
      mms.A = mms_args[0];
      mms.C = mms_args[1];
      if (mms_args.size() == 3) mms.K = int(mms_args[2]);
      if (mms.K != 1 && mms.K != 3) throw std::runtime_error("--mms A,C,K: K must be 1 or 3");
      mms.rho0 = m.rho0;
      mms.lam = m.lambda;
      mms.G = m.shear;
      for (int p = 0; p < np; ++p)
        for (int a = 0; a < 3; ++a) P.v[3 * size_t(p) + a] = mms.v(X0[3 * size_t(p) + a], 0.0);
      sim.measure();
      sim.initial_total_energy = sim.kinetic + sim.internal;
    }
    double mass0 = 0;
    for (int p = 0; p < np; ++p) mass0 += P.mass[p];
    const double E0 = sim.initial_total_energy;
    const double mom0[3] = {sim.momentum[0], sim.momentum[1], sim.momentum[2]};
    const double tend = end_time > 0 ? end_time : sim.model.endtime;
    const double eps = 1e-9 * sim.model.dt;
    std::ofstream series(prefix + "_series.csv");
    series << "step,t,kinetic,internal,px,py,pz,external_work\n";
    char line[400];
    auto record = [&]() {
      std::snprintf(line, sizeof line, "%ld,%.10g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", sim.steps, sim.time,
                    sim.kinetic, sim.internal, sim.momentum[0], sim.momentum[1], sim.momentum[2], sim.external_work);
      series << line;
    };
    record();
    size_t next_snap = 0;
    int nsnap_written = 0;
    auto snapshot = [&]() {
      const std::string path = prefix + "_snap_" + std::to_string(nsnap_written++) + ".bin";
      std::ofstream f(path, std::ios::binary);
      const double head[2] = {double(np), sim.time};
      f.write(reinterpret_cast<const char*>(head), sizeof head);
      auto put = [&](const std::vector<double>& v) {
        f.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(double)));
      };
      put(X0);
      put(P.x);
      put(P.v);
      put(P.sig);
      put(P.mass);
      put(P.vol);
      put(P.ie);
      put(P.epeff);
    };
    double loop_seconds = 0, max_energy_error = 0;
    std::string status = "ok", message, first_trip;
    long first_trip_step = -1;
    const double setup_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t_setup).count();
    LoopLimits limits;
    limits.end_time = tend;
    limits.eps = eps;
    limits.max_steps = max_steps;
    LoopHooks hooks;
    if (use_mms)
      hooks.before_step = [&](Simulation&) {
        const double t = sim.time;
        for (int p = 0; p < np; ++p) {
          double b[3];
          mms.force(&X0[3 * size_t(p)], t, b);
          for (int a = 0; a < 3; ++a) P.fext[3 * size_t(p) + a] = P.mass[p] * b[a];
        }
      };
    // --keep-going: an energy trip (finite energies) is recorded and the run goes on.
    hooks.tolerate = [&](Simulation&, const HealthError& e) {
      const bool energy_only = std::isfinite(sim.kinetic) && std::isfinite(sim.internal);
      if (!(keep_going && energy_only)) return false;
      if (first_trip_step < 0) {
        first_trip_step = sim.steps;
        first_trip = e.what();
      }
      return true;
    };
    hooks.after_step = [&](Simulation&, const LoopProgress& progress) {
      if (!progress.failure.empty()) return false;
      record();
      const double err = std::fabs((sim.kinetic + sim.internal) - E0 - sim.external_work);
      if (err > max_energy_error) max_energy_error = err;
      while (next_snap < snaps.size() && sim.time >= snaps[next_snap] - eps) {
        snapshot();
        ++next_snap;
      }
      return true;
    };
    const LoopProgress progress = run_steps(sim, limits, hooks);
    loop_seconds = progress.step_seconds;
    if (!progress.failure.empty()) {
      status = "stopped";
      message = progress.failure;
    }
    if (status == "ok" && nsnap_written == 0 && !snaps.empty()) snapshot();
    // Final checks: non-finite values anywhere, mass, momentum.
    long nonfinite = 0;
    for (const auto* v : {&P.x, &P.v, &P.sig, &P.ie, &P.vol})
      for (double d : *v) nonfinite += std::isfinite(d) ? 0 : 1;
    double mass1 = 0;
    for (int p = 0; p < np; ++p) mass1 += P.mass[p];
    std::ostringstream js;
    js << "{\n  \"status\": \"" << status << "\",\n  \"message\": \"" << json_escape(message) << "\",\n  \"deck\": \""
       << json_escape(deck) << "\",\n  \"particles\": " << np << ",\n  \"nodes\": " << sim.grid.nnode()
       << ",\n  \"steps\": " << sim.steps << ",\n  \"time\": " << json_number(sim.time) << ",\n  \"dt\": " << json_number(sim.model.dt)
       << ",\n  \"dcell\": " << json_number(sim.model.dcell) << ",\n  \"threads\": " << threads
       << ",\n  \"wall_seconds\": " << json_number(loop_seconds) << ",\n  \"setup_seconds\": " << json_number(setup_seconds)
       << ",\n  \"mass_initial\": " << json_number(mass0) << ",\n  \"mass_final\": " << json_number(mass1)
       << ",\n  \"kinetic_energy\": " << json_number(sim.kinetic) << ",\n  \"internal_energy\": " << json_number(sim.internal)
       << ",\n  \"initial_total_energy\": " << json_number(E0) << ",\n  \"external_work\": " << json_number(sim.external_work)
       << ",\n  \"max_energy_error\": " << json_number(max_energy_error) << ",\n  \"momentum_initial\": [" << json_number(mom0[0])
       << ", " << json_number(mom0[1]) << ", " << json_number(mom0[2]) << "],\n  \"momentum\": [" << json_number(sim.momentum[0]) << ", "
       << json_number(sim.momentum[1]) << ", " << json_number(sim.momentum[2]) << "],\n  \"nonfinite_values\": " << nonfinite
       << ",\n  \"particles_outside_grid\": " << sim.outside << ",\n  \"snapshots\": " << nsnap_written
       << ",\n  \"energy_check_first_step\": " << first_trip_step << ",\n  \"energy_check_message\": \""
       << json_escape(first_trip) << "\"";
    if (taylor_args.size() == 2) {
      const double dp = taylor_args[0], bin = taylor_args[1];
      const TaylorMeasures tm = taylor_measures(P.x, dp, 25.4);
      js << ",\n  \"taylor\": {\"L\": " << json_number(tm.length) << ", \"D\": " << json_number(tm.impact_diameter)
         << ", \"W\": " << json_number(tm.width_02) << "}";
      // Radius profile: axis through the mean (x, y); bins of width BIN from the lowest z.
      double cx = 0, cy = 0, zmin = INFINITY, zmax = -INFINITY;
      for (int p = 0; p < np; ++p) {
        cx += P.x[3 * size_t(p)];
        cy += P.x[3 * size_t(p) + 1];
        zmin = std::min(zmin, P.x[3 * size_t(p) + 2]);
        zmax = std::max(zmax, P.x[3 * size_t(p) + 2]);
      }
      cx /= np;
      cy /= np;
      const int nbin = int((zmax - zmin) / bin) + 1;
      std::vector<double> rmax(size_t(nbin), 0.0);
      for (int p = 0; p < np; ++p) {
        const int k = int((P.x[3 * size_t(p) + 2] - zmin) / bin);
        const double r = std::hypot(P.x[3 * size_t(p)] - cx, P.x[3 * size_t(p) + 1] - cy);
        if (k >= 0 && k < nbin && r > rmax[size_t(k)]) rmax[size_t(k)] = r;
      }
      js << ",\n  \"profile_z\": [";
      for (int k = 0; k < nbin; ++k) js << (k ? ", " : "") << json_number(zmin + (k + 0.5) * bin);
      js << "],\n  \"profile_r\": [";
      for (int k = 0; k < nbin; ++k) js << (k ? ", " : "") << json_number(rmax[size_t(k)]);
      js << "]";
    }
    js << "\n}\n";
    write_json(prefix + ".json", js.str());
    if (status == "stopped") {
      std::cerr << "mpm3d_verify: " << message << "\n";
      return 3;
    }
    return 0;
  } catch (const std::exception& e) {
    write_json(prefix + ".json", "{\n  \"status\": \"error\",\n  \"message\": \"" + json_escape(e.what()) + "\"\n}\n");
    std::cerr << "mpm3d_verify: " << e.what() << "\n";
    return 1;
  }
}
