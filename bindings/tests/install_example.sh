#!/usr/bin/env bash
# Installs the built project into a temporary prefix, moves the prefix (the installation
# must be relocatable), then builds and runs against it, as a user would:
#   - the out-of-tree example docs/examples/fortran_driver (find_package(MPM3D));
#   - a C program and the Fortran driver built by hand with pkg-config flags;
#   - the installed mpm3d program.
#   install_example.sh CMAKE BUILD_DIR SOURCE_DIR WORKDIR CONFIG Fortran_COMPILER C_COMPILER
set -euo pipefail
cmake=$1 build=$2 src=$3 work=$4 config=$5 fc=$6 cc=$7
example=$src/docs/examples/fortran_driver
deck=$example/block.mpm

rm -rf "$work"
mkdir -p "$work"
cd "$work"
log=$work/log.txt
run() { # run a step quietly, show its output on failure
  if ! "$@" >>"$log" 2>&1; then
    echo "FAIL: $*"
    tail -40 "$log"
    exit 1
  fi
}

echo "== install into a staging prefix, then move it"
run "$cmake" --install "$build" --prefix "$work/stage" ${config:+--config "$config"}
mv "$work/stage" "$work/prefix"
prefix=$work/prefix
for f in include/mpm3d.h bin/mpm3d; do
  [[ -e $prefix/$f ]] || { echo "FAIL: $f not installed"; exit 1; }
done
for f in libmpm3d.so mpm3d_api.mod MPM3DConfig.cmake MPM3DConfigVersion.cmake MPM3DTargets.cmake mpm3d.pc \
         mpm3d-fortran.pc; do
  [[ -n $(find "$prefix" -name "$f") ]] || { echo "FAIL: $f not installed"; exit 1; }
done
if grep -rl --include='*.cmake' --include='*.pc' -e "$build" "$prefix"; then
  echo "FAIL: these installed package files refer to the build tree"
  exit 1
fi
if grep -q "mpm3d_core" "$(find "$prefix" -name MPM3DTargets.cmake)"; then
  echo "FAIL: the exported targets mention the internal mpm3d_core"
  exit 1
fi
run "$prefix/bin/mpm3d" --version

echo "== find_package(MPM3D): configure, build and run docs/examples/fortran_driver"
run "$cmake" -S "$example" -B "$work/example" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_Fortran_COMPILER="$fc" \
    -DCMAKE_BUILD_TYPE=Release
run "$cmake" --build "$work/example"
"$work/example/driver" "$deck" 40 | tee driver.txt
grep -Eq '^ +40 ' driver.txt || { echo "FAIL: the driver did not reach step 40"; exit 1; }
"$work/example/driver" "$work/missing.mpm" 10 >missing.txt 2>&1 && { echo "FAIL: no error for a missing deck"; exit 1; }
grep -q "missing.mpm" missing.txt || { echo "FAIL: the driver's error does not name the deck"; cat missing.txt; exit 1; }

echo "== pkg-config"
export PKG_CONFIG_PATH=$(dirname "$(find "$prefix" -name mpm3d.pc)")
flags=$(pkg-config --cflags --libs mpm3d)
echo "pkg-config --cflags --libs mpm3d: $flags"
[[ $flags == *-lmpm3d* && $flags == *-I* ]] || { echo "FAIL: unexpected pkg-config flags"; exit 1; }
[[ $(pkg-config --modversion mpm3d) == "$("$prefix/bin/mpm3d" --version | awk '{print $NF}')" ]] ||
  { echo "FAIL: pkg-config version differs from the program's"; exit 1; }
libdir=$(pkg-config --variable=libdir mpm3d)
# shellcheck disable=SC2086
run "$cc" -std=c99 -Wall -Werror "$src/bindings/tests/pkgconfig_smoke.c" -o smoke_c $(pkg-config --cflags --libs mpm3d)
LD_LIBRARY_PATH=$libdir ./smoke_c "$deck"
# shellcheck disable=SC2086
run "$fc" "$example/driver.f90" -o driver_pc $(pkg-config --cflags --libs mpm3d-fortran)
LD_LIBRARY_PATH=$libdir ./driver_pc "$deck" 5 | tail -1
echo "OK: installed package works with find_package and pkg-config"
