// New thread shares of the patch loops from their measured busy times (rebalance_threads,
// declared in update_step.hpp; the ranges and the stealing built on the shares are in
// thread_balance.hpp).
#include <algorithm>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "thread_balance.hpp"

namespace mpm3d {

// The load balance of the patch stages, before the patch lists change, loop by loop
// (PatchLoop): each thread's speed in a loop (the particles it did there per busy second
// since the last binning: thread_done, else those of its range) gives its share of that
// loop in the next step, taken halfway to damp the jumps of the patch granularity. A thread that had no particles counts at the
// mean speed, and no share falls below a tenth of an equal one. On this project's virtual
// machines one core can run 1.5x slower than the other for minutes; equal ranges then
// leave the fast thread waiting a third of each step. A loop that did not run keeps its
// shares. The shares start equal, and again whenever the number of threads changes.
void rebalance_threads(StepContext* c) {
  if (!c->thread_share) return;
  int T = 1;
#ifdef _OPENMP
  T = omp_get_max_threads();
#endif
  if (T > kMaxBalancedThreads) {
    c->nshare = 0;
    return;
  }
  if (T != c->nshare) {
    c->nshare = T;
    for (int loop = 0; loop < LOOP_COUNT; ++loop)
      for (int t = 0; t < T; ++t) {
        c->thread_share[balance_index(loop, t)] = 1.0 / T;
        c->thread_busy[balance_index(loop, t)] = 0.0;
        if (c->thread_done) c->thread_done[balance_index(loop, t)] = 0.0;
      }
    return;
  }
  std::vector<double> rate(size_t(T), 0.0);
  for (int loop = 0; loop < LOOP_COUNT; ++loop) {
    double* share = c->thread_share + balance_index(loop, 0);
    double* busy = c->thread_busy + balance_index(loop, 0);
    double* done = c->thread_done ? c->thread_done + balance_index(loop, 0) : nullptr;
    double sum = 0.0;
    int known = 0;
    for (int t = 0; t < T && T > 1; ++t) {
      int lo, hi;
      double n;
      if (loop == LOOP_BIN) {
        thread_particles(c, t, T, lo, hi);
        n = hi - lo;
      } else if (done) {
        n = done[t];  // its own range and what it took from others
      } else if (loop == LOOP_STRESS) {
        thread_list_chunks(c, LOOP_STRESS, t, T, lo, hi);
        n = list_chunk_entries(c, lo, hi);
      } else {
        thread_patches(c, PatchLoop(loop), t, T, lo, hi);
        n = c->patch_start[hi] - c->patch_start[lo];
      }
      rate[size_t(t)] = 0.0;
      if (n > 0 && busy[t] > 0.0) {
        rate[size_t(t)] = n / busy[t];
        sum += rate[size_t(t)];
        ++known;
      }
    }
    if (known > 0) {
      const double mean = sum / known;
      for (int t = 0; t < T; ++t)
        if (!(rate[size_t(t)] > 0.0)) rate[size_t(t)] = mean, sum += mean;
      double total = 0.0;
      for (int t = 0; t < T; ++t) {
        share[t] = std::max(0.1 / T, 0.5 * share[t] + 0.5 * rate[size_t(t)] / sum);
        total += share[t];
      }
      for (int t = 0; t < T; ++t) share[t] /= total;
    }
    for (int t = 0; t < T; ++t) {
      busy[t] = 0.0;
      if (done) done[t] = 0.0;
    }
  }
}

}  // namespace mpm3d
