#!/usr/bin/env bash
# Issue 18: nothing lost to a crash.  A run is killed with SIGKILL N times,
# at random moments and, every third kill, as soon as a snapshot file (every
# other third: a restart file) is being written (its .tmp exists), resumed
# with --restart after each kill (from the start while no restart file exists
# yet), and when it has finished every snapshot and the statistics file are
# compared with the uninterrupted run: same file names, times and particle
# data, bit for bit (one thread, Scheduler:deterministic;
# tests/helpers/restart_compare.py).  Then the same with SIGTERM at random moments
# (each stop must exit with status 0 after writing a restart file).
#
#   BOLIDE_BUILDDIR=_build PYTHON=_build/.venv/bin/python tests/program/test_restart_kill.sh 50
#                                      50 kills of each kind (about 4 min on
#                                      2 loaded cores; the result is in
#                                      theory/restarts.md)
# make check runs it with BOLIDE_KILLS kills of each kind (default 15).
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}
H=$(cd "$(dirname "$0")/../helpers" && pwd) # restart_compare.py
PY=${PYTHON:-python3}
N=${1:-${BOLIDE_KILLS:-15}}
work=$(mktemp -d); trap 'kill $(jobs -p) 2>/dev/null; rm -rf "$work"' EXIT
cd "$work"
"$B/bolide-ic" sod --nx 16 --size 2,1,1 -o sod.hdf5 >/dev/null
cat >p.yml <<'YML'
InitialConditions:
  file_name: sod.hdf5
  periodic: true
TimeIntegration:
  time_end: 0.03
  dt_max: 0.001
Snapshots:
  subdir: out
  delta_time: 0.003
  compression: 9 # slower writes: a window for the kills aimed at them
Scheduler:
  deterministic: true
Restarts:
  enable: true
  subdir: out/restart
  delta_steps: 2
YML
mkdir A && (cd A && "$B/bolide" -t 1 ../p.yml >log 2>&1) || { echo "FAIL: uninterrupted run"; tail -3 A/log; exit 1; }
t0=$(date +%s.%N)
(cd A && "$B/bolide" -t 1 ../p.yml >/dev/null 2>&1)
t1=$(date +%s.%N)
# random delays up to half a whole run: some kills land at start-up, most
# mid-run, and the run progresses (a restart file every 2 steps); a run that
# finishes before its signal is started over
maxms=$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%d", 500 * (b - a)}')
echo "uninterrupted run: $(ls A/out/*.hdf5 | wc -l) snapshots, $(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.2f", b - a}') s; kills after 0-$maxms ms"
fail=0
RANDOM=${BOLIDE_KILL_SEED:-18}
mkfifo wait.fifo && exec 3<>wait.fifo # read -t on it: a sleep without a process
for sig in KILL TERM; do
  d=$sig; mkdir $d; cd $d
  kills=0 runs=0 intmp=0 insnap=0 bad=0 cycles=0
  while :; do
    runs=$((runs + 1))
    opt=()
    [ -e out/restart/restart.bin ] || [ -e out/restart/restart.prev.bin ] && opt=(--restart)
    if [ $kills -ge "$N" ]; then
      "$B/bolide" -t 1 "${opt[@]}" ../p.yml >log.$runs 2>&1 || { echo "FAIL: $sig: final run"; tail -3 log.$runs; bad=1; }
      break
    fi
    touch .start
    "$B/bolide" -t 1 "${opt[@]}" ../p.yml >log.$runs 2>&1 &
    pid=$!
    if [ $sig = TERM ]; then # after the handlers are installed
      for _ in $(seq 400); do grep -q "particles" log.$runs 2>/dev/null && break; sleep 0.01; done
    fi
    aim=$([ $sig = KILL ] && echo $((kills % 3)) || echo 0)
    if [ "$aim" -eq 0 ]; then
      ms=$((RANDOM % (maxms + 1)))
      sleep "$(awk -v m=$ms 'BEGIN {printf "%.3f", m / 1000}')"
    else
      # aimed: as soon as a snapshot (1) or a restart file (2) is being written
      pat=$([ "$aim" -eq 1 ] && echo 'out/*.hdf5.tmp' || echo 'out/restart/restart.bin.tmp')
      for _ in $(seq 20000); do compgen -G "$pat" >/dev/null && break; kill -0 $pid 2>/dev/null || break; read -t 0.001 -u 3; done
    fi
    kill -s $sig $pid 2>/dev/null
    { wait $pid; } 2>/dev/null; rc=$?
    if [ $rc -eq 0 ] && grep -q "^\[.*\] done:" log.$runs && ! grep -q "received" log.$runs; then
      # finished before the signal: compare, then start over
      "$PY" "$H/restart_compare.py" ../A/out out >cmp.txt || { echo "FAIL: SIG$sig: outputs differ:"; head -5 cmp.txt; bad=1; break; }
      cycles=$((cycles + 1))
      rm -rf out; continue
    fi
    kills=$((kills + 1))
    if [ $sig = KILL ]; then
      [ $rc -eq 137 ] || { echo "FAIL: SIGKILL: run $runs exit $rc"; tail -3 log.$runs; bad=1; break; }
      [ -e out/restart/restart.bin.tmp ] && intmp=$((intmp + 1))
      # a snapshot's temporary file: killed while writing it (removed by the next run)
      compgen -G 'out/*.tmp' >/dev/null && insnap=$((insnap + 1))
    else
      if [ $rc -ne 0 ] || ! grep -q "SIGTERM received" log.$runs; then
        echo "FAIL: SIGTERM: run $runs exit $rc"; tail -3 log.$runs; bad=1; break
      fi
    fi
  done
  if [ $bad -eq 0 ] && { compgen -G 'out/*.tmp' || compgen -G 'out/restart/*.tmp'; } >/dev/null; then
    echo "FAIL: SIG$sig: temporary files left: $(ls out/*.tmp out/restart/*.tmp 2>/dev/null)"; bad=1
  fi
  if [ $bad -eq 0 ]; then
    if "$PY" "$H/restart_compare.py" ../A/out out >cmp.txt; then
      cycles=$((cycles + 1))
      echo "ok: SIG$sig: $kills kills in $runs runs, $cycles complete runs compared ($intmp kills during a restart write, $insnap during a snapshot write); last: $(cat cmp.txt)"
    else
      echo "FAIL: SIG$sig: outputs differ after $kills kills:"; head -5 cmp.txt; bad=1
    fi
  fi
  [ $bad -eq 0 ] || fail=1
  cd ..
done
exit $fail
