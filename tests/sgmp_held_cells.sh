#!/bin/sh
# sgmp with particles in a held lower face's first cell (inputs/hyperelastic/block_floor_sgmp.mpm:
# the block's first layers along x and z): both readers refuse it under our rules with the same
# message at the sgmp card's line, naming the faces and the cell to add; under the original's
# rule (sg_lower=truncate) both run it and warn with the same text.
# usage: sgmp_held_cells.sh MPM3D MPM3D_REF DECK WORKDIR (MPM3D_REF "": mpm3d alone)
set -u
mpm3d=$1 ref=$2 deck=$3 out=$4
mkdir -p "$out" && cd "$out" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
if [ -z "$ref" ]; then  # a build without the Fortran reference: mpm3d stands for both
  ref=$mpm3d
fi
"$mpm3d" --steps 1 --no-output --quiet "$deck" > cxx.log 2>&1; sc=$?
"$ref" --quiet --steps 1 "$deck" > ref.log 2>&1; sf=$?
cat cxx.log ref.log
[ $sc -eq 1 ] && [ $sf -eq 1 ] || fail "both programs must refuse the deck (status 1): mpm3d $sc, mpm3d_ref $sf"
want="block_floor_sgmp.mpm:23: 128 particles lie in the first cell along x, between the two node layers sgmp holds at the symmetric lower x face, which keep them from moving along x: add one cell outside that face (lower the first value of spx by dcel); 128 particles lie in the first cell along z, between the two node layers sgmp holds at the fixed lower z face, which keep them still: add one cell outside that face (lower the first value of spz by dcel), as the current MPM3D-F90's ChangeLog asks for sgmp; --rule sg_lower=truncate (in --rules original) runs the deck as that program does"
grep -qF "$want" cxx.log || fail "mpm3d's message is not the expected one"
sed 's/^mpm3d: //' cxx.log > cxx.msg
sed 's/^mpm3d_ref: //; s/^mpm3d: //' ref.log > ref.msg
cmp -s cxx.msg ref.msg || fail "the two readers' messages differ"
"$mpm3d" --steps 2 --no-output --quiet --rule sg_lower=truncate "$deck" > cxx2.log 2>&1 || fail "mpm3d refused it under sg_lower=truncate"
"$ref" --quiet --steps 2 --rule sg_lower=truncate "$deck" > ref2.log 2>&1 || fail "mpm3d_ref refused it under sg_lower=truncate"
cat cxx2.log ref2.log
grep -q "warning: 128 particles lie in the first cell along x" cxx2.log || fail "mpm3d gives no warning"
grep -q "warning: 128 particles lie in the first cell along x" ref2.log || fail "mpm3d_ref gives no warning"
echo "refused by both readers alike under our rules; warned and run under sg_lower=truncate"
