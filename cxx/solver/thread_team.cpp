// The time loop's choice of threads per step (cxx/solver/thread_team.hpp).
#include "solver/thread_team.hpp"

#include <algorithm>

namespace mpm3d {

namespace {
constexpr int kWarmUpSteps = 2;    // the first steps touch their memory first: not timed;
                                   // the last on the most threads, which start the team's
                                   // threads (a first step on them that a probe timed was
                                   // several times slower and kept short runs on one thread)
constexpr int kProbeSteps = 6;     // at least: three on the most threads, three on one
constexpr double kProbeSeconds = 0.05;  // at least, once the run has taken 64 times this:
                                        // scheduler time slices of a busy machine
constexpr int kProbeMaxSteps = 2000;
constexpr long kMinRunSteps = 16;  // steps between two probes at least
constexpr double kGapPerCost = 64.0;  // the wall time between probes, in probe costs
constexpr double kGapCap = 30.0;      // seconds: a busy machine that frees up is noticed
constexpr double kClearLoss = 3.0;    // a probe's step on the most threads this many times its
                                      // steps on one so far: the probe ends on one thread
constexpr double kSlowFactor = 1.5;   // steps on the most threads this much slower than the
                                      // probe's, on average since it: probe again
}  // namespace

void TeamChooser::start_probe() {
  phase_ = Phase::probe;
  probe_step_ = 0;
  for (int i = 0; i < 2; ++i) probe_time_[i] = 0.0;
  ++probes;
}

int TeamChooser::next(int most) {
  if (!adaptive || most <= 1) return current_ = most;
  if (most != most_) {  // a new run, or the caller changed its threads
    most_ = most;
    phase_ = Phase::warm_up;
    run_steps_ = 0;
  }
  switch (phase_) {
    case Phase::warm_up:  // on one thread, the last on the most: a busy machine pays one
      current_ = run_steps_ + 1 < kWarmUpSteps ? 1 : most_;
      break;
    case Phase::probe:  // one thread first, so that a clear loss ends the probe at once
      current_ = probe_step_ % 2 == 0 ? 1 : most_;
      break;
    case Phase::run:
      current_ = chosen_;
      break;
  }
  return current_;
}

void TeamChooser::took(double seconds) {
  (current_ == 1 ? steps_on_one : steps_on_most) += 1;
  if (!adaptive || most_ <= 1) return;
  run_seconds_ += seconds;
  switch (phase_) {
    case Phase::warm_up:
      if (++run_steps_ >= kWarmUpSteps) start_probe();
      return;
    case Phase::probe: {
      // The mean, not the fastest step: on a busy machine most steps on two threads are fast
      // and every few a thread waits out another process's time slice.
      probe_time_[current_ == 1 ? 1 : 0] += seconds;
      ++probe_step_;
      const double total = probe_time_[0] + probe_time_[1];
      // A probe lasts a 64th of the run so far, up to kProbeSeconds: short runs stay short.
      const double length = std::min(kProbeSeconds, run_seconds_ / kGapPerCost);
      const bool clear_loss = probe_step_ % 2 == 0 && probe_time_[0] > kClearLoss * probe_time_[1];
      if (!clear_loss &&
          (probe_step_ % 2 != 0 || probe_step_ < kProbeSteps || (total < length && probe_step_ < kProbeMaxSteps)))
        return;
      const double half = 0.5 * probe_step_;  // steps on each
      mean_most_ = probe_time_[0] / half;
      chosen_ = probe_time_[1] < probe_time_[0] ? 1 : most_;
      const double cost = total - 2.0 * std::min(probe_time_[0], probe_time_[1]);
      gap_ = std::min(kGapPerCost * cost, std::max(kGapCap, 0.25 * kGapPerCost * cost));
      phase_ = Phase::run;
      run_steps_ = 0;
      since_probe_ = 0.0;
      return;
    }
    case Phase::run:
      since_probe_ += seconds;
      ++run_steps_;
      if (run_steps_ < kMinRunSteps) return;
      if (since_probe_ >= gap_ || (chosen_ != 1 && since_probe_ > kSlowFactor * mean_most_ * run_steps_)) start_probe();
      return;
  }
}

}  // namespace mpm3d
