#!/usr/bin/env bash
# The parallel regions of one step (docs/PERFORMANCE.md, "Many threads"): every region is a
# fork and a join of the whole team, a fixed cost per step that grows with the thread count,
# so a new one should be a decision, not an accident. Counted with the LD_PRELOAD counter
# tools/omp_regions.c: the set-up's regions from a run of 0 steps, then those of a run of N
# steps that leaves the set-up's out, on a MUSL trilinear deck without contact: binning,
# P2G scatter, P2G assembly, integration, G2P, remap assembly, node velocities, stress
# update, energies, health check = 10 a step on 2 or more threads; none on one thread, where
# the stages call their loop bodies directly (a region's end costs a system call:
# one_thread, cxx/core/patch_loops.hpp).
# usage: omp_regions.sh MPM3D COUNTER.so DECK WORKDIR
set -euo pipefail
mpm3d=$1; counter=$2; deck=$3; work=$4
rm -rf "$work"; mkdir -p "$work"
steps=12
for t in 1 2 3; do
  OMP_REGIONS_OUT="$work/r$t.0" LD_PRELOAD="$counter" "$mpm3d" --threads "$t" --team fixed --steps 0 --no-output --quiet "$deck"
  read -r setup _ < "$work/r$t.0"
  OMP_REGIONS_SKIP=$setup OMP_REGIONS_OUT="$work/r$t.$steps" LD_PRELOAD="$counter" \
    "$mpm3d" --threads "$t" --team fixed --steps "$steps" --no-output --quiet "$deck"
  read -r regions _ < "$work/r$t.$steps"
  echo "threads $t: $setup regions in the set-up, $regions in $steps steps"
  [ "$t" -eq 1 ] || [ "$setup" -gt 0 ] || { echo "no region counted in the set-up"; exit 1; }
  want=$(( t == 1 ? 0 : 10 * steps ))
  [ "$regions" -eq "$want" ] || { echo "expected $want parallel regions in $steps steps on $t threads, counted $regions"; exit 1; }
done
