#!/usr/bin/env bash
# The result files of a run on several ranks (issue 17), written by the root: the curves
# (name_curv.dat, EnergyPlot.dat, MomentumPlot.dat, ContforcPlot.dat), the deck's animations
# and the HDF5 series (--hdf5) are byte for byte those of one process; the run log name.out
# has the same step lines (less their time estimates). With RESTART_AT > 0, a run stopped
# there by a 2-rank checkpoint and continued on 3 ranks leaves the same files too. Exit 77
# (skipped) when the deck is absent, or mpirun (tests/mpirun_setup.sh).
# usage: rank_outputs.sh MPM3D MPIRUN DECK STEPS RESTART_AT WORKDIR [CONFIGS...] [OPTIONS...]
set -euo pipefail
mpm3d=$1; mpirun=$2; deck=$3; steps=$4; restart_at=$5; work=$6
shift 6
configs=()
while [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; do configs+=("$1"); shift; done
[ ${#configs[@]} -gt 0 ] || configs=(2x1 3x1)
[ -f "$deck" ] || { echo "deck $deck absent: skipped"; exit 77; }
source "$(dirname "$0")/mpirun_setup.sh"
rm -rf "$work"; mkdir -p "$work"
run=(--quiet --hdf5 "$@")
ranks() { local n=$1; shift; timeout 600 "$mpirun" --oversubscribe --bind-to none -np "$n" "$mpm3d" "$@"; }
# The log's step lines, less the time estimate.
steps_of() { grep '^step' "$1" | sed 's/ *eta.*//'; }
same_files() {  # same_files DIR WHAT: DIR holds the files of $work/1x1, each identical
  local dir=$1 what=$2 f
  diff <(cd "$work/1x1" && ls) <(cd "$dir" && ls | grep -v '_checkpoint\.h5$') ||
    { echo "$what: not the files of one process"; exit 1; }
  for f in $(cd "$work/1x1" && ls); do
    case $f in
      *.out) diff <(steps_of "$work/1x1/$f") <(steps_of "$dir/$f") > /dev/null ||
               { echo "$what: the step lines of $f differ"; exit 1; } ;;
      *) cmp "$work/1x1/$f" "$dir/$f" || { echo "$what: $f differs from one process's"; exit 1; } ;;
    esac
  done
}
"$mpm3d" --threads 1 "${run[@]}" --steps "$steps" --out-dir "$work/1x1" "$deck"
# Sanity: the curves moved (equal files are not trivially equal).
curv=$(ls "$work"/1x1/*_curv.dat)
[ "$(sed -n 2p "$curv" | cut -c13-)" != "$(tail -1 "$curv" | cut -c13-)" ] || { echo "the curves did not change"; exit 1; }
[ -n "$(steps_of "$work"/1x1/*.out)" ] || { echo "no step lines in the log (a shorter --end-time?)"; exit 1; }
for rt in "${configs[@]}"; do
  ranks "${rt%x*}" --threads "${rt#*x}" "${run[@]}" --steps "$steps" --out-dir "$work/$rt" "$deck"
  same_files "$work/$rt" "$rt"
done
if [ "$restart_at" -gt 0 ]; then
  ranks 2 --threads 1 "${run[@]}" --steps "$restart_at" --out-dir "$work/restart" --checkpoint-every "$restart_at" "$deck"
  ranks 3 --threads 1 "${run[@]}" --steps "$steps" --out-dir "$work/restart" \
    --restart "$(ls "$work"/restart/*_checkpoint.h5)" "$deck"
  same_files "$work/restart" "2 ranks to step $restart_at, then 3"
fi
echo "the root's files on ranks x threads ${configs[*]} identical to one process's$([ "$restart_at" -gt 0 ] && echo ", also after a restart on 3 ranks from 2 ranks' checkpoint")"
