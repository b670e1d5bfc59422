#!/bin/sh
# Rule pressure_q, which acts on the output variable pres only: usage rules_pressure.sh MPM3D
# DECK OUT (DECK with bulk viscosity and a 'curv pres' column). The curve files of runs with
# pressure_q=in and =out are equal in every column but the pressure's, which differs.
set -u
mpm3d=$1 deck=$2 out=$3
stem=$(basename "$deck" .mpm)
rm -rf "$out" && mkdir -p "$out/in" "$out/out" || exit 1
"$mpm3d" --threads 2 --quiet --steps 200 --out-dir "$out/in" --rule pressure_q=in "$deck" || exit 1
"$mpm3d" --threads 2 --quiet --steps 200 --out-dir "$out/out" --rule pressure_q=out "$deck" || exit 1
awk 'NR == FNR { a[FNR] = $0; next }
     FNR == 1 { for (i = 1; i <= NF; i++) if ($i ~ /^pres/) pc = i; if (!pc) { print "no pres column"; bad = 1 }; next }
     { n = split(a[FNR], x); for (i = 1; i <= NF; i++) { if (i == pc) { if (x[i] != $i) dp++ } else if (x[i] != $i) { print "column " i " differs at row " FNR; bad = 1 } } }
     END { if (!dp) { print "the pressure column is the same under both values"; bad = 1 }
           else print dp " rows of the pressure column differ, every other column equal"; exit bad }' \
    "$out/in/${stem}_curv.dat" "$out/out/${stem}_curv.dat"
