// The time loop's choice of threads per step (cxx/solver/thread_team.hpp).
#include "solver/thread_team.hpp"

#include <algorithm>

namespace mpm3d {

namespace {
constexpr int kWarmUpSteps = 2;    // the first steps touch their memory first: not timed;
                                   // the last on the most threads, which start the team's
                                   // threads (a first step on them that a probe timed was
                                   // several times slower and kept short runs on one thread)
constexpr int kBlock = 4;          // a probe's steps in a row on one side, the first not
                                   // timed: the particles' data moves to the other caches
                                   // (steps that alternated found one thread 20 % slower than
                                   // it runs alone, and kept a small deck on two that one
                                   // thread ran 1.3 times faster)
constexpr int kProbeSteps = 2 * kBlock;  // at least: a block on one thread, one on the most
constexpr double kProbeSeconds = 0.05;  // at least, once the run has taken 64 times this:
                                        // scheduler time slices of a busy machine
constexpr int kProbeMaxSteps = 2000;
constexpr long kMinRunSteps = 16;  // steps between two probes at least
constexpr double kGapPerCost = 64.0;  // the wall time between probes, in probe costs
constexpr double kGapCap = 30.0;      // seconds: a busy machine that frees up is noticed
constexpr double kClearLoss = 3.0;    // a probe's steps on the most threads this many times its
                                      // steps on one so far, on average: it ends on one thread
constexpr double kSlowFactor = 1.5;   // steps on the most threads this much slower than the
                                      // probe's, on average since it: probe again
}  // namespace

void TeamChooser::start_probe() {
  phase_ = Phase::probe;
  probe_step_ = 0;
  probe_all_ = 0.0;
  for (int i = 0; i < 2; ++i) {
    probe_time_[i] = 0.0;
    probe_timed_[i] = 0;
  }
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
      current_ = (probe_step_ / kBlock) % 2 == 0 ? 1 : most_;
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
      const int side = current_ == 1 ? 1 : 0;
      probe_all_ += seconds;
      if (probe_step_ % kBlock != 0) {
        probe_time_[side] += seconds;
        ++probe_timed_[side];
      }
      ++probe_step_;
      const double total = probe_time_[0] + probe_time_[1];
      // A probe lasts a 64th of the run so far, up to kProbeSeconds: short runs stay short.
      const double length = std::min(kProbeSeconds, run_seconds_ / kGapPerCost);
      const bool measured = probe_timed_[0] > 0 && probe_timed_[1] > 0;
      const double mean_most = measured ? probe_time_[0] / probe_timed_[0] : 0.0;
      const double mean_one = measured ? probe_time_[1] / probe_timed_[1] : 0.0;
      const bool clear_loss = side == 0 && measured && mean_most > kClearLoss * mean_one;
      const bool pair_done = probe_step_ % (2 * kBlock) == 0;
      if (!clear_loss && (!pair_done || probe_step_ < kProbeSteps ||
                          (total < length && probe_step_ < kProbeMaxSteps)))
        return;
      mean_most_ = mean_most;
      chosen_ = mean_one < mean_most ? 1 : most_;
      // What the probe cost over its steps at the faster side's mean, its untimed steps
      // included (threads woken, data moved between the caches).
      const double cost = probe_all_ - probe_step_ * std::min(mean_most, mean_one);
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
