#!/usr/bin/env bash
# The C++ library called from Fortran must give the same bits as the mpm3d program.
#   compare_state.sh MPM3D FORTRAN_STATE H5DIFF DECK WORKDIR [NSTEPS [KERNELS]]
# Runs DECK for NSTEPS (60) steps with the Fortran test program (module mpm3d_api ->
# libmpm3d) and with `mpm3d --state`, both with the stage kernels KERNELS ("cxx",
# "fortran" or "stage=lang,..."; default: all C++), then `h5diff` (no tolerance) must
# find nothing. Exits 77 (skip) when the deck is absent or KERNELS needs Fortran kernels
# this build lacks.
set -euo pipefail
mpm3d=$1 fprog=$2 h5diff=$3 deck=$4 work=$5 nsteps=${6:-60} kernels=${7:-}

if [[ ! -x $h5diff ]]; then
  echo "FAIL: h5diff not found ('$h5diff'; Debian package hdf5-tools)"
  exit 1
fi
if [[ ! -f $deck ]]; then
  echo "SKIP: deck $deck not found"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"
cd "$work"

fargs=("$deck" api.h5 "$nsteps") kopt=()
if [[ -n $kernels ]]; then
  fargs+=("$kernels")
  if [[ $kernels == *=* ]]; then kopt=(--kernels "$kernels"); else kopt=(--kernel "$kernels"); fi
fi
set +e
"$fprog" "${fargs[@]}"
rc=$?
set -e
[[ $rc -eq 77 ]] && exit 77
[[ $rc -ne 0 ]] && { echo "FAIL: the Fortran program failed (exit $rc)"; exit 1; }
"$mpm3d" --steps "$nsteps" --no-output --quiet "${kopt[@]}" --state cli.h5 "$deck"

# h5diff compares every dataset and attribute; equal files give exit 0 and no output.
set +e
out=$("$h5diff" cli.h5 api.h5 2>&1)
rc=$?
set -e
if [[ $rc -ne 0 || -n $out ]]; then
  echo "FAIL: the library's state differs from the program's (h5diff exit $rc):"
  echo "$out" | head -40
  "$h5diff" -r cli.h5 api.h5 | head -40 || true
  exit 1
fi

# The comparison is not vacuous: the initial state differs from both.
"$mpm3d" --steps 0 --no-output --quiet --state initial.h5 "$deck"
if "$h5diff" -q initial.h5 api.h5 >/dev/null 2>&1; then
  echo "FAIL: the state after $nsteps steps equals the initial state"
  exit 1
fi
echo "OK: $(basename "$deck"), $nsteps steps${kernels:+, kernels $kernels}: library (from Fortran) == mpm3d program, bit for bit"
