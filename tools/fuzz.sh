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
# The core library's sources (cxx/CMakeLists.txt's mpm3d_core: every unit of these folders),
# found here rather than listed, so that a new unit cannot leave the fuzzer unlinkable; the
# *_avx2 units with -mavx2 as in the CMake build, the C step table with clang; one at a time
# (about a minute and a half), so that the first failing unit stops the script.
SRC=$(ls cxx/{core,materials,transfer,stages,input,io,solver}/*.cpp)
BIN="$OUT/fuzz_deck"
OBJ="$OUT/obj"
newest=$(ls -t $SRC cxx/*/*.hpp cxx/stages/step_order.[ch] tests/fuzz/fuzz_deck.cpp "$0" | head -1)
if [ ! -x "$BIN" ] || [ "$newest" -nt "$BIN" ]; then
  echo "building $BIN"
  rm -rf "$OBJ"; mkdir -p "$OBJ"
  FLAGS="-g -O1 -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -ffp-contract=off"
  INC="-Icxx $(pkg-config --cflags eigen3 2>/dev/null || echo -I/usr/include/eigen3) $HDF5_INC"
  ${FUZZ_CC:-clang} $FLAGS -Icxx -c cxx/stages/step_order.c -o "$OBJ/step_order.o"
  for f in $SRC tests/fuzz/fuzz_deck.cpp; do
    case "$f" in *_avx2.cpp) isa=-mavx2 ;; *) isa= ;; esac
    # shellcheck disable=SC2086
    $CXX -std=c++17 $FLAGS $isa -Wno-unknown-pragmas $INC -c "$f" -o "$OBJ/$(echo "$f" | tr / _).o"
  done
  # shellcheck disable=SC2086
  $CXX -fsanitize=fuzzer,address,undefined "$OBJ"/*.o $HDF5_LIB -lpthread -o "$BIN"
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
