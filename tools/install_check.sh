#!/usr/bin/env bash
# The plain CMake recipe of README ("Without root or without Debian"), as a user would run
# it, with GoogleTest hidden: configure must say that the GoogleTest suites are left out,
# mpm3d and the installed pieces must build, `cmake --install` into a temporary prefix must
# give bin/mpm3d, the library, the Fortran module and the CMake package, and the installed
# mpm3d must run a deck. Called by .ci/run; usage: tools/install_check.sh [JOBS]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${1:-$(nproc)}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake -S . -B "$tmp/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$tmp/prefix" \
      -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON > "$tmp/configure.log"
grep -q "GoogleTest not found" "$tmp/configure.log" || {
  cat "$tmp/configure.log"; echo "install_check: configure did not say GoogleTest is missing"; exit 1; }
cmake --build "$tmp/build" -j "$jobs" --target mpm3d mpm3d_capi mpm3d_fortran > "$tmp/build.log" ||
  { tail -30 "$tmp/build.log"; exit 1; }
cmake --install "$tmp/build" > "$tmp/install.log"
for f in bin/mpm3d bin/mpm3d-compare include/mpm3d/mpm3d_api.mod; do
  [ -e "$tmp/prefix/$f" ] || { echo "install_check: $f not installed"; exit 1; }
done
ls "$tmp"/prefix/lib*/libmpm3d* > /dev/null && ls "$tmp"/prefix/lib*/cmake/*/MPM3DConfig.cmake > /dev/null
"$tmp/prefix/bin/mpm3d" --version
"$tmp/prefix/bin/mpm3d" --steps 20 --quiet --out-dir "$tmp/run" --summary "$tmp/run/summary.json" \
  inputs/impact/two_blocks.mpm
grep -q '"steps": 20' "$tmp/run/summary.json" || { echo "install_check: the installed mpm3d did not run"; exit 1; }
echo "install_check: configured without GoogleTest, built, installed into a temporary prefix, ran a deck"
