#!/bin/sh
# A restart keeps the rules of the run it continues: usage rules_restart.sh MPM3D DECK OUT.
# A checkpoint written under --rules original continues under the same rules bit for bit
# (the state equals an uninterrupted run's); asked to continue under other rules, mpm3d
# refuses with exit status 1 and names both.
set -u
mpm3d=$1 deck=$2 out=$3
rm -rf "$out" && mkdir -p "$out" || exit 1
"$mpm3d" --threads 2 --quiet --no-output --rules original --steps 8 --checkpoint "$out/c.h5" "$deck" || exit 1
"$mpm3d" --threads 2 --quiet --no-output --rules original --steps 16 --state "$out/whole.h5" "$deck" || exit 1
"$mpm3d" --threads 2 --quiet --no-output --rules original --steps 16 --restart "$out/c.h5" --state "$out/cont.h5" "$deck" || exit 1
cmp "$out/whole.h5" "$out/cont.h5" || { echo "the continued run differs from the whole run"; exit 1; }
"$mpm3d" --threads 2 --quiet --no-output --steps 16 --restart "$out/c.h5" "$deck" 2> "$out/err.txt"
rc=$?
cat "$out/err.txt"
[ $rc -eq 1 ] || { echo "exit status $rc, expected 1"; exit 1; }
grep -q "written under the rules '.*', the run asks for '.*' (give the same --rules and --rule options)" "$out/err.txt" ||
  { echo "no message naming both rule sets"; exit 1; }
echo "restart under the same rules: the same state; under others: refused"
