#!/usr/bin/env bash
# make bench: ns per particle-step, speedup and parallel efficiency at 1..N threads on the
# Taylor decks, measured side by side in one run; peak memory per particle from
# /usr/bin/time -v. Writes docs/bench/bench.csv and prints a table.
# usage: tools/bench.sh BUILD_DIR [max_threads] [decks...]
set -euo pipefail
build=$1; shift
maxt=${1:-$(nproc)}; [ $# -gt 0 ] && shift
decks=("$@")
if [ ${#decks[@]} -eq 0 ]; then
  decks=(inputs/taylor/taylor_coarse.mpm inputs/taylor/taylor_medium.mpm)
  [ -f ../shared/decks/Taylor.mpm ] && decks=(../shared/decks/Taylor.mpm "${decks[@]}")
fi
steps=${BENCH_STEPS:-100}
repeats=${BENCH_REPEATS:-3}
mkdir -p docs/bench
csv=docs/bench/bench.csv
tmp=$(mktemp -d)
echo "deck,particles,threads,steps,ns_per_particle_step,speedup,efficiency,peak_rss_bytes_per_particle,stage_shares" > "$csv"
for deck in "${decks[@]}"; do
  base=""
  for ((t = 1; t <= maxt; t = (t < 2 ? t + 1 : t * 2))); do
    best=""
    for ((r = 0; r < repeats; ++r)); do
      /usr/bin/time -v "$build/cxx/mpm3d" --threads "$t" --steps "$steps" --no-output --quiet \
        --summary "$tmp/s.json" "$deck" > "$tmp/out" 2> "$tmp/time"
      ns=$(sed -n 's/.*"ns_per_particle_step": \([0-9.e+-]*\).*/\1/p' "$tmp/s.json")
      if [ -z "$best" ] || awk "BEGIN{exit !($ns < $best)}"; then
        best=$ns
        rss=$(awk '/Maximum resident set size/ {print $6 * 1024}' "$tmp/time")
      fi
    done
    np=$(sed -n 's/.*"particles": \([0-9]*\).*/\1/p' "$tmp/s.json")
    [ -n "$base" ] || base=$best
    shares=$("$build/cxx/mpm3d" --threads "$t" --steps "$steps" --no-output "$deck" | sed -n 's/^stage shares: //p')
    awk -v d="$(basename "$deck")" -v np="$np" -v t="$t" -v s="$steps" -v ns="$best" -v b="$base" -v rss="$rss" -v sh="$shares" \
      'BEGIN{sp=b/ns; printf "%s,%d,%d,%d,%.1f,%.3f,%.3f,%.0f,%s\n", d, np, t, s, ns, sp, sp/t, rss/np, sh}' >> "$csv"
  done
done
# Serial speed of the Fortran reference program next to the C++ one: (t(N steps) - t(0
# steps)) / (particles * N), so the deck reading is left out, as in mpm3d's own figure.
if [ -x "$build/fortran_ref/mpm3d_ref" ]; then
  ref_csv=docs/bench/reference.csv
  echo "deck,particles,steps,mpm3d_ref_ns_per_particle_step,mpm3d_1thread_ns_per_particle_step,ratio" > "$ref_csv"
  for deck in "${decks[@]}"; do
    best=""
    for ((r = 0; r < repeats; ++r)); do
      t0=$(date +%s.%N); "$build/fortran_ref/mpm3d_ref" --steps 0 "$deck" > /dev/null; t1=$(date +%s.%N)
      "$build/fortran_ref/mpm3d_ref" --steps "$steps" "$deck" > /dev/null; t2=$(date +%s.%N)
      d=$(awk -v a="$t0" -v b="$t1" -v c="$t2" 'BEGIN{print (c - b) - (b - a)}')
      if [ -z "$best" ] || awk "BEGIN{exit !($d < $best)}"; then best=$d; fi
    done
    np=$(awk -F, -v d="$(basename "$deck")" '$1 == d && $3 == 1 {print $2}' "$csv")
    cx=$(awk -F, -v d="$(basename "$deck")" '$1 == d && $3 == 1 {print $5}' "$csv")
    awk -v d="$(basename "$deck")" -v np="$np" -v s="$steps" -v t="$best" -v cx="$cx" \
      'BEGIN{ns=t*1e9/(np*s); printf "%s,%d,%d,%.1f,%.1f,%.2f\n", d, np, s, ns, cx, ns/cx}' >> "$ref_csv"
  done
  column -s, -t < "$ref_csv"
fi
rm -rf "$tmp"
column -s, -t < "$csv"
