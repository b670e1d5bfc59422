/* OpenMP parallel regions of a program, counted from outside it (make bench, tools/bench.py).
 *
 * Loaded with LD_PRELOAD into a program built with GCC's OpenMP, it stands in front of
 * libgomp's GOMP_parallel, the entry of every `#pragma omp parallel` (and `parallel for`,
 * whatever the schedule), and sums the regions and the wall time spent inside them, leaving
 * out the first OMP_REGIONS_SKIP regions (default 0: the set-up's, whose first one also
 * starts the thread pool). At exit it writes "regions seconds_inside" to the file named by
 * OMP_REGIONS_OUT (stderr without it). A run of 0 steps gives the set-up's regions; a run of
 * N steps that skips them gives the regions per step and, with the step loop's time, the
 * time a step spends outside every parallel region: the serial part that bounds the
 * speedup at many threads (Amdahl), measurable on any core count.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

typedef void (*gomp_parallel_fn)(void (*)(void*), void*, unsigned, unsigned);

static long regions, skip = -1;
static double seconds_inside;

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags) {
  static gomp_parallel_fn real;
  if (!real) real = (gomp_parallel_fn)dlsym(RTLD_NEXT, "GOMP_parallel");
  if (!real) {
    fputs("omp_regions: GOMP_parallel not found (not a libgomp program?)\n", stderr);
    abort();
  }
  if (skip < 0) {
    const char* s = getenv("OMP_REGIONS_SKIP");
    skip = s ? atol(s) : 0;
  }
  if (skip > 0) {
    --skip;
    real(fn, data, num_threads, flags);
    return;
  }
  const double t0 = now();
  real(fn, data, num_threads, flags);
  seconds_inside += now() - t0;
  ++regions;
}

__attribute__((destructor)) static void report(void) {
  const char* path = getenv("OMP_REGIONS_OUT");
  FILE* f = path ? fopen(path, "w") : stderr;
  if (!f) return;
  fprintf(f, "%ld %.9f\n", regions, seconds_inside);
  if (f != stderr) fclose(f);
}
