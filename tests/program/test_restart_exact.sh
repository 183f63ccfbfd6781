#!/usr/bin/env bash
# Issue 18 item 1: a resumed run writes exactly the snapshots, statistics
# lines and final state of the uninterrupted run, bit for bit with
# Scheduler:deterministic and one thread.  Sod (periodic), snapshots every
# 0.01 to 0.06; the run is stopped by --steps at several steps (before,
# between and after snapshots), resumed each time with --restart, and every
# snapshot and the statistics file are compared with the straight run
# (tests/helpers/restart_compare.py).
# Then the same with self-gravity and Gravity:reuse_steps > 0 (Evrard
# collapse, 912 particles): a step that reuses the far field of the
# last full evaluation must do so after a resume too (the positions, lists,
# multipoles and local expansions of that evaluation are in the file), so
# the resumed run repeats the uninterrupted one bit for bit.  On the CPU
# (--no-gpu): a GPU run keeps its far field on the device and does not save
# it, and its gravity sums are not reproducible to the bit anyway.
# Then the gravity case in individual time steps (time bins), and Sod with
# the rk2 and pc integrators.
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}
H=$(cd "$(dirname "$0")/../helpers" && pwd) # restart_compare.py
PY=${PYTHON:-python3}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"

# resume WHAT "N1 N2 ... -1" ARGS...: resume from the restart file of the
# part before with --restart, stopping at each step count N (-1: to the end),
# bolide's other arguments ARGS; logs b1.log, b2.log, ...
resume() {
  local what=$1 stops=$2 k=0 n
  shift 2
  for n in $stops; do
    k=$((k + 1))
    if [ "$n" -lt 0 ]; then opt=(); else opt=(-n "$n"); fi
    "$B/bolide" -t 1 --restart "${opt[@]}" "$@" p.yml >b$k.log 2>&1 || { echo "FAIL: resumed $what $k"; tail -3 b$k.log; exit 1; }
  done
}
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
resume "run" "7 12 20 -1" "$@"
grep -q "resumed from" b1.log || { echo "FAIL: no resume message"; fail=1; }
"$PY" "$H/restart_compare.py" A B || fail=1
# resumed from the file written at the end of the finished run (a run killed
# after it, before it exited): nothing to do, and no statistics line added
# (once, the closing line came twice: test_restart_kill.sh caught it at
# random)
"$B/bolide" -t 1 --restart "$@" p.yml >b9.log 2>&1 || { echo "FAIL: resumed at the end"; tail -3 b9.log; exit 1; }
"$PY" "$H/restart_compare.py" A B || { echo "FAIL: resumed at the end: the outputs changed"; fail=1; }

# self-gravity with the far field reused (Gravity:reuse_steps 4, a loose
# reuse_tolerance so that most steps reuse it)
mkdir grav && cd grav
"$PY" "${BOLIDE_SRCDIR:?}/examples/EvrardCollapse/make_ic.py" 12 evrard.hdf5 >/dev/null
sed -e 's/^  time_end: 3.0/  time_end: 0.16/' -e 's/^  delta_time: 0.5/  delta_time: 0.04\n  subdir: A/' \
  "$BOLIDE_SRCDIR/examples/EvrardCollapse/params.yml" >p.yml
cat >>p.yml <<'YML'
  reuse_steps: 4
  reuse_tolerance: 0.1
Scheduler:
  deterministic: true
Restarts:
  enable: true
  subdir: A/restart
YML
"$B/bolide" --no-gpu -t 1 p.yml >a.log 2>&1 || { echo "FAIL: uninterrupted gravity run"; tail -3 a.log; exit 1; }
steps=$(awk 'NF == 6 && $1 ~ /^[0-9]+$/ {n = $1} END {print n}' a.log)
reused=$(sed -n 's/.*gravity: \([0-9]*\) of [0-9]* steps reused.*/\1/p' a.log)
echo "uninterrupted gravity run: $steps steps, ${reused:-0} reused the far field, $(ls A/*.hdf5 | wc -l) snapshots"
[ "${reused:-0}" -gt 0 ] || { echo "FAIL: no step reused the far field (test set-up)"; exit 1; }
set -- --no-gpu -P Snapshots:subdir:B -P Restarts:subdir:B/restart
"$B/bolide" -t 1 -n 2 "$@" p.yml >b0.log 2>&1 || { echo "FAIL: first part (gravity)"; tail -3 b0.log; exit 1; }
resume "gravity run" "5 7 11 14 -1" "$@"
grep -q "resumed from" b1.log || { echo "FAIL: no resume message (gravity)"; fail=1; }
"$PY" "$H/restart_compare.py" A B || { echo "FAIL: the resumed run with Gravity:reuse_steps differs"; fail=1; }

# individual time steps (TimeIntegration:global_step: false): the particles'
# bins and the integer time are in the file; a resumed run takes the same
# steps with the same particles active
cd .. && mkdir bins && cd bins
cp ../grav/evrard.hdf5 ../grav/p.yml .
set -- --no-gpu -P TimeIntegration:global_step:false -P Gravity:reuse_steps:0
"$B/bolide" -t 1 "$@" p.yml >a.log 2>&1 || { echo "FAIL: uninterrupted run in bins"; tail -3 a.log; exit 1; }
steps=$(awk 'NF == 6 && $1 ~ /^[0-9]+$/ {n = $1} END {print n}' a.log)
echo "uninterrupted run in bins: $steps steps, $(ls A/*.hdf5 | wc -l) snapshots"
set -- "$@" -P Snapshots:subdir:B -P Restarts:subdir:B/restart
"$B/bolide" -t 1 -n 3 "$@" p.yml >b0.log 2>&1 || { echo "FAIL: first part (bins)"; tail -3 b0.log; exit 1; }
resume "run in bins" "6 9 13 -1" "$@"
"$PY" "$H/restart_compare.py" A B || { echo "FAIL: the resumed run in time bins differs"; fail=1; }

# the Runge-Kutta 2 and predictor-corrector integrators (TimeIntegration:
# scheme, theory/integrators.md): the evaluation of a step's end is the
# next step's first stage, and rk2's next step (its error control) is the
# file's next time step; Sod as above
for scheme in rk2 pc; do
  cd "$work" && mkdir "$scheme" && cd "$scheme"
  cp ../sod.hdf5 ../p.yml .
  set -- -P TimeIntegration:scheme:$scheme
  # (rk2: a tolerance that its error control meets with shorter steps than
  # dt_max and rejected steps: 55 steps instead of 31, 12 taken again)
  [ "$scheme" = rk2 ] && set -- "$@" -P TimeIntegration:rk2_tolerance:1e-6
  "$B/bolide" -t 1 "$@" p.yml >a.log 2>&1 || { echo "FAIL: uninterrupted run ($scheme)"; tail -3 a.log; exit 1; }
  steps=$(awk 'NF == 6 && $1 ~ /^[0-9]+$/ {n = $1} END {print n}' a.log)
  echo "uninterrupted run ($scheme): $steps steps, $(ls A/*.hdf5 | wc -l) snapshots"
  set -- "$@" -P Snapshots:subdir:B -P Restarts:subdir:B/restart
  "$B/bolide" -t 1 -n 3 "$@" p.yml >b0.log 2>&1 || { echo "FAIL: first part ($scheme)"; tail -3 b0.log; exit 1; }
  resume "run ($scheme)" "7 12 20 -1" "$@"
  "$PY" "$H/restart_compare.py" A B || { echo "FAIL: the resumed run with scheme $scheme differs"; fail=1; }
done
exit $fail
