#!/usr/bin/env bash
# Nothing lost on a failure (docs/RELIABILITY.md, "Result files"):
# - kill: the run is killed (SIGKILL) right after its second progress line, which mpm3d
#   prints after handing the report to the files; name.out must hold both report lines and
#   EnergyPlot.dat and name_curv.dat a row for every step up to the second report.
# - full: one result file is on a full device (a link to /dev/full): the run must stop with
#   status 1 and a message naming that file.
# usage: output_loss.sh MPM3D DECK kill|full [FILE]
set -u
exe=$1 deck=$2 mode=$3 file=${4:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
name=$(basename "$deck"); name=${name%.*}

case "$mode" in
kill)
  coproc RUN { exec "$exe" --threads 1 --out-dir "$work" "$deck" 2>/dev/null; }
  pid=$RUN_PID
  reports=0 last_step=-1
  while IFS= read -r line <&"${RUN[0]}"; do
    if [[ $line =~ ^step\ +([0-9]+) ]]; then
      reports=$((reports + 1)); last_step=${BASH_REMATCH[1]}
      if [ "$reports" -ge 2 ]; then kill -9 "$pid"; break; fi
    fi
  done
  wait "$pid" 2>/dev/null
  rc=$?
  if [ "$reports" -lt 2 ]; then echo "FAIL: the run printed $reports progress lines before it ended (rc $rc)"; exit 1; fi
  if [ "$rc" -ne 137 ]; then echo "FAIL: the run was not killed (rc $rc)"; exit 1; fi
  in_out=$(grep -c '^step ' "$work/$name.out")
  # EnergyPlot.dat: one row per step from step 1; name_curv.dat: a header, then the same.
  energy_rows=$(wc -l < "$work/EnergyPlot.dat")
  curve_rows=$(($(wc -l < "$work/${name}_curv.dat") - 1))
  echo "killed after step $last_step: $in_out report lines in $name.out, $energy_rows rows in EnergyPlot.dat, $curve_rows in ${name}_curv.dat"
  [ "$in_out" -ge 2 ] || { echo "FAIL: $name.out lost reported lines"; exit 1; }
  [ "$energy_rows" -ge "$last_step" ] || { echo "FAIL: EnergyPlot.dat lost reported steps"; exit 1; }
  [ "$curve_rows" -ge "$last_step" ] || { echo "FAIL: ${name}_curv.dat lost reported steps"; exit 1; }
  ;;
full)
  [ -w /dev/full ] || { echo "no /dev/full: skipped"; exit 77; }
  ln -s /dev/full "$work/$file"
  "$exe" --threads 1 --quiet --out-dir "$work" "$deck" >/dev/null 2>"$work/err"
  rc=$?
  cat "$work/err"
  [ "$rc" -eq 1 ] || { echo "FAIL: status $rc, expected 1"; exit 1; }
  grep -q "cannot write $work/$file" "$work/err" || { echo "FAIL: the message does not name $file"; exit 1; }
  # The files before the failure keep what they held: the log's head is in name.out.
  if [ "$file" != "$name.out" ]; then
    grep -q . "$work/$name.out" || { echo "FAIL: $name.out lost its lines"; exit 1; }
  fi
  ;;
*) echo "unknown mode $mode"; exit 2 ;;
esac
echo PASS
