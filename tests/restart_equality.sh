#!/usr/bin/env bash
# Restart equality (docs/RELIABILITY.md): a run checkpointed at step MID and restarted with a
# different thread count ends bit-identical to an uninterrupted run (h5diff of the --state
# files, no tolerance), and its legacy text files (curves, energy, momentum, TecPlot) are the
# same bytes; the HDF5 animation series holds the same frames (h5diff). Exit 77 (skipped) when the deck is absent.
# usage: restart_equality.sh MPM3D DECK STEPS MID WORKDIR [OPTION...]  (options for every run)
set -euo pipefail
mpm3d=$1; deck=$2; steps=$3; mid=$4; work=$5
shift 5
extra=("$@")
[ -f "$deck" ] || { echo "deck $deck absent: skipped"; exit 77; }
rm -rf "$work"; mkdir -p "$work/full" "$work/split"
# Every kind of output on: TecPlot, ParaView, the HDF5 series, curves of two variables.
sed -e 's/^ *endi.*$/tecp\npara\nhdf5\noutr seqv\noutr pres\ncurv velz 1\nendi/' "$deck" > "$work/r.mpm"
deck=$work/r.mpm
"$mpm3d" ${extra[@]+"${extra[@]}"} --quiet --threads 1 --steps "$steps" --out-dir "$work/full" --state "$work/full.h5" "$deck"
"$mpm3d" ${extra[@]+"${extra[@]}"} --quiet --threads 2 --steps "$mid" --out-dir "$work/split" --checkpoint "$work/ck.h5" "$deck"
[ ! -e "$work/ck.h5.tmp" ] || { echo "temporary checkpoint left behind"; exit 1; }
# The checkpoint is at step MID.
h5dump -a /simulation/step "$work/ck.h5" | grep -q "(0): $mid\$" || { echo "checkpoint not at step $mid"; exit 1; }
# The interrupted run went on past the checkpoint (its later rows and frames must not be
# repeated): continue it to a step between MID and STEPS, then restart from MID.
cp "$work/ck.h5" "$work/ck_mid.h5"
"$mpm3d" ${extra[@]+"${extra[@]}"} --quiet --threads 1 --steps $(( (mid + steps) / 2 )) --out-dir "$work/split" --restart "$work/ck.h5" \
         --checkpoint "$work/ck_later.h5" "$deck"
"$mpm3d" ${extra[@]+"${extra[@]}"} --quiet --threads 3 --steps "$steps" --out-dir "$work/split" --restart "$work/ck_mid.h5" \
         --state "$work/restarted.h5" "$deck"
h5diff "$work/full.h5" "$work/restarted.h5" || { echo "restarted run differs"; exit 1; }
for f in "$work"/full/*; do
  n=$(basename "$f")
  case "$n" in
    *.out) continue ;;   # the log notes the restart
    *.h5) h5diff "$f" "$work/split/$n" || { echo "$n differs after the restart"; exit 1; } ;;
    *) cmp "$f" "$work/split/$n" || { echo "$n differs after the restart"; exit 1; } ;;
  esac
done
# Sanity: the run moved the particles after the checkpoint.
"$mpm3d" ${extra[@]+"${extra[@]}"} --quiet --no-output --threads 1 --steps "$mid" --state "$work/mid.h5" "$deck"
if h5diff -q "$work/mid.h5" "$work/full.h5" > /dev/null; then echo "state did not change"; exit 1; fi
echo "restart at step $mid of $steps (2 then 3 threads) == uninterrupted run (1 thread), bit for bit"
