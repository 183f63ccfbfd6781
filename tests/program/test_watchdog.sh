#!/usr/bin/env bash
# Issue 18 item 7: the watchdog after every step.  A bad value is injected at
# the end of a step (BOLIDE_TEST_INJECT=STEP:FIELD:VALUE, for tests only):
# NaN and Inf in fields, a negative density, a negative internal energy of an
# ideal gas, and a velocity that moves a particle across more than its cell
# in the next step.  Each stops the run with status 1 and one error line
# naming the step, the particle id, the field (or the displacement) and the
# cell; a crash snapshot is written; the last restart file stays valid, and
# resuming from it (without the injection) repeats the uninterrupted run bit
# for bit.
# BOLIDE_WATCHDOG_GPU=1 (make check-gpu): every run with --gpu, the
# particles resident on the device, where the watchdog checks them (a pass
# over the device arrays after each step and each drift); the runs must say
# that the GPU ran them.
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}
H=$(cd "$(dirname "$0")/../helpers" && pwd) # restart_compare.py
PY=${PYTHON:-python3}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$B/bolide-ic" sod --nx 16 --size 2,1,1 -o sod.hdf5 >/dev/null
cat >p.yml <<'YML'
InitialConditions:
  file_name: sod.hdf5
  periodic: true
TimeIntegration:
  time_end: 0.012
  dt_max: 0.001
Snapshots:
  subdir: out
  delta_time: 0.004
Scheduler:
  deterministic: true
Restarts:
  enable: true
  subdir: out/restart
  delta_steps: 2
YML
fail=0
G=(); [ "${BOLIDE_WATCHDOG_GPU:-0}" = 1 ] && G=(--gpu)
mkdir A && (cd A && "$B/bolide" "${G[@]}" -t 1 ../p.yml >log 2>err) || { echo "FAIL: uninterrupted run (a false alarm?)"; cat A/err; exit 1; }
if [ ${#G[@]} -gt 0 ]; then
  grep -q "particles stay on it between steps" A/log || { echo "FAIL: --gpu run not on the GPU"; grep -i gpu A/log; exit 1; }
  echo "on the GPU: $(grep -o 'GPU .*(Scheduler:gpu[^)]*)' A/log | head -1)"
fi
grep "watchdog:" A/log
check() { # name injection step expected-text
  local d=$1; mkdir "$d"
  (cd "$d" && BOLIDE_TEST_INJECT=$2 "$B/bolide" "${G[@]}" -t 1 ../p.yml >log 2>err); local rc=$?
  local line; line=$(grep "error" "$d/err")
  if [ $rc -ne 1 ] || [ "$(grep -c error "$d/err")" -ne 1 ] || ! grep -q "watchdog: step $3 .*particle id [0-9]* .*cell .*$4" "$d/err" ||
     [ ! -e "$d/out/crash_step$(printf %06d "$3").hdf5" ]; then
    echo "FAIL: $2: exit $rc"; cat "$d/err"; ls "$d/out"; fail=1; return
  fi
  echo "ok: $2: $line"
}
check N 5:u:nan 5 "field u is nan"
check I 3:h:inf 3 "field h is inf"
check R 4:rho:-1 4 "negative density"
check U 6:u:-1 6 "negative internal energy"
check V 3:vx:1e9 4 "moved .* more than its cell"
# the last restart file (step 4) resumes to the uninterrupted run
(cd N && "$B/bolide" "${G[@]}" -t 1 --restart ../p.yml >log2 2>err2) || { echo "FAIL: resume after the watchdog"; cat N/err2; fail=1; }
grep -q "resumed from out/restart/restart.bin at step 4" N/log2 || { echo "FAIL: not resumed from step 4"; fail=1; }
rm -f N/out/crash_step*.hdf5
"$PY" "$H/restart_compare.py" A/out N/out || fail=1
exit $fail
