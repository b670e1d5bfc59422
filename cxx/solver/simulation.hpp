// The simulation: a Simulation owns the model, the grid and the step context, and advances
// the model one step at a time with a table of stage kernels (set-up, step, regrid,
// measure, health and energy checks); HealthError and the bounds of the health check.
#pragma once
#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "input/data_in.hpp"
#include "solver/ranks.hpp"
#include "solver/thread_team.hpp"
#include "stages/update_step.hpp"

namespace mpm3d {

// Bounds of the per-step health check on the density: rho / rho0 must stay within them.
constexpr double kDensityRatioMin = 1.0e-3, kDensityRatioMax = 1.0e3;

// The energy warnings of the health check fire when a body's internal energy falls below
// -kEnergyWarnFraction (|E0| + |W|), or the kinetic energy rises above E0 + |W| by more than
// that (E0 the initial total energy, W the bound of the external work).
constexpr double kEnergyWarnFraction = 1.0e-3;

// A numerical breakdown found by the per-step health check.
class HealthError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Simulation {
 public:
  // order: the particles' storage order (order_by_blocks, cxx/core/particle.hpp; deck: as read).
  explicit Simulation(Model model, int patch_cells = 4, ParticleOrder order = ParticleOrder::blocks);
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  void step();  // one explicit step; throws HealthError (see health_check)
  // QuLo's end of the run (the current version's rule): past the end time, the kinetic
  // share of the energy below 0.005 and the time above 100.
  bool quasi_static_done() const {
    return time > model.endtime && kinetic / (kinetic + internal) < 0.005 && time > 100.0;
  }
  void set_stages(const StageTable& t) { stages_ = t; }
  // Redefines the background grid (restart): the lattice (origin, cell h, deck_nc cells,
  // patch size) and the window of cells off .. off + nc - 1 on it.
  void set_grid(const double origin[3], double h, const int deck_nc[3], int patch_cells, const int off[3],
                const int nc[3]);

  Model model;
  Grid grid;
  StepContext ctx{};  // every particle; with contact: component 1 (ctx.contact.other = &ctx2)
  Grid grid2;         // contact only: component 2's grid
  StepContext ctx2{};  // contact only: component 2's context
  double contact_force[3] = {0, 0, 0};  // contact: force on component 1 in the last step
  int contact_nodes = 0;                // contact: nodes corrected in the last step
  long steps = 0;
  double time = 0.0;
  TeamChooser team;  // threads per step in the time loop (cxx/solver/time_loop.cpp)
  double kinetic = 0.0, internal = 0.0, momentum[3] = {0, 0, 0};
  double initial_total_energy = 0.0;
  // Bound of the work of gravity and loads so far (health check): the energy stage's
  // sum |f.v| (result[8]) times dt, added after each step.
  double external_work = 0.0;
  // The work of gravity and the point loads so far: the energy stage's sum f.v (result[9])
  // times dt, with the end-of-step velocities (first order in dt). The energy balance:
  // kinetic + internal - initial_total_energy - load_work (damping and contact losses in it).
  double load_work = 0.0;
  int outside = 0;  // particles outside the grid after the last step
  // Energy warnings of the health check (health_check), each raised once per run (per
  // body for the internal energy); the driver prints and clears new_energy_warnings. With
  // strict_energy the first one stops the run as a HealthError instead.
  bool strict_energy = false;
  std::vector<std::string> new_energy_warnings;
  double stage_seconds[ST_COUNT] = {};  // wall time spent in each stage (regrids count as bin)
  // Patches at rest skipped (StepContext::at_rest; docs/ARCHITECTURE.md "Patches at
  // rest"): the same bits as computing them, which false does (mpm3d --no-rest-skip).
  bool skip_rest = true;
  long rest_particle_steps = 0;  // particles of patches at rest, summed over the steps

  // Adaptive background grid (model.regrid_every > 0): the grid window is redefined from
  // the particles before steps 0, N, 2N, ... and whenever a particle inside the deck's box
  // has left the window (a forced regrid, then binning again).
  int regrid_every = 0;
  long regrids = 0, regrids_forced = 0;
  PatchStats stats;         // particles per patch after the last binning
  std::string regrid_note;  // the log line of a regrid in the set-up or the last step; the
                            // driver prints and clears it

