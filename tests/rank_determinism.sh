#!/usr/bin/env bash
# Bit-for-bit results for any ranks x threads (docs/DESIGN.md, MPI): runs DECK on one
# process with one thread, then under mpirun at each RANKSxTHREADS of CONFIGS (default
# 2x1 3x1 4x1 2x2), and compares the final states with h5diff (no tolerance); with a
# reference program given, its state must match too. The ranks run oversubscribed on a small
# machine (--oversubscribe, no binding): this checks the bits, not the speed. Exit 77
# (skipped) when the deck is absent, or mpirun (tests/mpirun_setup.sh).
# Arguments from the first one starting with -- on are options of every run (mpm3d and
# mpm3d_ref), e.g. --patch-cells 2; those after a word 'ranks:' of the mpirun runs only.
# usage: rank_determinism.sh MPM3D MPIRUN DECK STEPS WORKDIR [MPM3D_REF|none [CONFIGS...] [OPTIONS...] [ranks: OPTIONS...]]
set -euo pipefail
mpm3d=$1; mpirun=$2; deck=$3; steps=$4; work=$5; ref=${6:-}
[ "$ref" != none ] || ref=  # 'none': no reference program
shift $(( $# < 6 ? $# : 6 ))
configs=()
while [ $# -gt 0 ] && [ "${1#--}" = "$1" ] && [ "$1" != ranks: ]; do configs+=("$1"); shift; done
opts=(); rank_opts=()
while [ $# -gt 0 ] && [ "$1" != ranks: ]; do opts+=("$1"); shift; done
if [ $# -gt 0 ]; then shift; rank_opts=("$@"); fi
[ ${#configs[@]} -gt 0 ] || configs=(2x1 3x1 4x1 2x2)
[ -f "$deck" ] || { echo "deck $deck absent: skipped"; exit 77; }
source "$(dirname "$0")/mpirun_setup.sh"
rm -rf "$work"; mkdir -p "$work"
run=(--steps "$steps" --no-output --quiet "${opts[@]}")
"$mpm3d" --threads 1 "${run[@]}" --state "$work/1x1.h5" --summary "$work/1x1.json" "$deck"
# The summary's figures of the run (energies, momentum, external work, bounding box...), to
# the last bit (printed with 17 digits); not its timings, its thread or rank counts.
figures() {
  grep -E '"(particles|steps|time|kinetic_energy|internal_energy|initial_total_energy|external_work|work_of_loads|energy_balance|momentum|bbox_min|bbox_max|max_epeff|contact_force|contact_nodes|particles_outside_grid|patches_empty|patch_max_particles|regrids|regrids_forced|grid_window_offset|grid_window_cells)"' "$1"
}
for rt in "${configs[@]}"; do
  r=${rt%x*}; t=${rt#*x}
  timeout 600 "$mpirun" --oversubscribe --bind-to none -np "$r" "$mpm3d" --threads "$t" "${run[@]}" "${rank_opts[@]}" \
    --state "$work/$rt.h5" --summary "$work/$rt.json" "$deck"
  grep -q "\"ranks\": $r," "$work/$rt.json" || { echo "$rt: the summary does not report $r ranks"; exit 1; }
  h5diff "$work/1x1.h5" "$work/$rt.h5" || { echo "$rt differs from one rank, one thread"; exit 1; }
  diff <(figures "$work/1x1.json") <(figures "$work/$rt.json") || { echo "$rt: the summary's figures differ"; exit 1; }
done
if [ -n "$ref" ] && [ -x "$ref" ]; then
  "$ref" --steps "$steps" "${opts[@]}" --state "$work/ref.h5" "$deck" > /dev/null
  h5diff "$work/1x1.h5" "$work/ref.h5" || { echo "mpm3d_ref differs"; exit 1; }
fi
# Sanity: the run moved the particles (so equal files are not trivially equal).
"$mpm3d" --steps 0 --no-output --quiet "${opts[@]}" --state "$work/t0.h5" "$deck"
if h5diff -q "$work/t0.h5" "$work/1x1.h5" > /dev/null; then echo "state did not change"; exit 1; fi
echo "identical bits at ranks x threads ${configs[*]}, one process${ref:+ and mpm3d_ref} after $steps steps"
