#!/usr/bin/env bash
# Renders docs/examples/taylor_pvd.png and taylor_xdmf.png (tools/paraview_examples.py): the
# coarse Taylor bar of `make run` with 'para' added, run with --hdf5 to 24 microseconds,
# opened in ParaView (pvbatch under xvfb-run; Debian: paraview python3-paraview xvfb).
# usage: tools/paraview_examples.sh BUILD_DIR [OUT_DIR (default docs/examples)]
set -euo pipefail
build=$1; out=${2:-docs/examples}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sed 's/^endi/para\nendi/' "$here/../inputs/taylor/taylor_coarse.mpm" > "$work/taylor.mpm"
"$build/cxx/mpm3d" --quiet --hdf5 --end-time 0.024 --out-dir "$work" "$work/taylor.mpm"
mkdir -p "$out"
xvfb-run -a pvbatch "$here/paraview_examples.py" "$work" "$(cd "$out" && pwd)"
ls -l "$out"/taylor_pvd.png "$out"/taylor_xdmf.png
