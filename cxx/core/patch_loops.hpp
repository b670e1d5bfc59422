// The parallel loops of the trilinear patch stages: over the patches, and over the patch
// lists in chunks. Which thread runs a patch or a chunk never changes a bit (every patch
// writes its own buffer and its own nodes; the assembly reads the buffers in a fixed
// order), so the loops only decide speed.
//
// Each thread takes one contiguous run of patches holding an equal share of the binned
// particles, the same run in every stage, so a thread finds most of the nodes and
// particles it wrote in the stage before in its own cache. Side by side on the 2-core
// machine (docs/PERFORMANCE.md) OpenMP's static schedule over the patches (equal patch
// counts) and its dynamic one were 6-9% slower at 2 threads; measured timers, shares and
// work stealing on top of these runs gained under 2% and were dropped.
#pragma once
#include <algorithm>
#include <cstdint>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <type_traits>
#include <vector>

#include "core/step_state.hpp"
#include "core/team_pool.hpp"

namespace mpm3d {

// The thread count the stages use: OpenMP's (--threads, OMP_NUM_THREADS, the time loop's
// per-step choice).
inline int omp_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

// The stress update reads no patch buffer; it takes the patch lists in chunks of this many
// entries: runs of whole lane groups.
constexpr int kListChunk = 64;

// The calling thread's number t in its team and the team's size T (0 and 1 outside a
// team_region).
inline void team_position(int& t, int& T) {
  t = team_thread();
  T = team_size();
}

// Whether the stages run on one thread (the time loop's choice or the run's --threads 1):
// they then call their loop bodies directly, with no team to meet.
inline bool one_thread() {
#ifdef _OPENMP
  return omp_get_max_threads() == 1;
#else
  return true;
#endif
}

// body() by every thread of the team (team_pool.hpp: the OpenMP thread count, persistent
// threads that meet on one cache line instead of a parallel region's fork and join), or
// once directly on one thread (one_thread: team_position then gives 0 of 1, and
// team_barrier is free).
template <class F>
inline void team_region(F&& body) {
  if (one_thread()) {
    body();
    return;
  }
  using Body = typename std::remove_reference<F>::type;
  team_run(omp_threads(), [](void* b) { (*static_cast<Body*>(b))(); }, static_cast<void*>(&body));
}

// f(i) for i in [0, n), in one contiguous run per thread (OpenMP's static schedule: the
// first n % T threads one more), or in order directly on one thread (one_thread).
template <class F>
inline void team_for(int n, F&& f) {
  if (one_thread()) {
    for (int i = 0; i < n; ++i) f(i);
    return;
  }
  team_region([&] {
    int t, T;
    team_position(t, T);
    const int q = n / T, r = n % T;
    const int lo = t * q + (t < r ? t : r), hi = lo + q + (t < r ? 1 : 0);
    for (int i = lo; i < hi; ++i) f(i);
  });
}

// body(lo, hi, acc) over [0, n) in one contiguous run per thread, each with its own
// accumulator started at init; the accumulators combined in thread order (combine(a, b)
// into a). One thread: body(0, n, acc) directly.
template <class A, class F, class C>
inline A team_reduce(long n, A init, F&& body, C&& combine) {
  A acc = init;
  if (one_thread()) {
    body(0L, n, acc);
    return acc;
  }
  struct alignas(64) Slot {
    A v;
  };
  std::vector<Slot> part(static_cast<size_t>(omp_threads()), Slot{init});
  team_region([&] {
    int t, T;
    team_position(t, T);
    body(n * t / T, n * (t + 1) / T, part[size_t(t)].v);
  });
  for (const Slot& s : part) combine(acc, s.v);
  return acc;
}

// Patches [lo, hi) of thread t of T: the first patch whose list starts at or after the
// thread's equal share of the binned particles, up to the next thread's (with patches at
// rest, of the work: StepContext::patch_work).
inline void thread_patches(const StepContext* c, int t, int T, int& lo, int& hi) {
  const int n = c->patch.npatch;
  const int* start = c->patch.patch_work ? c->patch.patch_work : c->patch.patch_start;
  const int64_t total = start[n];
  auto first = [&](int u) -> int {
    if (u >= T) return n;
    const int target = int(total * u / T);
    return int(std::lower_bound(start, start + n, target) - start);
  };
  lo = first(t);
  hi = first(t + 1);
}

// f(q) for every patch q, each thread over its thread_patches run.
template <class F>
inline void for_patches(const StepContext* c, F&& f) {
  team_region([&] {
    int t, T, lo, hi;
    team_position(t, T);
    thread_patches(c, t, T, lo, hi);
    for (int q = lo; q < hi; ++q) f(q);
  });
}

// Patch q is at rest this step (StepContext::at_rest): no stage touches it.
inline bool patch_at_rest(const StepContext* c, int q) { return c->rest.at_rest && c->rest.at_rest[q]; }

// f(first, count) for every chunk of kListChunk entries of the patch lists (the last one
// shorter); the static schedule gives each thread one contiguous run of chunks.
template <class F>
inline void for_list_chunks(const StepContext* c, F&& f) {
  const int total = c->patch.patch_start[c->patch.npatch];
  const int nchunk = (total + kListChunk - 1) / kListChunk;
  team_for(nchunk, [&](int k) { f(k * kListChunk, std::min(kListChunk, total - k * kListChunk)); });
}

// f(first, count) over the patch lists for the stress stage: with patches at rest the list
// of each patch not at rest, each thread over its run of patches (shared by their work);
// otherwise chunks of the lists (for_list_chunks).
template <class F>
inline void for_stress_lists(const StepContext* c, F&& f) {
  if (!c->rest.at_rest) {
    for_list_chunks(c, f);
    return;
  }
  for_patches(c, [&](int q) {
    if (!patch_at_rest(c, q)) f(c->patch.patch_start[q], c->patch.patch_start[q + 1] - c->patch.patch_start[q]);
  });
}

}  // namespace mpm3d
