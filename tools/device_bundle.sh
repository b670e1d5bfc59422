#!/usr/bin/env bash
# Packs what a lent many-core machine needs to run this machine's build (docs/PERFORMANCE.md,
# "Many cores"): such a machine has neither this project's Debian libraries nor ../shared,
# and reaches no package registry. Writes .devpack/ in the repository root (ignored by git):
#   bundle.tar.xz  bin/ (mpm3d, mpm3d_ref, h5diff, and ORIGINAL_EXE when given, as
#                  bin/original), lib/ (every shared library they need but glibc's), and
#                  shared/ (the current decks, the current references' EnergyPlot.dat and
#                  Taylor.mpm, copied from ../shared for that machine's runs only: never
#                  commit them);
#   env.sh         to source there first, from the repository root: unpacks the bundle to
#                  /tmp/mpm3d_bundle, sets PATH and LD_LIBRARY_PATH, points ../shared at the
#                  copy, and, where the machine has an Open MPI of its own (libmpi.so.40),
#                  uses it and its newer libstdc++ instead of the carried ones; OMPI's
#                  run-as-root settings for the benchmark drivers.
# Then, for instance (carry .devpack):
#   source .devpack/env.sh && python3 tools/scaling.py $MPM3D_BUILD out.csv Taylor.mpm
#   source .devpack/env.sh && python3 tools/current_speed.py $MPM3D_BUILD $MPM3D_BIN/original \
#       --threads 1,2,4,8,16
#   source .devpack/env.sh && python3 tools/rank_bench.py $MPM3D_BUILD ranks.csv \
#       --configs 1x1,1x16,16x1,4x4 inputs/taylor/taylor_medium.mpm
# usage: tools/device_bundle.sh BUILD_DIR [ORIGINAL_EXE]
set -euo pipefail
build=$(cd "$1" && pwd)
original=${2:-}
root=$(cd "$(dirname "$0")/.." && pwd)
shared=$(cd "$root/.." && pwd)/shared
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/bin" "$stage/lib" "$stage/shared/decks" "$stage/shared/reference/current"
cp "$build/cxx/mpm3d" "$build/fortran_ref/mpm3d_ref" "$stage/bin/"
cp "$(command -v h5diff)" "$stage/bin/"
[ -z "$original" ] || cp "$original" "$stage/bin/original"
ldd "$stage"/bin/* 2>/dev/null | awk '/=> \//{print $3}' | sort -u | while read -r lib; do
  case $(basename "$lib") in
    libc.so*|libm.so*|libpthread.so*|libdl.so*|librt.so*|ld-linux*|libresolv.so*) ;;
    *) cp -L "$lib" "$stage/lib/" ;;
  esac
done
if [ -d "$shared/decks/current" ]; then
  cp -r "$shared/decks/current" "$stage/shared/decks/"
  for d in "$shared"/reference/current/*/; do
    mkdir -p "$stage/shared/reference/current/$(basename "$d")"
    cp "$d/EnergyPlot.dat" "$stage/shared/reference/current/$(basename "$d")/"
  done
fi
[ -f "$shared/decks/Taylor.mpm" ] && cp "$shared/decks/Taylor.mpm" "$stage/shared/decks/"
mkdir -p "$root/.devpack"
tar cJf "$root/.devpack/bundle.tar.xz" -C "$stage" bin lib shared
cat > "$root/.devpack/env.sh" <<'EOF'
# Sourced on the lent machine from the repository root (tools/device_bundle.sh).
MPM3D_BUNDLE=/tmp/mpm3d_bundle
mkdir -p "$MPM3D_BUNDLE" && tar xJf .devpack/bundle.tar.xz -C "$MPM3D_BUNDLE"
if [ -e /usr/lib/x86_64-linux-gnu/libmpi.so.40 ]; then
  (cd "$MPM3D_BUNDLE/lib" && rm -f libmpi* libopen-* libpmix* libhwloc* libevent* libfabric* libuc* \
     libpsm* libibverbs* librdmacm* libnl-* liboshmem* libstdc++* libgcc_s*)
fi
export LD_LIBRARY_PATH=$MPM3D_BUNDLE/lib PATH=$MPM3D_BUNDLE/bin:$PATH PYTHONUNBUFFERED=1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# The drivers take a build directory: cxx/mpm3d and fortran_ref/mpm3d_ref in it.
export MPM3D_BIN=$MPM3D_BUNDLE/bin MPM3D_BUILD=$MPM3D_BUNDLE/build
mkdir -p "$MPM3D_BUILD/cxx" "$MPM3D_BUILD/fortran_ref"
ln -sf "$MPM3D_BIN/mpm3d" "$MPM3D_BUILD/cxx/mpm3d"
ln -sf "$MPM3D_BIN/mpm3d_ref" "$MPM3D_BUILD/fortran_ref/mpm3d_ref"
[ -e ../shared ] || ln -s "$MPM3D_BUNDLE/shared" ../shared
EOF
du -h "$root/.devpack/bundle.tar.xz"
