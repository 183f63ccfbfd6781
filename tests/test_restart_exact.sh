#!/usr/bin/env bash
# Issue 18 item 1: a resumed run writes exactly the snapshots, statistics
# lines and final state of the uninterrupted run, bit for bit with
# Scheduler:deterministic and one thread.  Sod (periodic), snapshots every
# 0.01 to 0.06; the run is stopped by --steps at several steps (before,
# between and after snapshots), resumed each time with --restart, and every
# snapshot and the statistics file are compared with the straight run
# (tests/restart_compare.py).
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}
S=$(cd "$(dirname "$0")" && pwd)
PY=${PYTHON:-python3}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$B/bolide-ic" sod --nx 16 --size 2,1,1 -o sod.hdf5 >/dev/null
cat >p.yml <<'YML'
InitialConditions:
  file_name: sod.hdf5
  periodic: true
TimeIntegration:
  time_end: 0.06
  dt_max: 0.002
Snapshots:
  subdir: A
  delta_time: 0.01
Scheduler:
  deterministic: true
Restarts:
  enable: true
  subdir: A/restart
YML
fail=0
"$B/bolide" -t 1 p.yml >a.log 2>&1 || { echo "FAIL: uninterrupted run"; tail -3 a.log; exit 1; }
steps=$(awk 'NF == 6 && $1 ~ /^[0-9]+$/ {n = $1} END {print n}' a.log)
echo "uninterrupted run: $steps steps, $(ls A/*.hdf5 | wc -l) snapshots"
# stop at a few steps, resume each time from the last stop
set -- -P Snapshots:subdir:B -P Restarts:subdir:B/restart
"$B/bolide" -t 1 -n 3 "$@" p.yml >b0.log 2>&1 || { echo "FAIL: first part"; tail -3 b0.log; exit 1; }
k=0
for n in 7 12 20 -1; do
  k=$((k + 1))
  if [ "$n" -lt 0 ]; then opt=(); else opt=(-n "$n"); fi
  "$B/bolide" -t 1 --restart "${opt[@]}" "$@" p.yml >b$k.log 2>&1 || { echo "FAIL: resumed run $k"; tail -3 b$k.log; exit 1; }
done
grep -q "resumed from" b1.log || { echo "FAIL: no resume message"; fail=1; }
"$PY" "$S/restart_compare.py" A B || fail=1
exit $fail
