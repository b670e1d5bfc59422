#!/bin/sh
# The newest public MPM3D-F90's 3D landslide decks (311,550 particles, 9.9 MB each) are not
# kept anywhere: the shared folder's make_landslide_decks.py writes them byte for byte.
#   newest_landslide.sh NEWEST_DIR OUT_DIR NAME COMMAND...
# writes OUT_DIR/{BS,GIMP,SG}.mpm once (when NAME.mpm is missing), then runs COMMAND.
# Exit 77 (skipped) when NEWEST_DIR or its script is absent.
set -u
newest=$1 out=$2 name=$3
shift 3
script="$newest/make_landslide_decks.py"
if [ ! -f "$script" ]; then
  echo "$script absent: skipped"
  exit 77
fi
if [ ! -f "$out/$name.mpm" ]; then
  mkdir -p "$out" && python3 "$script" "$out" > /dev/null || exit 1
fi
exec "$@"
