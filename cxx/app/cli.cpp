// The program mpm3d (run_main, app/cli.hpp): command-line options and usage text, the
// stop signals, the output loop around Simulation::step, the summary JSON.
#include "app/cli.hpp"

#include <algorithm>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/team_pool.hpp"
#include "input/ffi.hpp"
#include "io/data_out.hpp"
#include "io/json_text.hpp"
#include "mpm3d.hpp"
#include "solver/checkpoint.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace mpm3d {

namespace {

const char* kVersion = "mpm3d (MPM3D-CXX) 0.1.0";


struct Options {
  std::string deck, out_dir = ".", summary, state, kernel, kernels, checkpoint, restart;
  long max_steps = -1, checkpoint_every = 0;
  double rebalance_above = 1.03;
  double end_time = -1.0;
  int threads = 0, patch_cells = 4;
  long regrid_every = -1;  // -1: the deck's
  std::string particle_order = "blocks";
  RuleRequest rules;  // --rules, --rule, --time-step
  bool no_output = false, quiet = false, hdf5 = false, vtu_binary = false, patch_given = false, strict_energy = false, no_rest_skip = false,
       fixed_team = false;
};

// SIGINT/SIGTERM: the time loop finishes the current step, writes a checkpoint and exits
// with 128 + the signal number. The handler is one-shot: a second signal kills at once.
volatile std::sig_atomic_t g_signal = 0;
extern "C" void on_stop_signal(int sig) { g_signal = sig; }

void install_signal_handlers() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART | SA_RESETHAND;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

long to_long(const std::string& opt, const char* s) {
  long v;
  if (!parse_integer(s, v)) throw UsageError(opt + " needs an integer, got '" + s + "'");
  return v;
}

Options parse_args(int argc, char** argv, bool& exit_now) {
  Options o;
  exit_now = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw UsageError(a + " needs a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::cout << usage_text();
      exit_now = true;
      return o;
    } else if (a == "--version") {
      std::cout << kVersion << "\n";
      exit_now = true;
      return o;
    } else if (a == "--threads") {
      o.threads = int(to_long(a, value()));
      if (o.threads < 1) throw UsageError("--threads must be at least 1");
    } else if (a == "--team") {
      const std::string v = value();
      if (v != "adaptive" && v != "fixed") throw UsageError("--team takes adaptive or fixed, not '" + v + "'");
      o.fixed_team = v == "fixed";
    } else if (a == "--steps") {
      o.max_steps = to_long(a, value());
      if (o.max_steps < 0) throw UsageError("--steps must not be negative");
    } else if (a == "--rebalance-above") {
      const char* s = value();
      if (!parse_real(s, o.rebalance_above) || !(o.rebalance_above >= 1.0))
        throw UsageError("--rebalance-above needs a number of at least 1");
    } else if (a == "--end-time") {
      const char* s = value();
      if (!parse_real(s, o.end_time) || !(o.end_time > 0.0)) throw UsageError("--end-time needs a positive number");
    } else if (a == "--out-dir") {
      o.out_dir = value();
    } else if (a == "--no-output") {
      o.no_output = true;
    } else if (a == "--summary") {
      o.summary = value();
    } else if (a == "--state") {
      o.state = value();
    } else if (a == "--hdf5") {
      o.hdf5 = true;
    } else if (a == "--vtu-binary") {
      o.vtu_binary = true;
    } else if (a == "--checkpoint") {
      o.checkpoint = value();
    } else if (a == "--checkpoint-every") {
      o.checkpoint_every = to_long(a, value());
      if (o.checkpoint_every < 1) throw UsageError("--checkpoint-every must be at least 1");
    } else if (a == "--restart") {
      o.restart = value();
    } else if (a == "--patch-cells") {
      o.patch_given = true;
      o.patch_cells = int(to_long(a, value()));
      if (o.patch_cells < 1 || o.patch_cells > 64) throw UsageError("--patch-cells must lie in 1..64");
    } else if (a == "--particle-order") {
      o.particle_order = value();
      if (o.particle_order != "blocks" && o.particle_order != "deck")
        throw UsageError("--particle-order must be blocks or deck");
    } else if (a == "--time-step") {
      const std::string v = value();
      if (v != "book" && v != "current") throw UsageError("--time-step must be book or current");
      add_rule_setting(o.rules, "time_step=" + v);
    } else if (a == "--rules") {
      try {
        o.rules.preset = parse_rule_preset(value());
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
    } else if (a == "--rule") {
      try {
        add_rule_setting(o.rules, value());
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
    } else if (a == "--regrid-every") {
      o.regrid_every = to_long(a, value());
      if (o.regrid_every < 0 || o.regrid_every > 1000000000) throw UsageError("--regrid-every must lie in 0..1000000000");
    } else if (a == "--kernel") {
      o.kernel = value();
    } else if (a == "--kernels") {
      o.kernels = value();
    } else if (a == "--list-stages") {
      for (const char* n : kStageNames) std::cout << n << "\n";
      exit_now = true;
      return o;
    } else if (a == "--no-rest-skip") {
      o.no_rest_skip = true;
    } else if (a == "--strict-energy") {
      o.strict_energy = true;
    } else if (a == "--quiet" || a == "-q") {
      o.quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option " + a);
    } else if (o.deck.empty()) {
      o.deck = a;
    } else {
      throw UsageError("more than one deck given ('" + o.deck + "' and '" + a + "')");
    }
  }
  if (o.deck.empty()) throw UsageError("no deck given");
  return o;
}

void write_text_atomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    if (!f) throw std::runtime_error("cannot write " + path);
    f << text;
    if (!f) throw std::runtime_error("cannot write " + path);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error("cannot write " + path);
}

bool dir_writable(const std::string& dir) {
  struct stat st;
  return stat(dir.c_str(), &st) == 0 && S_ISDIR(st.st_mode) && access(dir.c_str(), W_OK) == 0;
}

}  // namespace