  // Energies and momentum of the current state (the energy stage on its own), summed over
  // the patch lists of the last binning (the constructor's, a step's or bin_particles').
  void measure();
  // Bins the particles as they are now (both contact components, no regrid) into the patch
  // lists, then the patch statistics and buffers: after the particle arrays were replaced
  // wholesale (a restart), before a measure().
  void bin_particles();

  // A distributed run (cxx/solver/ranks.hpp): the other ranks, or null (one process). distribute
  // keeps this rank's share of the particles; from then on the model holds those only.
  Ranks* ranks = nullptr;
  void distribute(Ranks& r);
  // The particle set changed size or order (a distributed run's migration): the per-particle
  // scratch arrays follow and the contexts point at the new arrays.
  void particles_changed();
  int global_np() const { return ranks ? ranks->global_np() : model.particles.np; }

 private:
  StageTable stages_;
  std::vector<double> lx_;
  std::vector<double> partials_;  // the energy stage's columns (kReduceFields, npatch + 1)
  std::vector<int> cell_, pscratch_;
  std::vector<double> aux_;  // sgmp: the cell centres' fields (kAuxFields per cell)
  std::vector<double> sg_w_;  // sgmp: the weights per patch-list entry (P2G's 8, G2P's 8)
  std::vector<int> sg_cell_;  // sgmp: and their centres (8 each)
  std::vector<uint16_t> sg_reach_;  // sgmp: and the neighbour patches they reach
  std::vector<double> gravity_;
  std::vector<int> body_comp_;                        // contact: component of each body
  std::vector<double> gnormal1_, gnormal2_, cpartials_;  // contact only
  void bind();       // points ctx at the arrays
  void bind_grid();  // ... and at the grid's (again after a regrid)
  // Stage s of the table (stages_), timed, on component 1's context and, with contact and
  // when the stage runs per component, on component 2's.
  void run_stage(int s);
  // f(), its wall time added to stage s's.
  template <class F>
  void timed(int s, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    stage_seconds[s] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  // The bin stage with the adaptive window around it (regrids), then the patch buffers.
  void bin_stage();
  void regrid(int escaped);
  void note_regrid(int escaped);
  void ensure_patch_buffers();
  void health_check();
  void energy_check(double ie_min);
  // What a user of this deck can change when its energy runs away (the health check's
  // advice): a smaller dtscale; MUSL where the deck uses USF or USL; --rule
  // dp_return=original for a cohesionless Drucker-Prager material under our return; with
  // sgmp, the cell missing outside a held lower face that particles start next to.
  std::string instability_advice() const;
  std::string products_advice() const;
  // The energy warning's likely causes: the EOS of the materials that have one, the
  // particle cards' densities, else the time step.
  std::string energy_causes() const;
  // The health check's report on deck particle `deck` (0-based; the lowest of its kind on
  // every rank), written by format(p) on the rank that stores it as p.
  template <class F>
  std::string about_particle(int deck, F&& format) const;
  // "body B" of stored particle p, and ", rank R" when the run has several ranks.
  std::string body_and_rank(int p) const;
  std::vector<char> body_ie_warned_;
  bool kinetic_warned_ = false;
  bool lists_binned_ = false;  // the patch lists come from a bin of the current grid
  // TLmp: the bin of the reference positions, which never move, still holds (the same grid
  // and the same particles since it ran), so the bin stage has nothing to redo.
  bool reference_bin_holds_ = false;
  // The current version's dt from the particle velocities (Model::dt_per_step).
  double velocity_time_step();
  // Patches at rest: still_ (np) the kernels' bits (StepContext::still); per patch
  // of the last bin quiet_ (every particle still and at rest), quiet_before_ (the same at
  // the end of the step before, over that step's lists), rest_ and the work shares.
  std::vector<unsigned char> still_, quiet_, quiet_before_, rest_, ring_;
  std::vector<int> patch_work_;
  bool rest_on_ = false;       // rest_possible() held in the last step
  // The stages keep the still bits this step (track_): every step while a patch was quiet
  // at the end of the last tracked step, else one step in kRestProbeSteps.
  bool track_ = true, any_quiet_ = false;
  bool rest_possible() const;  // the deck and the stage table allow skipping patches at rest
  void quiet_patches(std::vector<unsigned char>& quiet) const;
  void mark_rest();    // after the bin stage, when possible: at_rest, patch_work for this step
  void forget_rest();  // the particles or the grid changed: nothing is known still
};

}  // namespace mpm3d
