#!/usr/bin/env bash
# Bounded libFuzzer run of the deck reader (`make fuzz [FUZZ_TIME=seconds]`).
#   tools/fuzz.sh [SECONDS] [BUILD_DIR]
# Builds tests/fuzz/fuzz_deck.cpp with clang (-fsanitize=fuzzer,address,undefined) and the
# reader, grid and solver sources (no OpenMP, one core), then fuzzes for SECONDS (default
# 600) seeded with the repository decks (inputs/, tests/decks, fortran_ref/testdecks,
# tests/fuzz_regressions) and ../shared/decks when present - read where they lie, never
# copied into the repository. The grown corpus and any crash/timeout/leak/oom inputs go
# to BUILD_DIR (default build-fuzz): corpus/ and artifacts/. Exit status 1 when the run
# left any artifact.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_TO_RUN=${1:-600}
OUT=${2:-build-fuzz}
CXX=${FUZZ_CXX:-clang++}
mkdir -p "$OUT/corpus" "$OUT/artifacts"
HDF5_INC=$(pkg-config --cflags hdf5 2>/dev/null || echo -I/usr/include/hdf5/serial)
HDF5_LIB=$(pkg-config --libs hdf5 2>/dev/null || echo -lhdf5_serial)
SRC="cxx/input/ffi.cpp cxx/input/data_in.cpp cxx/input/data_in_cards.cpp cxx/input/data_in_finish.cpp cxx/input/particle_gen.cpp cxx/input/output_variables.cpp cxx/core/particle.cpp cxx/core/grid.cpp cxx/materials/material.cpp cxx/materials/material_models.cpp cxx/materials/constitution.cpp
     cxx/stages/stages.cpp cxx/stages/stage_bin.cpp cxx/stages/stage_p2g.cpp cxx/stages/stage_grid.cpp cxx/stages/stage_g2p.cpp cxx/stages/stage_stress.cpp
     cxx/stages/stage_energy.cpp cxx/transfer/assembly.cpp cxx/transfer/trilinear.cpp cxx/transfer/stencil27.cpp
     cxx/transfer/smoothed_gradient.cpp cxx/io/data_out.cpp cxx/solver/simulation.cpp cxx/io/analysis.cpp"
BIN="$OUT/fuzz_deck"
newest=$(ls -t $SRC cxx/*.hpp cxx/*/*.hpp tests/fuzz/fuzz_deck.cpp "$0" | head -1)
if [ ! -x "$BIN" ] || [ "$newest" -nt "$BIN" ]; then
  echo "building $BIN"
  # shellcheck disable=SC2086
  $CXX -std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
    -ffp-contract=off -Wno-unknown-pragmas -Icxx $(pkg-config --cflags eigen3 2>/dev/null || echo -I/usr/include/eigen3) \
    $HDF5_INC tests/fuzz/fuzz_deck.cpp $SRC $HDF5_LIB -o "$BIN"
fi
SEEDS=()
for d in inputs tests/decks fortran_ref/testdecks tests/fuzz_regressions ../shared/decks; do
  [ -d "$d" ] && SEEDS+=("$d")
done
echo "fuzzing for $SECONDS_TO_RUN s, seeds: ${SEEDS[*]}"
# -fork=1: crashes, timeouts and OOMs are recorded and the run goes on; leaks are checked.
set +e
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ASAN_OPTIONS=detect_leaks=1 \
"$BIN" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
  -max_total_time="$SECONDS_TO_RUN" -timeout=20 -rss_limit_mb=2048 -max_len=8192 \
  -dict=tools/fuzz_deck.dict -artifact_prefix="$OUT/artifacts/" -print_final_stats=1 \
  "$OUT/corpus" "${SEEDS[@]}" 2>&1 | tee "$OUT/fuzz.log" | grep -E "^#|ERROR|FINDING|SUMMARY|stat::|INFO: fuzzed|crash|timeout" | tail -n 40
set -e
n=$(find "$OUT/artifacts" -type f | wc -l)
echo "corpus: $(find "$OUT/corpus" -type f | wc -l) inputs; artifacts (crash/timeout/leak/oom): $n in $OUT/artifacts"
[ "$n" -eq 0 ]
