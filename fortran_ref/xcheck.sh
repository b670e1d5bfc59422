#!/bin/sh
# Cross-language checks of the Fortran reference (used by fortran_ref/tests.cmake).
#
#   xcheck.sh KIND OUT DECK MPM3D MPM3D_REF H5DIFF STEPS [MPM3D OPTIONS...]
#
# KIND
#   kernels  state of `mpm3d` (C++ stages) against `mpm3d OPTIONS` (e.g. --kernel fortran,
#            --kernels p2g=fortran) after STEPS steps: identical bits (plain h5diff), and
#            the same energies, momentum, bounding box, ... in the --summary files.
#   ref      state of `mpm3d` against the Fortran program `mpm3d_ref` after STEPS steps,
#            and the same energies, external-work bound and momentum (mpm3d --summary,
#            mpm3d_ref --energies).
#   regrid   `mpm3d OPTIONS` against `mpm3d_ref OPTIONS` (e.g. --regrid-every 5): the same
#            states and the same adaptive-grid windows at the same steps (the 'regrid step K
#            window ...' lines both print).
#   rules    a rule setting (OPTIONS: --rules ..., --rule NAME=VALUE): `mpm3d OPTIONS` on 1 and
#            2 threads, with every stage from Fortran, and `mpm3d_ref OPTIONS` write the same
#            state after STEPS steps, and that state differs from the plain run's (the
#            setting does something).
#   init     `mpm3d --steps 0 --state` against `mpm3d_ref --init-state` (the two readers).
#   crlf     as init, on a copy of DECK with CRLF line ends and tabs for blanks.
#   unstable DECK with 'dtscale 0.9' (USL decks diverge): both programs must stop at the
#            same step with status 3 (health check) and write the same state.
#   detect   h5diff must see the difference between the states after 0 and 1 steps
#            (guards against a comparison that passes vacuously).
#   refuse   both programs must refuse (exit status 1, naming the same line) decks made
#            from DECK by adding unsupported or bad cards before 'endi'.
# Exit status 77 (skipped) when DECK does not exist.
set -u
kind=$1 out=$2 deck=$3 mpm3d=$4 ref=$5 h5diff=$6 steps=$7
shift 7
if [ ! -f "$deck" ]; then
  echo "deck $deck not found: skipped"
  exit 77
