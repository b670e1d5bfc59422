// The threads of the C++ stages' parallel loops (patch_loops.hpp): the calling thread and
// persistent workers that wait for the next loop by spinning, then sleep. An OpenMP
// parallel region costs a fork and a join of the team; on the 2-core machine 3.4 us,
// against 0.4 us for a meeting on one shared cache line (docs/PERFORMANCE.md, "Threads that
// pay"), and a small deck's step is ten such loops of 10-50 us each. The thread count is
// still OpenMP's (omp_get_max_threads: --threads, OMP_NUM_THREADS and the time loop's
// per-step choice); the Fortran reference stages keep their OpenMP regions.
#pragma once

namespace mpm3d {

// fn(arg) on `threads` threads at once, the caller being thread 0; returns when every one
// has returned. Inside it, team_thread() and team_size() give each its place; a call from
// inside one runs fn(arg) on the calling thread alone, as a nested OpenMP region would.
// fn must not throw.
void team_run(int threads, void (*fn)(void*), void* arg);

// Every thread of the running team_run waits here for the others (nothing outside one).
void team_barrier();

// The calling thread's number in its team_run and the team's size (0 and 1 outside one).
int team_thread();
int team_size();

// team_run calls with more than one thread by the calling thread since it started, and the
// wall time it spent in them (the regions-a-step test, tests/omp_regions.sh; the serial part
// of a step, tools/bench.py).
long team_runs();
double team_seconds();

}  // namespace mpm3d
