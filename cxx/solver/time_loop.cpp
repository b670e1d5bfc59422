// The time loop (cxx/solver/time_loop.hpp).
#include "solver/time_loop.hpp"

#include <chrono>
#include <cmath>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace mpm3d {

LoopProgress run_steps(Simulation& sim, const LoopLimits& limits, const LoopHooks& hooks) {
  LoopProgress progress;
  auto going = [&]() {
    // No end time (the API's mpm3d_step): no comparison with the clock at all.
    const bool before_end = limits.settle ? !sim.quasi_static_done()
                                          : std::isinf(limits.end_time) || sim.time < limits.end_time - limits.eps;
    return before_end && (limits.max_steps < 0 || sim.steps < limits.max_steps);
  };
  int most = 1;  // the caller's threads: each step runs on them or on one (TeamChooser)
#ifdef _OPENMP
  most = omp_get_max_threads();
#endif
  while (going()) {
    const auto t0 = std::chrono::steady_clock::now();
    if (hooks.before_step) hooks.before_step(sim);
#ifdef _OPENMP
    omp_set_num_threads(sim.team.next(most));
#endif
    const auto t1 = std::chrono::steady_clock::now();
    try {
      sim.step();
    } catch (const HealthError& e) {
      if (!(hooks.tolerate && hooks.tolerate(sim, e))) progress.failure = e.what();
    }
    const auto t2 = std::chrono::steady_clock::now();
    sim.team.took(std::chrono::duration<double>(t2 - t1).count());
    ++progress.steps_run;
    progress.step_seconds += std::chrono::duration<double>(t2 - t0).count();
    const bool go_on = hooks.after_step ? hooks.after_step(sim, progress) : true;
    if (!progress.failure.empty() || !go_on) break;
  }
#ifdef _OPENMP
  omp_set_num_threads(most);  // the caller's setting back
#endif
  return progress;
}

}  // namespace mpm3d
