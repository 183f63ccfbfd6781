#!/usr/bin/env bash
# Issue 18 item 2: SIGTERM, SIGINT, SIGHUP and SIGUSR1 make a run write a
# restart file and exit with status 0 and one line naming the signal; a
# second signal stops it at once; Restarts:delta_steps, Restarts:max_run_time
# and the stop file (RESTART_DIR/stop) write a restart file (and stop).  Each
# stopped run is resumed and its outputs compared with the uninterrupted run,
# bit for bit (one thread, Scheduler:deterministic).
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}
H=$(cd "$(dirname "$0")/../helpers" && pwd) # restart_compare.py
PY=${PYTHON:-python3}
work=$(mktemp -d); trap 'kill $(jobs -p) 2>/dev/null; rm -rf "$work"' EXIT
cd "$work"
"$B/bolide-ic" sod --nx 16 --size 2,1,1 -o sod.hdf5 >/dev/null
cat >p.yml <<'YML'
InitialConditions:
  file_name: sod.hdf5
  periodic: true
TimeIntegration:
  time_end: 0.06
  dt_max: 0.0008
Snapshots:
  subdir: out
  delta_time: 0.01
Scheduler:
  deterministic: true
Restarts:
  enable: true
  subdir: out/restart
  delta_steps: 20
YML
fail=0
mkdir A && (cd A && "$B/bolide" -t 1 ../p.yml >log 2>err) || { echo "FAIL: uninterrupted run"; tail -3 A/err; exit 1; }
grep -q "restart file out/restart/restart.bin at step 20," A/log && grep -q "at step 60," A/log ||
  { echo "FAIL: Restarts:delta_steps 20 wrote no files at steps 20 and 60"; fail=1; }
steps() { awk 'NF == 6 && $1 ~ /^[0-9]+$/ {n = $1} END {print n + 0}' "$1" 2>/dev/null; }
# start a run in folder $1 and wait until it has done $2 steps
start() {
  mkdir -p "$1"
  (cd "$1" && exec "$B/bolide" -t 1 ../p.yml >log 2>err) &
  pid=$!
  for _ in $(seq 600); do [ "$(steps "$1/log")" -ge "$2" ] && return; sleep 0.05; done
}
resume_and_compare() {
  (cd "$1" && "$B/bolide" -t 1 --restart ../p.yml >log2 2>err2) || { echo "FAIL: $1: resumed run"; tail -2 "$1/err2"; fail=1; return; }
  "$PY" "$H/restart_compare.py" A/out "$1/out" >cmp.txt || { echo "FAIL: $1: outputs differ"; cat cmp.txt; fail=1; return; }
  echo "ok: $1: $(cat cmp.txt)"
}
k=0
for sig in TERM INT HUP USR1; do
  k=$((k + 1))
  start S$sig $((5 + 12 * k))
  kill -s $sig $pid
  wait $pid; rc=$?
  if [ $rc -ne 0 ] || [ "$(wc -l <S$sig/err)" -ne 1 ] || ! grep -q "SIG$sig received" S$sig/err; then
    echo "FAIL: SIG$sig: exit $rc, stderr:"; cat S$sig/err; fail=1; continue
  fi
  echo "ok: SIG$sig: exit 0 after step $(steps S$sig/log): $(cat S$sig/err)"
  [ $sig = TERM ] && resume_and_compare S$sig
done
# a second signal stops at once
start D 20
kill -s TERM $pid; kill -s INT $pid # (two of one kind could merge while pending)
wait $pid; rc=$?
if [ $rc -eq 0 ] || ! grep -q "second signal" D/err; then echo "FAIL: second signal: exit $rc"; cat D/err; fail=1
else echo "ok: second signal: exit $rc: $(tail -1 D/err)"; fi
# the stop file
start F 30
touch F/out/restart/stop
wait $pid; rc=$?
if [ $rc -ne 0 ] || ! grep -q "stop file" F/err || [ -e F/out/restart/stop ]; then echo "FAIL: stop file: exit $rc"; cat F/err; fail=1
else echo "ok: stop file: $(cat F/err)"; resume_and_compare F; fi
# Restarts:max_run_time (hours)
mkdir M && (cd M && "$B/bolide" -t 1 -P Restarts:max_run_time:0.0002 ../p.yml >log 2>err); rc=$?
if [ $rc -ne 0 ] || ! grep -q "max_run_time" M/err || [ "$(steps M/log)" -ge "$(steps A/log)" ]; then
  echo "FAIL: max_run_time: exit $rc, $(steps M/log) steps"; cat M/err; fail=1
else echo "ok: max_run_time: stopped after step $(steps M/log): $(cat M/err)"; fi
exit $fail
