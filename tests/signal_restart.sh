#!/usr/bin/env bash
# A signal mid-run (docs/RELIABILITY.md): SIGTERM or SIGINT sent to a running mpm3d once it
# has printed a progress line makes it finish the step, write a checkpoint and exit with
# 128 + the signal number; restarting from that checkpoint ends bit-identical to an
# uninterrupted run. Exit 77 (skipped) when the deck is absent.
# usage: signal_restart.sh MPM3D DECK STEPS WORKDIR TERM|INT
set -euo pipefail
mpm3d=$1; deck=$2; steps=$3; work=$4; sig=$5
[ -f "$deck" ] || { echo "deck $deck absent: skipped"; exit 77; }
rm -rf "$work"; mkdir -p "$work/out"
# A progress line at every step.
sed -e 's/^ *rpt[a-z]* .*$//' -e 's/^ *endi.*$/rpttime 1.0d-12\nendi/' "$deck" > "$work/sig.mpm"
"$mpm3d" --quiet --threads 1 --steps "$steps" --no-output --state "$work/full.h5" "$work/sig.mpm"
ck=()
[ "$sig" = INT ] && ck=(--checkpoint "$work/given.h5")
"$mpm3d" --threads 1 --steps "$steps" --out-dir "$work/out" "${ck[@]}" "$work/sig.mpm" \
  > "$work/stdout.txt" 2> "$work/stderr.txt" &
pid=$!
until grep -q '^step' "$work/stdout.txt" 2>/dev/null; do
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.02
done
kill -s "$sig" "$pid" 2>/dev/null || true
rc=0; wait "$pid" || rc=$?
want=$([ "$sig" = INT ] && echo 130 || echo 143)
[ "$rc" = "$want" ] || { echo "exit status $rc, expected $want"; cat "$work/stderr.txt"; exit 1; }
ckpt=$([ "$sig" = INT ] && echo "$work/given.h5" || echo "$work/out/sig_checkpoint.h5")
[ -f "$ckpt" ] || { echo "no checkpoint $ckpt"; exit 1; }
ls "$work" "$work/out" | grep -q '\.tmp$' && { echo "temporary file left behind"; exit 1; }
grep -q "interrupted by SIG$sig at step" "$work/stderr.txt" || { echo "no message"; cat "$work/stderr.txt"; exit 1; }
at=$(h5dump -a /simulation/step "$ckpt" | sed -n 's/^ *(0): \([0-9]*\)$/\1/p')
[ -n "$at" ] && [ "$at" -ge 1 ] && [ "$at" -lt "$steps" ] || { echo "checkpoint at step '$at' (run of $steps)"; exit 1; }
"$mpm3d" --quiet --threads 2 --steps "$steps" --no-output --restart "$ckpt" --state "$work/restarted.h5" "$work/sig.mpm"
h5diff "$work/full.h5" "$work/restarted.h5" || { echo "restarted run differs"; exit 1; }
echo "SIG$sig at step $at of $steps: checkpoint written, exit $rc; the restart matches bit for bit"
