#!/usr/bin/env bash
# The thread team's meetings in one step (docs/PERFORMANCE.md, "Threads that pay"): every
# parallel loop of a stage is a hand-over to the team and a wait for all of it, a fixed cost
# per step that grows with the thread count, so a new one should be a decision, not an
# accident. On a MUSL trilinear deck without contact: binning, P2G scatter, P2G assembly,
# integration, G2P, remap assembly, node velocities, stress update, energies, health check
# = 10 a step on 2 or more threads; none on one thread, where the stages call their loop
# bodies directly. The team's loops are counted by mpm3d itself (the summary's
# team.regions: the set-up's from a run of 0 steps, then a run of N steps), and none of
# them may be an OpenMP parallel region (a fork and a join of the team: 3.4 us against 0.4
# us on the 2-core machine), counted from outside with the LD_PRELOAD counter
# tools/omp_regions.c.
# usage: omp_regions.sh MPM3D COUNTER.so DECK WORKDIR
set -euo pipefail
mpm3d=$1; counter=$2; deck=$3; work=$4
rm -rf "$work"; mkdir -p "$work"
steps=12
regions_of() { python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["team"]["regions"])' "$1"; }
for t in 1 2 3; do
  OMP_REGIONS_OUT="$work/omp$t.0" LD_PRELOAD="$counter" "$mpm3d" --threads "$t" --team fixed --steps 0 \
    --no-output --quiet --summary "$work/s$t.0.json" "$deck"
  OMP_REGIONS_OUT="$work/omp$t.$steps" LD_PRELOAD="$counter" "$mpm3d" --threads "$t" --team fixed --steps "$steps" \
    --no-output --quiet --summary "$work/s$t.$steps.json" "$deck"
  setup=$(regions_of "$work/s$t.0.json"); total=$(regions_of "$work/s$t.$steps.json")
  read -r omp_setup _ < "$work/omp$t.0"
  read -r omp_total _ < "$work/omp$t.$steps"
  regions=$(( total - setup ))
  echo "threads $t: $setup team loops in the set-up, $regions in $steps steps; OpenMP regions: $omp_setup, $omp_total"
  [ "$t" -eq 1 ] || [ "$setup" -gt 0 ] || { echo "no team loop counted in the set-up"; exit 1; }
  want=$(( t == 1 ? 0 : 10 * steps ))
  [ "$regions" -eq "$want" ] || { echo "expected $want team loops in $steps steps on $t threads, counted $regions"; exit 1; }
  [ "$omp_total" -eq 0 ] || { echo "expected no OpenMP parallel region, counted $omp_total"; exit 1; }
done
