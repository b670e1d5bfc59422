#!/usr/bin/env bash
# make run: runs a deck into out/NAME (NAME: the deck's file name without its extension,
# wherever the deck lives); for a Taylor bar deck (file name or title with "taylor") it then
# prints the final length and impact-end diameter next to the paper's (Huang et al.,
# MPM3DMP) and the experiment's (Johnson & Cook 1983).
# usage: tools/taylor_run.sh BUILD_DIR DECK [extra mpm3d options]
set -euo pipefail
build=$1; deck=$2; shift 2
name=$(basename "$deck"); name=${name%.*}
out=${OUT_DIR:-out/$name}
mkdir -p "$out"
"$build/cxx/mpm3d" --out-dir "$out" --summary "$out/summary.json" --state "$out/state.h5" "$@" "$deck"
title=$(grep -v '^[[:space:]]*\(!\|$\)' "$deck" | head -1 || true)
if ! printf '%s %s' "$name" "$title" | grep -qi taylor; then
  printf 'results in %s/\n' "$out"
  exit 0
fi
# Particle spacing: from the deck's cyli card, else from the run's dcell / 2.
dp=$(awk 'tolower(substr($1,1,4))=="part" && tolower(substr($2,1,4))=="cyli" {print $6; exit}' "$deck")
[ -n "$dp" ] || dp=$(awk 'tolower(substr($1,1,4))=="dcel" {print $2/2; exit}' "$deck")
read -r _ L _ D _ W < <("$build/cxx/mpm3d_taylor" "$out/state.h5" "$dp")
printf '\nTaylor bar at the end of the run (particle-centre extent plus one spacing, dp = %s mm):\n' "$dp"
printf '  %-34s %8s %8s\n' "" "L (mm)" "D (mm)"
printf '  %-34s %8.2f %8.2f\n' "this run" "$L" "$D"
printf '  %-34s %8s %8s\n' "paper, MPM3DMP (coarse..fine)" "16.3-16.5" "13.4-13.6"
printf '  %-34s %8s %8s\n' "experiment (Johnson & Cook 1983)" "16.2" "13.5"
printf 'results in %s/\n' "$out"
