#!/bin/sh
# Any path length (the original stopped beyond 80 characters, the newest program beyond 256):
# a deck under a directory path of over 300 characters, with ParaView frames, curves, the
# HDF5 state and a checkpoint written under another such path, read back by a restart; and
# the Fortran program mpm3d_ref on the same deck.
#   long_path.sh MPM3D MPM3D_REF DECK WORKDIR
set -u
mpm3d=$1 ref=$2 deck=$3 work=$4
seg=$(printf 'a%.0s' $(seq 1 60))
dir="$work/$seg/$seg/$seg/$seg/$seg"
out="$dir/results_$(printf 'o%.0s' $(seq 1 40))"
rm -rf "$work" && mkdir -p "$dir" || exit 1
name=deck_with_a_long_name_$(printf 'n%.0s' $(seq 1 40))
long_deck="$dir/$name.mpm"
sed 's/^musl on/musl on\npara/' "$deck" > "$long_deck" || exit 1
echo "deck path: ${#long_deck} characters"
[ ${#long_deck} -gt 300 ] || { echo "the path is not long enough"; exit 1; }
"$mpm3d" --threads 2 --quiet --steps 20 --out-dir "$out" --state "$out/state.h5" \
  --checkpoint "$out/check.h5" "$long_deck" || { echo "mpm3d failed"; exit 1; }
for f in "$name.out" "${name}_curv.dat" EnergyPlot.dat "${name}_anim.pvd" state.h5 check.h5; do
  [ -s "$out/$f" ] || { echo "missing: $out/$f"; exit 1; }
done
ls "$out" | grep -q "^${name}_anim_1.vtu$" || { echo "no ParaView frame"; exit 1; }
"$mpm3d" --threads 2 --quiet --steps 30 --out-dir "$out" --restart "$out/check.h5" "$long_deck" ||
  { echo "restart failed"; exit 1; }
"$ref" --quiet --steps 20 --state "$out/ref.h5" "$long_deck" > /dev/null || { echo "mpm3d_ref failed"; exit 1; }
[ -s "$out/ref.h5" ] || { echo "mpm3d_ref wrote no state"; exit 1; }
echo "paths of ${#long_deck} and ${#out} characters: read, written and restarted"
