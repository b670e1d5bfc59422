// What a meeting of the threads costs (docs/PERFORMANCE.md, "Threads that pay"): an empty
// OpenMP parallel region (a fork and a join of libgomp's team), an OpenMP barrier, and the
// same two with the stages' team (cxx/core/team_pool.hpp): an empty team_run and a
// team_barrier. Microseconds each, the median of 5 passes of 20,000.
// usage: mpm3d_team_cost [THREADS]   (default: OpenMP's thread count)
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/team_pool.hpp"

namespace {

constexpr int kReps = 20000, kPasses = 5;

template <class F>
double median_us(F&& pass) {
  std::vector<double> t;
  for (int k = 0; k < kPasses; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    pass();
    t.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / kReps);
  }
  std::sort(t.begin(), t.end());
  return t[kPasses / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : omp_get_max_threads();
  volatile int sink = 0;
  const double omp_region = median_us([&] {
    for (int i = 0; i < kReps; ++i) {
#pragma omp parallel num_threads(threads)
      sink = sink + 0;
    }
  });
  const double omp_barrier = median_us([&] {
#pragma omp parallel num_threads(threads)
    for (int i = 0; i < kReps; ++i) {
#pragma omp barrier
    }
  });
  auto nothing = [](void*) {};
  const double team_run = median_us([&] {
    for (int i = 0; i < kReps; ++i) mpm3d::team_run(threads, nothing, nullptr);
  });
  const double team_barrier = median_us([&] {
    mpm3d::team_run(threads, [](void*) {
      for (int i = 0; i < kReps; ++i) mpm3d::team_barrier();
    }, nullptr);
  });
  std::printf("threads %d: OpenMP region %.2f us, OpenMP barrier %.2f us, team_run %.2f us, team_barrier %.2f us\n",
              threads, omp_region, omp_barrier, team_run, team_barrier);
  return 0;
}
