#!/usr/bin/env bash
# Checkpoints across rank counts (docs/ARCHITECTURE.md, "Ranks (MPI)"): a checkpoint written
# by 2 ranks after STEPS1 steps is the file one process writes (h5diff, no tolerance);
# continued to STEPS2 on 3 ranks, on one process, and from one process's checkpoint on 2
# ranks, the final state is that of an uninterrupted one-process run. Exit 77 (skipped)
# when mpirun cannot start (tests/mpirun_setup.sh).
# usage: rank_restart.sh MPM3D MPIRUN DECK STEPS1 STEPS2 WORKDIR [OPTIONS...] (options of every run)
set -euo pipefail
mpm3d=$1; mpirun=$2; deck=$3; steps1=$4; steps2=$5; work=$6
shift 6
[ -f "$deck" ] || { echo "deck $deck absent: skipped"; exit 77; }
source "$(dirname "$0")/mpirun_setup.sh"
rm -rf "$work"; mkdir -p "$work"
run=(--no-output --quiet "$@")
ranks() { local n=$1; shift; timeout 600 "$mpirun" --oversubscribe --bind-to none -np "$n" "$mpm3d" --threads 1 "$@"; }
"$mpm3d" --threads 1 "${run[@]}" --steps "$steps2" --state "$work/whole.h5" "$deck"
"$mpm3d" --threads 1 "${run[@]}" --steps "$steps1" --checkpoint "$work/one.ckpt.h5" "$deck"
ranks 2 "${run[@]}" --steps "$steps1" --checkpoint "$work/two.ckpt.h5" "$deck"
h5diff "$work/one.ckpt.h5" "$work/two.ckpt.h5" || { echo "the 2-rank checkpoint differs from one process's"; exit 1; }
ranks 3 "${run[@]}" --steps "$steps2" --restart "$work/two.ckpt.h5" --state "$work/two_three.h5" "$deck"
h5diff "$work/whole.h5" "$work/two_three.h5" || { echo "2 ranks then 3 differ from the uninterrupted run"; exit 1; }
"$mpm3d" --threads 2 "${run[@]}" --steps "$steps2" --restart "$work/two.ckpt.h5" --state "$work/two_one.h5" "$deck"
h5diff "$work/whole.h5" "$work/two_one.h5" || { echo "2 ranks then one process differ from the uninterrupted run"; exit 1; }
ranks 2 "${run[@]}" --steps "$steps2" --restart "$work/one.ckpt.h5" --state "$work/one_two.h5" "$deck"
h5diff "$work/whole.h5" "$work/one_two.h5" || { echo "one process then 2 ranks differ from the uninterrupted run"; exit 1; }
# Sanity: the second part changed the state.
"$mpm3d" --threads 1 "${run[@]}" --steps "$steps1" --state "$work/half.h5" "$deck"
if h5diff -q "$work/half.h5" "$work/whole.h5" > /dev/null; then echo "state did not change after the checkpoint"; exit 1; fi
echo "checkpoints of 1 and 2 ranks identical after $steps1 steps; 2->3, 2->1, 1->2 ranks identical to one run at $steps2"