// An error every rank meets at once (after a collective decided it): each returns 1, the
// root prints it.
struct AllRanksError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What several ranks cannot run yet (app/mpi_main.cpp, cxx/parallel/): the first such feature, or "".
std::string not_distributed(const Options& opt, const Model& m) {
  for (const auto& c : m.curves)
    if (c.var == "spre" && !opt.no_output) return "the curve variable spre (smoothed pressure) (give --no-output)";
  if (m.sg) return "sgmp";
  return "";
}

int run_main(int argc, char** argv, Ranks* ranks) {
  Options opt;
  // Errors every rank meets alike (usage, deck, refusals) are printed by the root only.
  const bool root = !ranks || ranks->root();
  static std::ostream silent(nullptr);
  std::ostream& err = root ? std::cerr : silent;
  try {
    bool exit_now;
    opt = parse_args(argc, argv, exit_now);
    if (exit_now) return 0;
    StageTable probe = cxx_stages();
    if (!opt.kernel.empty()) select_stages(probe, opt.kernel, false);
    if (!opt.kernels.empty()) select_stages(probe, opt.kernels, true);
  } catch (const UsageError& e) {
    err << "mpm3d: " << e.what() << " (see --help)\n";
    return 2;
  } catch (const std::exception& e) {  // bad --kernel/--kernels
    err << "mpm3d: " << e.what() << "\n";
    return 2;
  }
  bool stepping = false;  // from the first step on, an error may be one rank's alone
  try {
    Model model = read_deck(opt.deck, deck_memory_budget(), opt.rules);
    if (opt.regrid_every >= 0) model.regrid_every = int(opt.regrid_every);
    if (model.sg && model.regrid_every > 0)
      throw std::runtime_error("--regrid-every with 'sgmp': the cell-centre grid of sgmp does not move");
    if (model.tl && model.regrid_every > 0)
      throw std::runtime_error("--regrid-every with 'TLmp': the reference grid of TLmp cannot move");
    if (ranks) {
      const std::string no = not_distributed(opt, model);
      if (!no.empty())
        throw std::runtime_error(no + " cannot run on several MPI ranks yet (run on one rank, with --threads)");
    }
    {  // --out-dir: created (with its parents) when missing
      std::error_code ec;
      std::filesystem::create_directories(opt.out_dir, ec);
      if (ec) throw std::runtime_error("cannot create output directory '" + opt.out_dir + "': " + ec.message());
    }
    if (!dir_writable(opt.out_dir)) throw std::runtime_error("output directory '" + opt.out_dir + "' is not writable");
    // A checkpoint is written with --checkpoint, --checkpoint-every or on a signal; the
    // default file is name_checkpoint.h5 in the output directory.
    const std::string default_ckpt = opt.out_dir + "/" + model.base_name + "_checkpoint.h5";
    const std::string ckpt_path =
        !opt.checkpoint.empty() ? opt.checkpoint : (opt.checkpoint_every > 0 ? default_ckpt : std::string());
    for (const std::string* f : std::initializer_list<const std::string*>{&opt.summary, &opt.state, &ckpt_path}) {
      if (f->empty()) continue;
      const size_t slash = f->find_last_of('/');
      const std::string d = slash == std::string::npos ? "." : f->substr(0, slash == 0 ? 1 : slash);
      if (!dir_writable(d)) throw std::runtime_error("cannot write '" + *f + "': directory not writable");
    }
#ifdef _OPENMP
    if (opt.threads > 0) omp_set_num_threads(opt.threads);
    const int threads = omp_get_max_threads();
    // --team adaptive: the set-up on one thread (a busy machine makes its parallel regions
    // spin; docs/PERFORMANCE.md, "Threads that pay"); the time loop chooses per step.
    if (!opt.fixed_team) omp_set_num_threads(1);
#else
    const int threads = 1;
#endif
    const auto t_start = std::chrono::steady_clock::now();
    // A restart keeps the patch size of the checkpoint (it fixes the summation order).
    const int patch_cells = opt.restart.empty() ? opt.patch_cells : checkpoint_patch_cells(opt.restart);
    Simulation sim(std::move(model), patch_cells,
                   opt.particle_order == "deck" ? ParticleOrder::deck : ParticleOrder::blocks);
    sim.strict_energy = opt.strict_energy;
    sim.skip_rest = !opt.no_rest_skip;
    sim.team.adaptive = !opt.fixed_team;
    if (!root) opt.quiet = true;  // the root reports for every rank
    {
      StageTable t = cxx_stages();
      if (!opt.kernel.empty()) select_stages(t, opt.kernel, false);
      if (!opt.kernels.empty()) select_stages(t, opt.kernels, true);
      sim.set_stages(t);
    }
    OutputSchedule resume;
    const bool restarted = !opt.restart.empty();
    const bool series = opt.hdf5 || (sim.model.hdf5 && !opt.no_output);
    {
      // The current version's frames hold displacements (disx..z): the initial positions are
      // kept (and checkpointed) when the run writes frames, or when the checkpoint holds them.
      Particles& P = sim.model.particles;
      const bool frames = (sim.model.paraview && !opt.no_output) || series;
      if (P.x0.empty() && sim.model.current_version &&
          (restarted ? checkpoint_has_particle_array(opt.restart, "initial_position") : frames))
        P.x0 = P.x;
    }
    // Every rank reads the whole checkpoint (written by any number of ranks), then keeps
    // its share.
    if (restarted) read_checkpoint(opt.restart, sim, resume);
    if (ranks) {
      ranks->set_rebalance_above(opt.rebalance_above);
      sim.distribute(*ranks);
    }
    const Model& m = sim.model;
    const double end_time = opt.end_time > 0.0 ? opt.end_time : m.endtime;
    // On several ranks the root writes every file: each frame from the particles gathered
    // on it, each step's curve values from the ranks holding the curves' particles.
    Output out;
    if (root && (!opt.no_output || series))
      out.open(m, opt.out_dir, !opt.no_output, series, restarted ? &resume : nullptr, opt.vtu_binary);
    const bool animates = Output::animates(m, !opt.no_output, series);
    const bool curves = !opt.no_output && !m.curves.empty();
    std::vector<int> curve_rows;
    std::vector<double> curve_values;
    auto write_frame = [&](double time, long step) {
      if (!ranks) return out.frame(m, time, step);
      Particles all;
      ranks->gather(m.particles, all);
      if (!root) return;
      std::swap(sim.model.particles, all);
      out.frame(m, time, step);
      std::swap(sim.model.particles, all);
    };
    install_signal_handlers();
    std::ostringstream head;
    head << "MPM3D-CXX: " << m.title << "\n  deck " << opt.deck << ", " << sim.global_np() << " particles, "
         << m.bodies.size() << " bodies, " << m.nmat << " materials\n  grid " << sim.grid.deck_nc[0] << " x "
         << sim.grid.deck_nc[1] << " x " << sim.grid.deck_nc[2] << " cells of " << m.dcell << ", patches of "
         << sim.grid.patch_cells << "^3 cells";
    if (sim.regrid_every > 0) head << ", adaptive: redefined every " << sim.regrid_every << " steps";
    head << "\n  scheme "
         << (m.scheme == SCHEME_MUSL ? "MUSL" : m.scheme == SCHEME_USL ? "USL" : "USF") << ", dt " << m.dt
         << ", end time " << end_time << ", threads " << threads;
    if (ranks) head << " on each of " << ranks->size() << " MPI ranks";
    if (restarted) head << "\n  restarted from " << opt.restart << " at step " << sim.steps << ", t " << sim.time;
    if (opt.patch_given && restarted && opt.patch_cells != patch_cells)
      head << "\n  warning: --patch-cells ignored: a restart keeps the checkpoint's " << patch_cells;
    {
      const std::string changed = rules_changed(m.rules, m.deck_current);
      head << "\n  rules: " << (changed.empty() ? std::string("ours") : changed) << " (" << rules_text(m.rules) << ")";
    }
    if (m.gimp) head << "\n  GIMP shape functions (27 nodes)";
    if (m.bspline) head << "\n  quadratic B-spline shape functions (27 nodes)";
    if (m.sg) head << "\n  smoothed-gradient MPM (sgmp): through the cell centres";
    if (m.fix_layers() == 2) head << "\n  two node layers held on each fixed or symmetric face";
    if (m.contact)
      head << "\n  contact between components 1 and 2, friction " << m.contact_mu << ", normals from "
           << (m.contact_normbody == 0 ? std::string("both components") : "component " + std::to_string(m.contact_normbody));
    for (const auto& w : m.warnings) head << "\n  warning: " << w;
    out.log(head.str());
    if (!opt.quiet) std::cout << head.str() << std::endl;
    // --quiet hides progress, never warnings: the deck's go to stderr before the first step.
    if (opt.quiet && root)
      for (const auto& w : m.warnings) std::cerr << "mpm3d: warning: " << w << std::endl;
    auto log_regrid = [&]() {
      if (sim.regrid_note.empty()) return;
      out.log(sim.regrid_note);
      if (!opt.quiet) std::cout << sim.regrid_note << std::endl;
      sim.regrid_note.clear();
    };
    log_regrid();

    double dt_min = m.dt, dt_max = m.dt, max_epeff = 0.0;
    double next_out = restarted ? resume.next_out : m.outtime, next_rpt = restarted ? resume.next_rpt : m.rpttime;
    if (!restarted && animates) write_frame(0.0, 0);
    const double eps = 1e-9 * m.dt;
    std::string failure;
    std::vector<std::string> energy_warnings;  // printed when raised, listed in the summary
    long last_ckpt = restarted ? sim.steps : -1;
    std::string last_ckpt_path = restarted ? opt.restart : std::string();
    auto save_checkpoint = [&](const std::string& path) {
      OutputSchedule o;
      out.save_state(o);
      o.next_out = next_out;
      o.next_rpt = next_rpt;
      if (ranks) {
        // The root writes every rank's particles, in one process's storage order, and (USF
        // contact) the nodes' contact marks from their owners: the file of one process.
        Particles all;
        ranks->gather(sim.model.particles, all);
        if (m.contact && m.scheme == SCHEME_USF) ranks->share_owned_nodes(sim.ctx, sim.ctx.contact.gnormal, 3);
        std::string error;
        if (root) {
          try {
            write_checkpoint(path, sim, o, &all);
          } catch (const std::exception& e) {
            error = std::string(e.what()).empty() ? "checkpoint " + path + ": not written" : e.what();
          }
        }
        error = ranks->broadcast(error, 0);
        if (!error.empty()) throw AllRanksError(error);
      } else {
        write_checkpoint(path, sim, o);
      }
      last_ckpt = sim.steps;
      last_ckpt_path = path;
    };
    int interrupted = 0;
    LoopLimits limits;
    limits.end_time = end_time;
    limits.eps = eps;
    limits.max_steps = opt.max_steps;
    // QuLo without --end-time: on past the end time until the load has settled.
    limits.settle = m.load_ramp_time > 0.0 && opt.end_time <= 0.0;
    LoopHooks hooks;
    hooks.before_step = [&](Simulation&) {
      dt_min = std::min(dt_min, m.dt);
      dt_max = std::max(dt_max, m.dt);
    };
    hooks.after_step = [&](Simulation&, const LoopProgress& progress) {
      log_regrid();
      for (const auto& w : sim.new_energy_warnings) {
        out.log("warning: " + w);
        if (root) std::cerr << "mpm3d: warning: " << w << std::endl;
        energy_warnings.push_back(w);
      }
      sim.new_energy_warnings.clear();
      if (!progress.failure.empty()) return false;
      if (curves) {
        held_curve_values(m, curve_rows, curve_values);
        if (ranks) ranks->max(curve_values);
      }
      out.step(m, StepRecord{sim.time, sim.steps, sim.kinetic, sim.internal, sim.momentum, sim.contact_force,
                             curve_values.data()});
      if (sim.time >= next_out - eps) {
        if (animates) write_frame(sim.time, sim.steps);
        next_out += m.outtime;
      }
      if (sim.time >= next_rpt - eps || sim.time >= end_time - eps) {
        next_rpt += m.rpttime;
        const double left = (end_time - sim.time) / m.dt * (progress.step_seconds / double(progress.steps_run));
        char line[256];
        std::snprintf(line, sizeof line, "step %7ld  t %.4e  KE %.4e  IE %.4e  E %.4e  outside %d  eta %.1f s",
                      sim.steps, sim.time, sim.kinetic, sim.internal, sim.kinetic + sim.internal, sim.outside,
                      left > 0 ? left : 0.0);
        out.log(line);
        out.flush();  // a killed run keeps every reported step; a full disk stops the run here
        if (!opt.quiet) std::cout << line << std::endl;
      }
      if (opt.checkpoint_every > 0 && sim.steps % opt.checkpoint_every == 0) save_checkpoint(ckpt_path);
      interrupted = ranks ? -ranks->min(-int(g_signal)) : int(g_signal);  // every rank stops at one step
      return interrupted == 0;
    };
    stepping = true;
#ifdef _OPENMP
    omp_set_num_threads(threads);  // the run's threads, for the time loop to choose from
#endif
    const LoopProgress progress = run_steps(sim, limits, hooks);
    const long steps_run = progress.steps_run;
    const double step_seconds = progress.step_seconds;
    failure = progress.failure;
    if (!failure.empty()) {
      if (last_ckpt >= 0)
        failure += "; the last checkpoint (step " + std::to_string(last_ckpt) + ") is kept in " + last_ckpt_path;
    } else if (interrupted) {
      const std::string path = ckpt_path.empty() ? default_ckpt : ckpt_path;
      if (last_ckpt != sim.steps || last_ckpt_path != path) save_checkpoint(path);
    } else if (!ckpt_path.empty() && last_ckpt != sim.steps) {
      save_checkpoint(ckpt_path);
    }
    if (ranks && (!opt.state.empty() || !opt.summary.empty())) {
      // The whole particle set on the root, for the state file and the summary.
      Particles all;
      ranks->gather(m.particles, all);
      if (root) std::swap(sim.model.particles, all);
    }
    const Particles& P = m.particles;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int p = 0; p < P.np; ++p) {
      max_epeff = std::max(max_epeff, P.epeff[p]);
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], P.x[3 * size_t(p) + a]);
        hi[a] = std::max(hi[a], P.x[3 * size_t(p) + a]);
      }
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    const double ns = steps_run > 0 ? step_seconds * 1e9 / (double(sim.global_np()) * double(steps_run)) : 0.0;
    std::vector<std::string> warnings = m.warnings;
    if (sim.outside > 0)
      warnings.push_back(std::to_string(sim.outside) + " particles left the grid and were frozen");
    const size_t printed_already = energy_warnings.size();  // the energy warnings come first
    warnings.insert(warnings.begin() + long(m.warnings.size()), energy_warnings.begin(), energy_warnings.end());
    if (!failure.empty()) warnings.push_back(failure);
    std::string stop_note;
    if (interrupted) {
      stop_note = std::string("interrupted by ") + (interrupted == SIGINT ? "SIGINT" : "SIGTERM") + " at step " +
                  std::to_string(sim.steps) + "; checkpoint " + last_ckpt_path + " (continue with --restart " +
                  last_ckpt_path + ")";
      warnings.push_back(stop_note);
    }
    // The state file holds the final state: not written when a signal stopped the run.
    if (!opt.state.empty() && !interrupted && root) write_state_h5(opt.state, m, sim.time, sim.steps, m.dt);
    // The most any rank sent per step (a collective: before the root alone writes).
    const double rank_bytes = ranks ? ranks->max(ranks->bytes_sent() / double(std::max(steps_run, 1L))) : 0.0;
    if (!opt.summary.empty() && root) {
      std::ostringstream js;
      js << "{\n  \"deck\": \"" << json_escape(opt.deck) << "\",\n  \"title\": \"" << json_escape(m.title)
         << "\",\n  \"particles\": " << P.np << ",\n  \"steps\": " << sim.steps << ",\n  \"time\": " << json_number(sim.time)
         << ",\n  \"rules\": {" << [&] {
              std::string s;
              for (int i = 0; i < kRuleCount; ++i)
                s += std::string(i ? ", " : "") + "\"" + kRules[i].name + "\": \"" + kRules[i].value[rule_value(m.rules, i)] + "\"";
              return s;
            }() << "}"
         << ",\n  \"dt_min\": " << json_number(dt_min) << ",\n  \"dt_max\": " << json_number(dt_max) << ",\n  \"threads\": " << threads
         << ",\n  \"team\": {\"adaptive\": " << (sim.team.adaptive ? "true" : "false")
         << ", \"steps_on_one_thread\": " << sim.team.steps_on_one << ", \"probes\": " << sim.team.probes
         << ", \"regions\": " << team_runs() << ", \"seconds_in_regions\": " << json_number(team_seconds()) << "}"
         << ",\n  \"ranks\": " << (ranks ? ranks->size() : 1)
         << ",\n  \"rank_imbalance\": " << json_number(ranks ? ranks->imbalance() : 1.0)
         << ",\n  \"rank_bytes_sent_per_step\": " << json_number(rank_bytes)
         << ",\n  \"rank_rebalances\": " << (ranks ? ranks->rebalances() : 0)
         << ",\n  \"wall_seconds\": " << json_number(wall) << ",\n  \"ns_per_particle_step\": " << json_number(ns)
         << ",\n  \"kinetic_energy\": " << json_number(sim.kinetic) << ",\n  \"internal_energy\": " << json_number(sim.internal)
         << ",\n  \"initial_total_energy\": " << json_number(sim.initial_total_energy)
         << ",\n  \"external_work\": " << json_number(sim.external_work)
         << ",\n  \"work_of_loads\": " << json_number(sim.load_work) << ",\n  \"energy_balance\": "
         << json_number(sim.kinetic + sim.internal - sim.initial_total_energy - sim.load_work) << ",\n  \"momentum\": ["
         << json_number(sim.momentum[0]) << ", " << json_number(sim.momentum[1]) << ", " << json_number(sim.momentum[2])
         << "],\n  \"bbox_min\": [" << json_number(lo[0]) << ", " << json_number(lo[1]) << ", " << json_number(lo[2]) << "],\n  \"bbox_max\": ["
         << json_number(hi[0]) << ", " << json_number(hi[1]) << ", " << json_number(hi[2]) << "],\n  \"max_epeff\": " << json_number(max_epeff)
         << ",\n  \"contact_force\": [" << json_number(sim.contact_force[0]) << ", " << json_number(sim.contact_force[1])
         << ", " << json_number(sim.contact_force[2]) << "],\n  \"contact_nodes\": " << sim.contact_nodes
         << ",\n  \"particles_outside_grid\": " << sim.outside << ",\n  \"regrid_every\": " << sim.regrid_every << ",\n  \"regrids\": " << sim.regrids
         << ",\n  \"regrids_forced\": " << sim.regrids_forced << ",\n  \"grid_window_offset\": [" << sim.grid.off[0]
         << ", " << sim.grid.off[1] << ", " << sim.grid.off[2] << "],\n  \"grid_window_cells\": [" << sim.grid.nc[0]
         << ", " << sim.grid.nc[1] << ", " << sim.grid.nc[2] << "],\n  \"patches\": " << sim.stats.patches
         << ",\n  \"patches_empty\": " << sim.stats.empty << ",\n  \"patch_max_particles\": " << sim.stats.max
         << ",\n  \"patch_mean_particles\": " << json_number(sim.stats.mean)
         << ",\n  \"patch_imbalance\": " << json_number(sim.stats.imbalance)
         << ",\n  \"rest_particle_steps\": " << sim.rest_particle_steps << ",\n  \"stage_seconds\": {";
      for (int st = 0; st < ST_COUNT; ++st)
        js << (st ? ", " : "") << "\"" << kStageNames[st] << "\": " << json_number(sim.stage_seconds[st]);
      js << "},\n  \"warnings\": [";
      for (size_t i = 0; i < warnings.size(); ++i) js << (i ? ", " : "") << "\"" << json_escape(warnings[i]) << "\"";
      js << "],\n  \"not_copied\": [";
      const std::vector<std::string> not_copied = not_copied_text(m);
      for (size_t i = 0; i < not_copied.size(); ++i) js << (i ? ", " : "") << "\"" << json_escape(not_copied[i]) << "\"";
      js << "],\n  \"sensitive\": [";
      const std::vector<std::string> sensitive = sensitive_text(m);
      for (size_t i = 0; i < sensitive.size(); ++i) js << (i ? ", " : "") << "\"" << json_escape(sensitive[i]) << "\"";
      js << "]\n}\n";
      write_text_atomic(opt.summary, js.str());
    }
    {
      std::ostringstream st;
      st << "stage shares:";
      double total = 0;
      for (double v : sim.stage_seconds) total += v;
      for (int s = 0; s < ST_COUNT; ++s)
        if (sim.stage_seconds[s] > 0) st << " " << kStageNames[s] << " " << int(100.0 * sim.stage_seconds[s] / total + 0.5) << "%";
      out.log(st.str());
      if (!opt.quiet) std::cout << st.str() << std::endl;
    }
    char tail[256];
    std::snprintf(tail, sizeof tail, "%s: %ld steps, t %.6g, %.2f s wall, %.1f ns per particle-step",
                  interrupted ? "stopped" : (failure.empty() ? "done" : "failed"), sim.steps,
                  sim.time, wall, ns);
    out.log(tail);
    if (!opt.quiet) std::cout << tail << std::endl;
    for (size_t i = 0; i < warnings.size(); ++i) {
      const std::string& w = warnings[i];
      const bool printed = (i >= m.warnings.size() && i < m.warnings.size() + printed_already) ||
                           (opt.quiet && i < m.warnings.size());  // --quiet: printed before the first step
      if (root && !printed && w != failure && w != stop_note) std::cerr << "mpm3d: warning: " << w << "\n";
    }
    if (!stop_note.empty() || !failure.empty()) out.log(stop_note.empty() ? failure : stop_note);
    out.flush();
    out.close();
    if (!failure.empty()) {
      err << "mpm3d: " << failure << "\n";
      return 3;
    }
    if (interrupted) {
      err << "mpm3d: " << stop_note << "\n";
      return 128 + interrupted;
    }
    return 0;
  } catch (const DeckError& e) {
    err << "mpm3d: " << e.what() << "\n";
    return 1;
  } catch (const AllRanksError& e) {
    err << "mpm3d: " << opt.deck << ": " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    if (ranks && stepping) {  // this rank's alone: the others would wait for it
      std::cerr << "mpm3d: rank " << ranks->rank() << ": " << opt.deck << ": " << e.what() << std::endl;
      ranks->abort(1);
    }
    err << "mpm3d: " << opt.deck << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace mpm3d
