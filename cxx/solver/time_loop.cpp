// The time loop (cxx/solver/time_loop.hpp).
#include "solver/time_loop.hpp"

#include <chrono>
#include <cmath>

namespace mpm3d {

LoopProgress run_steps(Simulation& sim, const LoopLimits& limits, const LoopHooks& hooks) {
  LoopProgress progress;
  auto going = [&]() {
    // No end time (the API's mpm3d_step): no comparison with the clock at all.
    const bool before_end = limits.settle ? !sim.quasi_static_done()
                                          : std::isinf(limits.end_time) || sim.time < limits.end_time - limits.eps;
    return before_end && (limits.max_steps < 0 || sim.steps < limits.max_steps);
  };
  while (going()) {
    const auto t0 = std::chrono::steady_clock::now();
    if (hooks.before_step) hooks.before_step(sim);
    try {
      sim.step();
    } catch (const HealthError& e) {
      if (!(hooks.tolerate && hooks.tolerate(sim, e))) progress.failure = e.what();
    }
    ++progress.steps_run;
    progress.step_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const bool go_on = hooks.after_step ? hooks.after_step(sim, progress) : true;
    if (!progress.failure.empty() || !go_on) break;
  }
  return progress;
}

}  // namespace mpm3d
