#!/usr/bin/env bash
# The 2e6-particle run of README.md ("Two million target particles") on the
# lent GPU host, in calls of at most 10 minutes each: restart files every
# 0.04 h of wall clock carry the run from one call to the next (the run
# folder is ignored by git, so it stays on the host while it is warm).
# Meant for tools/bench/device.sh's cmd step (BOLIDE_BUILD set, the GPU
# build); results are copied to /tmp/dout, which device.sh returns.
# Usage: device_2e6.sh start SECONDS    initial conditions (run.sh IC_ONLY=1), then
#                                       run for what is left of SECONDS
#        device_2e6.sh resume SECONDS   continue from the newest restart file (or
#                                       from the initial conditions if none yet)
# When the run has reached time_end, the analysis follows (analyse.py: core.txt,
# fragments_*.txt), within the same call if time is left, else in the next.
set -uo pipefail
cd "$(dirname "$0")" || exit 1
step=${1:?start or resume}
budget=${2:?seconds}
n=${N:-2000000}   # N, H_MAX: only to try the script on a small run
threads=${THREADS:-16}
dir=run_$n
# run.sh's options of the 1e6 run, with the h cap at 2 h0 of this resolution
# (h0 = 0.6 mm at 1e6, 0.476 mm at 2e6) and the 25 us of that run
BOLIDE_ARGS="-P Damage:max_change:1 -P SPH:continuity_min_density_ratio:0.5 -P SPH:h_max:${H_MAX:-0.00095}"
BOLIDE_ARGS+=" -P TimeIntegration:time_end:2.5e-5 -P Snapshots:delta_time:5e-6"
export BOLIDE_ARGS+=" -P Restarts:enable:true -P Restarts:delta_hours:${RESTART_HOURS:-0.04}"
out=/tmp/dout
mkdir -p "$out"
t0=$(date +%s)
done_re="done: .* to t = 2.5e-05"
if [ "$step" = start ]; then
  # run.sh writes the initial conditions and params.yml (however long
  # bolide-ic takes), then the run goes on for what is left of the budget
  IC_ONLY=1 ./run.sh "$n" "$threads" || exit 1
  echo "start: initial conditions after $(( $(date +%s) - t0 )) s"
  rm -rf "$dir/restart" "$dir/bolide.log"
  step=resume
  budget=$(( budget - ($(date +%s) - t0) ))
fi
if [ "$step" = resume ]; then
  if [ "$budget" -gt 30 ] && ! grep -q "$done_re" "$dir/bolide.log" 2>/dev/null; then
    from=""  # no restart file yet: from the initial conditions again
    [ -f "$dir/restart/restart.bin" ] && from=--restart
    # shellcheck disable=SC2086
    ( cd "$dir" && timeout "$budget" "$BOLIDE_BUILD/bolide" -t "$threads" $from $BOLIDE_ARGS params.yml \
        >>bolide.log 2>&1 )
    echo "resume: rc $? after $(( $(date +%s) - t0 )) s"
  fi
else
  echo "device_2e6.sh: error: start or resume"; exit 1
fi
grep -E "restart file|done:" "$dir/bolide.log" 2>/dev/null | tail -3
if grep -q "$done_re" "$dir/bolide.log" 2>/dev/null && [ ! -s "$dir/core.txt" ]; then
  left=$(( budget - ($(date +%s) - t0) ))
  [ "$left" -gt 60 ] && timeout "$left" env BOLIDE_BUILD="$BOLIDE_BUILD" "${PYTHON:-python3}" analyse.py "$dir"
fi
cp "$dir"/bolide.log "$dir"/core.txt "$dir"/statistics.txt "$out"/ 2>/dev/null
last=$(find "$dir" -name "fragments_*.txt" | sort | tail -1)
[ -n "$last" ] && cp "$last" "$out"/
exit 0
