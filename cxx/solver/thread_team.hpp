// How many threads the next step runs on. Every stage gives the same bits on any number of
// threads, so this decides speed only. Two threads do not pay on every step: on a small deck
// a step is a row of parallel regions too short to pay for the threads' meetings, and on a
// busy machine a thread waiting at a meeting spins while the thread it waits for has no core.
// So the time loop measures: it alternates blocks of steps on one thread and on the most
// threads the run may use, times each block's steps after its first (the data has moved
// between the caches), keeps the faster, and measures again after a gap of 64 times what the
// probe cost (its untimed steps included)
// (docs/PERFORMANCE.md, "Threads that pay"), or early when steps on the most threads slow
// down by half on average. A probe lasts at most a 64th of the run so far, so the probes
// cost a few percent of a run at most, however short.
#pragma once
#include <cstdint>

namespace mpm3d {

class TeamChooser {
 public:
  // Threads for the next step: `most` (the run's --threads or OpenMP's default), or one.
  int next(int most);
  // The wall time of the step just run on next()'s threads.
  void took(double seconds);
  bool adaptive = true;  // false: always `most` (--team fixed)
  long steps_on_one = 0, steps_on_most = 0;  // the run's steps on each (the summary)
  long probes = 0;

 private:
  enum class Phase { warm_up, probe, run };
  Phase phase_ = Phase::warm_up;
  int most_ = 0, current_ = 0, chosen_ = 0;
  int probe_step_ = 0;  // within the probe: blocks of steps on one thread, then on the most
  long probe_timed_[2] = {0, 0};  // the probe's timed steps on the most threads, on one
  long run_steps_ = 0;
  double probe_time_[2] = {0.0, 0.0};  // the probe's wall time on the most threads, on one
  double probe_all_ = 0.0;             // the wall time of all its steps, untimed ones too
  double mean_most_ = 0.0;             // its mean step on the most threads
  double gap_ = 0.0, since_probe_ = 0.0;     // wall time to the next probe, and so far
  double run_seconds_ = 0.0;                 // wall time of every step so far
  void start_probe();
};

}  // namespace mpm3d
