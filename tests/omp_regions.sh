#!/usr/bin/env bash
# The parallel regions of one step (docs/PERFORMANCE.md, "Many threads"): every region is a
# fork and a join of the whole team, a fixed cost per step that grows with the thread count,
# so a new one should be a decision, not an accident. Counted with the LD_PRELOAD counter
# tools/omp_regions.c: the set-up's regions from a run of 0 steps, then those of a run of N
# steps that leaves the set-up's out, on a MUSL trilinear deck without contact: binning,
# P2G scatter, P2G assembly, integration, G2P, remap assembly, node velocities, stress
# update, energies, health check = 10 a step, at any thread count.
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
  [ "$setup" -gt 0 ] || { echo "no region counted in the set-up"; exit 1; }
  [ "$regions" -eq $(( 10 * steps )) ] || { echo "expected 10 parallel regions a step, counted $regions in $steps steps"; exit 1; }
done
