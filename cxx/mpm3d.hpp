// MPM3D (the program's time loop): a Simulation owns the model, the grid and the step
// context, and advances the model one step at a time with a table of stage kernels.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "data_in.hpp"
#include "grid.hpp"
#include "update_step.hpp"

namespace mpm3d {

// A numerical breakdown found by the per-step health check.
class HealthError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Simulation {
 public:
  explicit Simulation(Model model, int patch_cells = 8);
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  void step();  // one explicit step; throws HealthError on NaN/Inf
  void set_stages(const StageTable& t) { stages_ = t; }

  Model model;
  Grid grid;
  StepContext ctx{};  // every particle; with contact: component 1 (ctx.other = &ctx2)
  Grid grid2;         // contact only: component 2's grid
  StepContext ctx2{};  // contact only: component 2's context
  double contact_force[3] = {0, 0, 0};  // contact: force on component 1 in the last step
  int contact_nodes = 0;                // contact: nodes corrected in the last step
  long steps = 0;
  double time = 0.0;
  double kinetic = 0.0, internal = 0.0, momentum[3] = {0, 0, 0};
  double initial_total_energy = 0.0;
  double external_work = 0.0;  // work of gravity and loads so far (health check)
  int outside = 0;  // particles outside the grid after the last step
  double stage_seconds[ST_COUNT] = {};  // wall time spent in each stage

  // Energies and momentum of the current state (the energy stage on its own).
  void measure();

 private:
  StageTable stages_;
  std::vector<double> lx_, partials_;
  std::vector<int> cell_, pscratch_;
  std::vector<double> gravity_;
  std::vector<int> body_comp_;                        // contact: component of each body
  std::vector<double> gnormal1_, gnormal2_, cpartials_;  // contact only
  void bind();  // points ctx at the arrays
  void ensure_patch_buffers();
  void health_check();
  double dt_work_of_body_forces() const;
};

// Command-line driver (used by main): returns the process exit code.
int run_main(int argc, char** argv);

}  // namespace mpm3d
