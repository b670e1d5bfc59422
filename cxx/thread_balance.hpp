// The thread balancer of the patch stages: each thread's range of patches, list chunks or
// particles from its measured share, the timing of the loops, and the work stealing of
// for_thread_items (rebalance_threads, which sets the shares, is in thread_balance.cpp).
// Internal linkage, so the AVX2 unit compiles its own copies (see lanes.hpp).
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "update_step.hpp"

namespace mpm3d {
namespace {

// Where the items of threads 0 .. u-1 of T end among total items in loop `loop`: the sum
// of their shares of total (equal shares without c->thread_share for T threads).
inline int share_boundary(const StepContext* c, PatchLoop loop, int u, int T, int64_t total) {
  if (u <= 0) return 0;
  if (u >= T) return int(total);
  if (!(c->thread_share && c->nshare == T)) return int((total * u) / T);
  const double* share = c->thread_share + balance_index(loop, 0);
  double cum = 0.0;
  for (int v = 0; v < u; ++v) cum += share[v];
  return int(std::min(double(total), std::max(0.0, cum * double(total) + 0.5)));
}

// Patches [lo, hi) of thread t of T in loop `loop`: contiguous ranges of the patch index
// holding the thread's share of the binned particles (patch_start is the prefix sum of the
// lists; equal shares without c->thread_share). The trilinear patch stages (P2G, assembly,
// integration, G2P, node velocities; the stress update in list chunks, the same runs of
// particles) all use such ranges, and the loops' shares
// differ little, so a thread finds in its own cache most nodes and particles it wrote in
// the loop before; with a dynamic schedule every stage dealt the patches out anew and
// about half of all node and particle reads came from the other core's cache. Which
// thread does a patch never changes a result.
inline void thread_patches(const StepContext* c, PatchLoop loop, int t, int T, int& lo, int& hi) {
  auto first = [&](int u) -> int {
    const int target = share_boundary(c, loop, u, T, c->patch_start[c->npatch]);
    if (u >= T) return c->npatch;
    return int(std::lower_bound(c->patch_start, c->patch_start + c->npatch, target) - c->patch_start);
  };
  lo = first(t);
  hi = first(t + 1);
}

// Particles [lo, hi) of thread t of T: consecutive runs of the particle index in the
// proportions of the thread shares of the bin loop (equal without them).
inline void thread_particles(const StepContext* c, int t, int T, int& lo, int& hi) {
  lo = share_boundary(c, LOOP_BIN, t, T, c->np);
  hi = share_boundary(c, LOOP_BIN, t + 1, T, c->np);
}

// This thread's number t and the team size T (0 and 1 without OpenMP).
inline void team_position(int& t, int& T) {
  t = 0;
  T = 1;
#ifdef _OPENMP
  t = omp_get_thread_num();
  T = omp_get_num_threads();
#endif
}

// The clock of the busy times (0 without OpenMP, which needs no balance).
inline double busy_clock() {
#ifdef _OPENMP
  return omp_get_wtime();
#else
  return 0.0;
#endif
}

// Whether a team of T threads records its busy times (the shares are set for its size).
inline bool balance_timed(const StepContext* c, int T) { return c->thread_busy && c->nshare == T; }

// Adds the seconds since t0 to thread t's busy time in loop `loop` (rebalance_threads).
inline void add_busy(const StepContext* c, PatchLoop loop, int t, double t0) {
  c->thread_busy[balance_index(loop, t)] += busy_clock() - t0;
}

// The unclaimed patches [first, end) of one thread's range in one word (StepContext::
// patch_ranges): its owner claims from the front, others from the end, each claim one
// compare-and-swap, so every patch is done exactly once.
inline uint64_t pack_range(int first, int end) { return (uint64_t(uint32_t(first)) << 32) | uint32_t(end); }

// Claims the next patch of range word w, from the front (the owner) or the end; -1 when
// none is left.
inline int claim_patch(uint64_t* w, bool front) {
  uint64_t cur = __atomic_load_n(w, __ATOMIC_ACQUIRE);
  for (;;) {
    const int first = int(cur >> 32), end = int(uint32_t(cur));
    if (first >= end) return -1;
    const uint64_t next = front ? pack_range(first + 1, end) : pack_range(first, end - 1);
    if (__atomic_compare_exchange_n(w, &cur, next, false, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE))
      return front ? first : end - 1;
  }
}

// The particle stages that need no patch buffer (the stress update) take the patch lists
// in chunks of this many entries: runs of whole lane groups, fine enough that the shares
// cut within a patch and that a stolen item is short.
constexpr int kListChunk = 64;

// Chunks [lo, hi) of the concatenated patch lists (patch_part) of thread t of T in loop
// `loop`: its share of the binned particles, rounded to whole chunks.
inline void thread_list_chunks(const StepContext* c, PatchLoop loop, int t, int T, int& lo, int& hi) {
  const int total = c->patch_start[c->npatch];
  const int nchunk = (total + kListChunk - 1) / kListChunk;
  auto first = [&](int u) -> int {
    if (u >= T) return nchunk;
    return std::min(nchunk, (share_boundary(c, loop, u, T, total) + kListChunk / 2) / kListChunk);
  };
  lo = first(t);
  hi = first(t + 1);
}

// List entries in chunks [lo, hi) (the last chunk of the lists may be short).
inline int list_chunk_entries(const StepContext* c, int lo, int hi) {
  const int total = c->patch_start[c->npatch];
  return std::min(total, hi * kListChunk) - std::min(total, lo * kListChunk);
}

// f(i) for every item i of a loop, each thread over its range(t, T, lo, hi); the thread's
// time in the loop goes to that loop's thread_busy, and the particles it did (weight(i)
// each) to thread_done (rebalance_threads). With c->patch_ranges a thread that is through
// its own range takes the remaining items of the others from their far ends (the ranges
// are set before the team starts, so no thread can miss one); which thread does an item
// never changes a bit.
template <class Range, class Weight, class F>
inline void for_thread_items(const StepContext* c, PatchLoop loop, Range&& range, Weight&& weight, F&& f) {
  int team = 1;
#ifdef _OPENMP
  team = omp_get_max_threads();
#endif
  const bool steal = c->patch_ranges && team > 1 && team <= kMaxBalancedThreads;
  if (steal)
    for (int t = 0; t < team; ++t) {
      int lo, hi;
      range(t, team, lo, hi);
      __atomic_store_n(c->patch_ranges + 8 * size_t(t), pack_range(lo, hi), __ATOMIC_RELAXED);
    }
#pragma omp parallel num_threads(team)
  {
    int t, T;
    team_position(t, T);
    const bool timed = balance_timed(c, T);
    const double t0 = timed ? busy_clock() : 0.0;
    int64_t done = 0;
    auto run = [&](int i) {
      f(i);
      done += weight(i);
    };
    if (steal && T == team) {
      for (int i; (i = claim_patch(c->patch_ranges + 8 * size_t(t), true)) >= 0;) run(i);
      for (int k = 1; k < T; ++k) {
        uint64_t* w = c->patch_ranges + 8 * size_t((t + k) % T);
        for (int i; (i = claim_patch(w, false)) >= 0;) run(i);
      }
    } else {
      int lo, hi;
      range(t, T, lo, hi);
      for (int i = lo; i < hi; ++i) run(i);
    }
    if (timed) {
      add_busy(c, loop, t, t0);
      if (c->thread_done) c->thread_done[balance_index(loop, t)] += double(done);
    }
  }
}

// f(q) for every patch q, each thread over its thread_patches range of loop `loop`.
template <class F>
inline void for_thread_patches(const StepContext* c, PatchLoop loop, F&& f) {
  for_thread_items(
      c, loop, [&](int t, int T, int& lo, int& hi) { thread_patches(c, loop, t, T, lo, hi); },
      [&](int q) { return c->patch_start[q + 1] - c->patch_start[q]; }, f);
}

// f(first, count) for every chunk of kListChunk entries of the patch lists (the last one
// shorter), each thread over its thread_list_chunks range of loop `loop`.
template <class F>
inline void for_thread_list_chunks(const StepContext* c, PatchLoop loop, F&& f) {
  auto count = [c](int k) { return list_chunk_entries(c, k, k + 1); };
  for_thread_items(
      c, loop, [&](int t, int T, int& lo, int& hi) { thread_list_chunks(c, loop, t, T, lo, hi); }, count,
      [&](int k) { f(k * kListChunk, count(k)); });
}

}  // namespace
}  // namespace mpm3d
