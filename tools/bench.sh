#!/usr/bin/env bash
# make bench: ns per particle-step, speedup and parallel efficiency at 1..N threads on the
# Taylor decks (and the elastic-only twin of the coarse one), with the adaptive grid off
# and on, measured side by side in one run (tools/bench.py);
# peak memory per particle from /usr/bin/time -v; the Fortran reference program's serial
# speed; the plots of tools/bench_plot.py. Writes docs/bench/{bench,reference}.csv and
# docs/bench/{speedup,efficiency}.png and prints the tables.
# usage: tools/bench.sh BUILD_DIR [max_threads] [decks...]
# environment: see tools/bench.py (BENCH_STEPS, BENCH_REPEATS, BENCH_REGRID, BENCH_ROUNDS,
# BENCH_FINE); BENCH_OUT (default docs/bench) for a trial run that keeps the committed files.
set -euo pipefail
build=$1; shift
maxt=${1:-$(nproc)}; [ $# -gt 0 ] && shift
decks=("$@")
steps=${BENCH_STEPS:-100}
repeats=${BENCH_REPEATS:-3}
outdir=${BENCH_OUT:-docs/bench}
mkdir -p "$outdir"
# Debian's python3 (python3-matplotlib is a Debian package; another python3 earlier on PATH
# may not see it).
py=python3
[ -x /usr/bin/python3 ] && py=/usr/bin/python3
csv=$outdir/bench.csv
echo "load before the bench: $(cat /proc/loadavg) (timings need a 1-minute load well below 1)"
"$py" tools/bench.py "$build" "$csv" "$maxt" ${decks[@]+"${decks[@]}"}
if [ ${#decks[@]} -eq 0 ]; then
  decks=(inputs/taylor/taylor_coarse.mpm inputs/taylor/taylor_medium.mpm)
  [ -f ../shared/decks/Taylor.mpm ] && decks=(../shared/decks/Taylor.mpm "${decks[@]}")
fi
# Serial speed of the Fortran reference program next to the C++ one: (t(N steps) - t(0
# steps)) / (particles * N), so the deck reading is left out, as in mpm3d's own figure;
# the best over the repeats, each pinned to every CPU in turn (the CPUs of a virtual
# machine may run at different speeds for minutes).
if [ -x "$build/fortran_ref/mpm3d_ref" ]; then
  pins=("")
  if command -v taskset > /dev/null; then
    pins=()
    for ((k = 0; k < $(nproc); ++k)); do pins+=("taskset -c $k"); done
  fi
  ref_csv=$outdir/reference.csv
  echo "deck,particles,steps,mpm3d_ref_ns_per_particle_step,mpm3d_1thread_ns_per_particle_step,ratio" > "$ref_csv"
  for deck in "${decks[@]}"; do
    best=""
    for ((r = 0; r < repeats; ++r)); do
      for pin in "${pins[@]}"; do  # pinned to each CPU in turn, as mpm3d's 1-thread time
        t0=$(date +%s.%N); $pin "$build/fortran_ref/mpm3d_ref" --steps 0 "$deck" > /dev/null; t1=$(date +%s.%N)
        $pin "$build/fortran_ref/mpm3d_ref" --steps "$steps" "$deck" > /dev/null; t2=$(date +%s.%N)
        d=$(awk -v a="$t0" -v b="$t1" -v c="$t2" 'BEGIN{print (c - b) - (b - a)}')
        if [ -z "$best" ] || awk "BEGIN{exit !($d < $best)}"; then best=$d; fi
      done
    done
    # The 1-thread row without the adaptive grid.
    np=$(awk -F, -v d="$(basename "$deck")" '$1 == d && $3 == 0 && $4 == 1 {print $2}' "$csv")
    cx=$(awk -F, -v d="$(basename "$deck")" '$1 == d && $3 == 0 && $4 == 1 {print $6}' "$csv")
    awk -v d="$(basename "$deck")" -v np="$np" -v s="$steps" -v t="$best" -v cx="$cx" \
      'BEGIN{ns=t*1e9/(np*s); printf "%s,%d,%d,%.1f,%.1f,%.2f\n", d, np, s, ns, cx, ns/cx}' >> "$ref_csv"
  done
  column -s, -t < "$ref_csv"
fi
# MPI ranks against threads (issue 17): 1x1, 1x2 and 2x1 side by side on the coarse and
# medium Taylor models, when mpm3d is built with MPI.
if command -v mpirun > /dev/null && ldd "$build/cxx/mpm3d" | grep -q libmpi; then
  "$py" tools/rank_bench.py "$build" "$outdir/ranks.csv" --rounds "${BENCH_ROUNDS:-5}" --steps "$steps" \
    inputs/taylor/taylor_coarse.mpm inputs/taylor/taylor_medium.mpm
fi
# Every public deck against the original programs (issue 36), when the user names them:
# BENCH_MPM3D_F90 (a checkout of the public MPM3D-F90, for its decks), BENCH_BOOK and
# BENCH_CURRENT (its programs at commits 2284feb and 4a6275f, built outside this repository);
# with BENCH_NEWEST (the newest program, commit 17fd4ee) also the newest decks (37 runs).
if [ -n "${BENCH_MPM3D_F90:-}" ] && [ -n "${BENCH_BOOK:-}" ] && [ -n "${BENCH_CURRENT:-}" ]; then
  "$py" tools/every_deck_speed.py "$build" --repo "$BENCH_MPM3D_F90" --book "$BENCH_BOOK" \
    --current "$BENCH_CURRENT" --rounds "${BENCH_ROUNDS:-3}" --csv "$outdir/every_deck.csv" \
    ${BENCH_NEWEST:+--newest "$BENCH_NEWEST"}
fi
"$py" tools/bench_plot.py "$csv" "$outdir"
column -s, -t < "$csv"
