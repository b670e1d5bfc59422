// The bin stage: each particle's cell, local coordinates and patch (the lane kernel
// bin_range), then a stable counting sort into the per-patch particle lists and the buffer
// slots of the non-empty patches.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "transfer/transfer_lanes.hpp"
#include "stages/update_step.hpp"

using namespace mpm3d;

extern "C" void mpm3d_cxx_bin(StepContext* c) {
  const int npatch = c->patch.npatch;
  int* patch_of = c->patch.pscratch;  // patch of each particle, -1 outside
  int outside = 0, nslot = 0;
  const int team = omp_threads();
  // One row of patch counts per thread, each zeroed by its thread.
  std::unique_ptr<int[]> counts(new int[size_t(team) * size_t(npatch)]);
  // Particles and non-empty patches of each thread's run of patches (own cache lines).
  struct alignas(64) RunSums {
    int particles, nonempty;
  };
  std::vector<RunSums> run_sums(static_cast<size_t>(team), RunSums{0, 0});
  const bool avx2 = lanes_use_avx2();
  const bool pre = c->ranks.prebinned != 0;
  const bool filter = c->contact.only_comp > 0;
  // One team for the whole stage: each thread bins an equal run of particles and counts
  // them by patch; then a stable counting sort with those runs as its chunks. The runs are
  // consecutive and ascending, so each patch lists its particles in ascending index
  // whatever the number of threads: the lists do not depend on it.
  auto bin = [&](int& outside_here) {
    int t, T;
    team_position(t, T);
    const int lo = int(int64_t(c->part.np) * t / T), hi = int(int64_t(c->part.np) * (t + 1) / T);
    int* cnt = counts.get() + size_t(t) * size_t(npatch);
    std::fill(cnt, cnt + npatch, 0);
    // Cells, local coordinates, patches (transfer_lanes.hpp), unless prebinned.
    if (!pre)
      outside_here += avx2 ? bin_range_avx2(c, lo, hi, patch_of) : bin_range<VectorLane<kLanes>>(c, lo, hi, patch_of);
    // Each thread counts (and below fills) a run of the particles in their canonical order:
    // the arrays' own, or c->ranks.order's (every particle binned first). The patch of particle p
    // in this context: prebinned patches are those of every particle, of either component.
    const int* order = c->ranks.order;
    auto particle = [&](int i) { return order ? order[i] : i; };
    auto patch = [&](int p) { return pre && filter && other_component(c, p) ? -1 : patch_of[p]; };
    if (order) team_barrier();
    for (int i = lo; i < hi; ++i) {
      const int p = particle(i), q = patch(p);
      if (q >= 0) ++cnt[q];
      else if (pre && c->part.cell[p] < 0 && !(filter && other_component(c, p))) ++outside_here;
    }
    team_barrier();
    // Patch starts, buffer slots, and each run's fill pointer into every patch's list: a
    // prefix sum over the patches in two passes, each thread over an equal run of patches
    // (a serial pass would cost T x npatch steps on one thread, about 1 % of a step of the
    // fine model at 16 threads): the run's particle and non-empty patch totals, then,
    // once every run has its totals, the run's own entries.
    const int q0 = int(int64_t(npatch) * t / T), q1 = int(int64_t(npatch) * (t + 1) / T);
    auto count_of = [&](int u, int q) -> int& { return counts[size_t(u) * size_t(npatch) + size_t(q)]; };
    {
      int particles = 0, nonempty = 0;
      for (int q = q0; q < q1; ++q) {
        int total = 0;
        for (int u = 0; u < T; ++u) total += count_of(u, q);
        particles += total;
        nonempty += total > 0;
      }
      run_sums[size_t(t)] = {particles, nonempty};
    }
    team_barrier();
    {
      int offset = 0, slot = 0;
      for (int u = 0; u < t; ++u) {
        offset += run_sums[size_t(u)].particles;
        slot += run_sums[size_t(u)].nonempty;
      }
      for (int q = q0; q < q1; ++q) {
        c->patch.patch_start[q] = offset;
        int total = 0;
        for (int u = 0; u < T; ++u) {
          int& n = count_of(u, q);
          const int here = n;
          n = offset + total;
          total += here;
        }
        c->patch.patch_slot[q] = total > 0 ? slot++ : -1;
        offset += total;
      }
      if (t == T - 1) {
        c->patch.patch_start[npatch] = offset;
        nslot = slot;
      }
    }
    team_barrier();
    for (int i = lo; i < hi; ++i) {
      const int p = particle(i), q = patch(p);
      if (q >= 0) c->patch.patch_part[cnt[q]++] = p;
    }
  };
  if (team == 1) {  // no team to meet (one_thread, patch_loops.hpp)
    bin(outside);
  } else {
    std::vector<int> outside_of(static_cast<size_t>(team), 0);
    team_region([&] { bin(outside_of[size_t(team_thread())]); });
    for (int n : outside_of) outside += n;
  }
  c->patch.nslot = nslot;
  c->out.noutside = outside;
}
