// The time loop: the one loop over Simulation::step that the program (app/cli.cpp), the C and
// Fortran API (mpm3d_step) and the verification driver run. It owns the stopping rule and the
// step timing; what a caller does around a step (output, checkpoints, signals, manufactured
// forces) it passes as hooks.
#pragma once
#include <functional>
#include <limits>
#include <string>

#include "solver/simulation.hpp"

namespace mpm3d {

// When the loop stops: at end_time - eps (never with the default, infinite end_time), after the run's step max_steps (a total, as
// Simulation::steps; < 0: no limit), or, with settle (a quasi-static load without an end
// time of its own), once Simulation::quasi_static_done().
struct LoopLimits {
  double end_time = std::numeric_limits<double>::infinity();
  double eps = 0.0;
  long max_steps = -1;
  bool settle = false;
};

// Where the loop stands after a step, for the hooks and the caller.
struct LoopProgress {
  long steps_run = 0;         // steps this loop has run
  double step_seconds = 0.0;  // wall time inside before_step and Simulation::step
  std::string failure;        // the HealthError of the last step that stopped the run, or ""
};

struct LoopHooks {
  // Before each step (manufactured forces, the time-step range of the summary).
  std::function<void(Simulation&)> before_step;
  // A HealthError the run may go on after (true); default: every one stops the run.
  std::function<bool(Simulation&, const HealthError&)> tolerate;
  // After each step, also the one that failed (progress.failure set; the loop stops after
  // it whatever this returns); false stops the loop.
  std::function<bool(Simulation&, const LoopProgress&)> after_step;
};

// Runs steps until a limit, a failure or after_step's false; returns the progress.
LoopProgress run_steps(Simulation& sim, const LoopLimits& limits, const LoopHooks& hooks = {});

}  // namespace mpm3d