fi
mkdir -p "$(dirname "$out")"
a="$out.a.h5"
b="$out.b.h5"
rm -f "$a" "$b"
# The deterministic lines of a summary JSON (no clock times, no thread counts).
summary_lines() {
  grep -E '"(particles|steps|time|dt_min|dt_max|kinetic_energy|internal_energy|initial_total_energy|external_work|momentum|bbox_min|bbox_max|max_epeff|particles_outside_grid)":' "$1"
}
# "key v [v v]" lines of the energies in a summary JSON (the order of mpm3d_ref --energies).
summary_energies() {
  summary_lines "$1" | grep -E '"(kinetic_energy|internal_energy|initial_total_energy|external_work|momentum)"' |
    sed 's/[]",:[]/ /g'
}
run() {
  echo "+ $*"
  "$@" || { echo "command failed with status $?"; exit 1; }
}
case $kind in
  kernels)
    run "$mpm3d" --threads 1 --steps "$steps" --no-output --quiet --state "$a" --summary "$a.json" "$deck"
    run "$mpm3d" --steps "$steps" --no-output --quiet "$@" --state "$b" --summary "$b.json" "$deck"
    summary_lines "$a.json" > "$a.sum"
    summary_lines "$b.json" > "$b.sum"
    if ! diff "$a.sum" "$b.sum"; then
      echo "the summaries differ"
      exit 1
    fi
    ;;
  ref)
    run "$mpm3d" --threads 1 --steps "$steps" --no-output --quiet --state "$a" --summary "$a.json" "$deck"
    run "$ref" --quiet --steps "$steps" --state "$b" --energies "$b.txt" "$deck"
    summary_energies "$a.json" > "$a.txt"
    cat "$a.txt" "$b.txt"
    # Numerical comparison of the exact decimal forms (%.17g and ES25.16): equal doubles.
    if ! paste "$a.txt" "$b.txt" | awk '
        NF % 2 != 0 || $1 != $(NF / 2 + 1) { bad = 1; next }
        { n = NF / 2; for (i = 2; i <= n; i++) if ($i + 0 != $(i + n) + 0) bad = 1 }
        END { if (NR != 5) bad = 1; exit bad }'; then
      echo "the energies differ"
      exit 1
    fi
    ;;
  regrid)
    run "$mpm3d" --threads 2 --steps "$steps" --no-output "$@" --state "$a" "$deck" > "$a.log"
    run "$ref" --steps "$steps" "$@" --state "$b" "$deck" > "$b.log"
    grep '^regrid step' "$a.log" | cut -d' ' -f1-9 > "$a.win"
    grep '^regrid step' "$b.log" | cut -d' ' -f1-9 > "$b.win"
    cat "$b.win"
    if [ ! -s "$a.win" ] || ! diff "$a.win" "$b.win"; then
      echo "the regrid windows differ (or there were none)"
      exit 1
    fi
    ;;
  rules)
    run "$mpm3d" --threads 1 --steps "$steps" --no-output --quiet "$@" --state "$a" "$deck"
    run "$mpm3d" --threads 2 --steps "$steps" --no-output --quiet "$@" --state "$b" "$deck"
    run "$h5diff" "$a" "$b"
    run "$mpm3d" --threads 2 --kernel fortran --steps "$steps" --no-output --quiet "$@" --state "$b" "$deck"
    run "$h5diff" "$a" "$b"
    run "$ref" --quiet --steps "$steps" "$@" --state "$b" "$deck"
    run "$h5diff" "$a" "$b"
    run "$mpm3d" --threads 1 --steps "$steps" --no-output --quiet --state "$b" "$deck"
    if "$h5diff" -q "$a" "$b"; then
      echo "the rule setting $* changed nothing in $steps steps"
      exit 1
    fi
    echo "the same state in every run under $*; it differs from the plain run's"
    exit 0
    ;;
  init)
    run "$mpm3d" --threads 1 --steps 0 --no-output --quiet --state "$a" "$deck"
    run "$ref" --quiet --steps 0 --init-state "$b" "$deck"
    ;;
  crlf)
    d="$out.crlf.mpm"
    sed 's/ /\t/g; s/$/\r/' "$deck" > "$d"
    run "$mpm3d" --threads 1 --steps 0 --no-output --quiet --state "$a" "$d"
    run "$ref" --quiet --steps 0 --init-state "$b" "$d"
    ;;
  unstable)
    d="$out.unstable.mpm"
    sed 's/^dtscale .*/dtscale 0.9/' "$deck" > "$d"
    echo "+ $mpm3d --threads 1 --steps $steps ... $d"
    "$mpm3d" --threads 1 --steps "$steps" --no-output --quiet --state "$a" "$d"
    sc=$?
    echo "+ $ref --steps $steps ... $d"
    "$ref" --quiet --steps "$steps" --state "$b" "$d"
    sf=$?
    echo "exit status: mpm3d $sc, mpm3d_ref $sf (3 expected)"
    [ $sc -eq 3 ] && [ $sf -eq 3 ] || exit 1
    ;;
  detect)
    run "$ref" --quiet --steps 0 --init-state "$a" "$deck"
    run "$mpm3d" --threads 1 --steps 1 --no-output --quiet --state "$b" "$deck"
    "$h5diff" -q "$a" "$b"
    st=$?
    echo "h5diff status $st (1 expected: the states differ)"
    [ $st -eq 1 ] || exit 1
    exit 0
    ;;
  refuse)
    bad=0
    n=0
    while IFS= read -r card; do
      n=$((n + 1))
      d="$out.refuse$n.mpm"
      rm -rf "$d"
      if [ "$card" = "NO-ENDI" ]; then
        sed '/^endi/d' "$deck" > "$d"
      elif [ "$card" = "LONG-LINE" ]; then
        { cat "$deck"; printf '!%05000d\n' 0; } > "$d"
      elif [ "$card" = "BINARY" ]; then
        sed "s/^endi/dcell 0\x01.5\nendi/" "$deck" > "$d"
      elif [ "$card" = "DIRECTORY" ]; then
        mkdir -p "$d"
      elif [ "$card" = "MISSING" ]; then
        :
      else
        sed "s/^endi/$card\\nendi/" "$deck" > "$d"
      fi
      "$mpm3d" --steps 1 --no-output --quiet "$d" > "$d.cxx.log" 2>&1
      sc=$?
      "$ref" --quiet --steps 1 "$d" > "$d.ref.log" 2>&1
      sf=$?
      echo "[$card] mpm3d $sc: $(head -c 200 "$d.cxx.log" | tr '\n' ' ')"
      echo "[$card] mpm3d_ref $sf: $(head -c 200 "$d.ref.log" | tr '\n' ' ')"
      if [ $sc -ne 1 ] || [ $sf -ne 1 ]; then
        echo "  both programs must refuse this deck with status 1"
        bad=1
      fi
      # ... and name the same line.
      lc=$(grep -o -m1 'mpm:[0-9]*:' "$d.cxx.log" | head -n1)
      lf=$(grep -o -m1 'mpm:[0-9]*:' "$d.ref.log" | head -n1)
      if [ "$lc" != "$lf" ]; then
        echo "  the programs name different lines ('$lc' and '$lf')"
        bad=1
      fi
    done <<'CARDS'
bulk -1.5 0.06
cont lagr -0.1 0
cont lagr 0.1 3
cont pena 0.1 0
deto 0.0 0.0 abc
mate 2 hiex 1.6d-3 6930.0
mate 2 hiex 1.6d-3
mate 2 hiex 1.6d-3 -6930.0
mate 2 null 1.0d-3 1500.0
mate 2 dpm 2.0d-3 10.0 0.3 -0.5 0.0 0.0 0.0
seos 1 3 1.0 2.0 3.0 4.0 5.0 6.0
seos 1 7 1.0
dcell abc
dtscale 3.0
nbmp 12
fixe 0 0 3 0 0 0
velo node 1 1.0 2.0 3.0 endx
adgr -1
frobnicate
dcell 1.0 2.0
dcell 1.0-3
dcell 1e400
dcell 1e
dcell 1e+
dcell 1.5.
dcell 0x10
dcell -
dcell NaN
nbmp 1.0
NO-ENDI
LONG-LINE
BINARY
DIRECTORY
MISSING
CARDS
    exit $bad
    ;;
  *)
    echo "unknown check '$kind'"
    exit 2
    ;;
esac
echo "+ $h5diff $a $b"
"$h5diff" "$a" "$b"
st=$?
[ $st -eq 0 ] && echo "identical"
exit $st
