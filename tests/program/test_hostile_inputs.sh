#!/usr/bin/env bash
# Hostile inputs that used to hang, take minutes or slip through (issue 18
# item 6), run through bolide itself: each must stop within seconds with one
# line "bolide: error: ..." naming the problem, or (an open box) follow its
# documented behaviour.
set -u
B=${BOLIDE_BUILDDIR:?}
[ -x "${PYTHON:-}" ] || { echo "no Python venv: skip"; exit 77; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$B/bolide-ic" box --n 12 -o box.hdf5 >/dev/null || exit 1
"$PYTHON" - <<'PY' || exit 1
import shutil
import h5py
def variant(name, edit):
    shutil.copy("box.hdf5", name + ".hdf5")
    with h5py.File(name + ".hdf5", "r+") as f:
        edit(f["PartType0"])
variant("far", lambda g: g["Coordinates"].__setitem__((3, 0), 1e300))
variant("fast", lambda g: g["Velocities"].__setitem__(slice(None), 1e200))
variant("one_point", lambda g: g["Coordinates"].__setitem__(slice(None), 0.5))
PY
cat >p.yml <<'YML'
InitialConditions:
  file_name: box.hdf5
  periodic: true
TimeIntegration:
  time_end: 0.01
Statistics:
  delta_time: 0.001
YML
fail=0
# expect NAME REGEX ARGS...: bolide ARGS p.yml fails within 10 s with one matching line
expect() {
  local name=$1 regex=$2; shift 2
  local start rc ms
  start=$(date +%s%N)
  timeout 10 "$B/bolide" -t 1 "$@" p.yml >out.txt 2>err.txt
  rc=$?
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  if [ $rc -eq 0 ] || [ $rc -eq 124 ] || [ "$(wc -l <err.txt)" -ne 1 ] || ! grep -Eq "^bolide: error: $regex" err.txt; then
    echo "FAIL $name: exit $rc after $ms ms:"; cat err.txt; fail=1
  else
    echo "ok   $name ($ms ms): $(cat err.txt)"
  fi
}
expect time_begin 'time step .* cannot advance the time t = -1e\+17' -P TimeIntegration:time_begin:-1e17
expect far_periodic 'far.hdf5: particle 3 \(id 4\): position x = 1e\+300 is more than a box size outside the periodic box' \
  -P InitialConditions:file_name:far.hdf5
expect fast 'fast.hdf5: particle 0 \(id 1\): speed 1.7[0-9]*e\+200 is above the speed of light' \
  -P InitialConditions:file_name:fast.hdf5
expect one_point 'one_point.hdf5: particles 0 \(id 1\) and 1 \(id 2\) are at the same position' \
  -P InitialConditions:file_name:one_point.hdf5
# a statistics interval of 1e-308 (2e305 lines between two steps) is legal:
# one line per step that crosses its times, no endless loop
if ! timeout 10 "$B/bolide" -t 1 -P Statistics:delta_time:1e-308 p.yml >out.txt 2>err.txt; then
  echo "FAIL stats_dt: Statistics:delta_time 1e-308 did not finish"; tail -2 err.txt; fail=1
else
  echo "ok   stats_dt 1e-308: $(grep -vc '^#' statistics.txt) statistics lines"
fi
# an open box removes a particle outside it, with a log line (documented)
if ! timeout 20 "$B/bolide" -t 1 -P InitialConditions:file_name:far.hdf5 -P InitialConditions:periodic:false p.yml >out.txt 2>err.txt ||
   ! grep -q 'removed particle id 4 at (1e+300' out.txt; then
  echo "FAIL far_open: not removed with a log line"; tail -3 out.txt err.txt; fail=1
else
  echo "ok   far_open: $(grep 'removed particle id 4' out.txt)"
fi

# a full disk during a snapshot (item 5): tests/helpers/faultfs.so fails HDF5's
# writes with ENOSPC after FAULTFS_BYTES, at a dataset or at the flush on
# closing (which crashed in HDF5's exit handler).  One line, exit 1, no
# temporary file; the earlier snapshots equal the uninterrupted run's and
# the last restart file (written every step; none before the snapshot at
# t = 0) resumes the run to its end with every snapshot bit-identical to the
# uninterrupted run's (one thread, Scheduler:deterministic).
cat >d.yml <<'YML'
InitialConditions:
  file_name: box.hdf5
  periodic: true
TimeIntegration:
  time_end: 0.02
  dt_max: 0.001
Snapshots:
  subdir: ref
  delta_time: 0.005
Scheduler:
  deterministic: true
Restarts:
  enable: true
  delta_hours: 0
  subdir: ref/restart
YML
"$B/bolide" -t 1 d.yml >ref.log 2>&1 || { echo "FAIL: the run without faults"; tail -3 ref.log; exit 1; }
S=$(stat -c %s ref/snapshot_0000.hdf5)
export ASAN_OPTIONS="${ASAN_OPTIONS:-}:verify_asan_link_order=0"
for k in 0 1 2; do
  for frac in 25 90; do
    bytes=$(( k * S + S * frac / 100 ))
    rm -rf full
    (trap '' XFSZ; LD_PRELOAD="$B/tests/helpers/faultfs.so" FAULTFS_BYTES=$bytes timeout 30 "$B/bolide" -t 1 \
       -P Snapshots:subdir:full -P Restarts:subdir:full/restart d.yml >full.log 2>err.txt)
    rc=$?
    snap=$(printf 'full/snapshot_%04d.hdf5' $k)
    if [ $rc -ne 1 ] || [ "$(wc -l <err.txt)" -ne 1 ] ||
       ! grep -q "^bolide: error: $snap: cannot write .*No space left on device" err.txt ||
       [ -n "$(ls full | grep tmp)" ] || [ -e "$snap" ]; then
      echo "FAIL disk full after $bytes bytes: exit $rc, left: $(ls full | tr '\n' ' ')"; cat err.txt; fail=1; continue
    fi
    "$PYTHON" - "$k" <<'PY' || { echo "FAIL disk full after $bytes bytes: earlier snapshots differ"; fail=1; }
import sys
import h5py
import numpy as np
for j in range(int(sys.argv[1])):
    with h5py.File(f"ref/snapshot_{j:04d}.hdf5") as a, h5py.File(f"full/snapshot_{j:04d}.hdf5") as b:
        for name in a["PartType0"]:
            if not np.array_equal(a["PartType0"][name][...], b["PartType0"][name][...]):
                sys.exit(f"snapshot {j}: {name} differs")
PY
    if [ $k -eq 0 ]; then # at t = 0, before any restart file
      echo "ok   disk full after $bytes bytes: $(cat err.txt)"
    elif ! timeout 60 "$B/bolide" -t 1 --restart -P Snapshots:subdir:full -P Restarts:subdir:full/restart d.yml >res.log 2>&1 ||
       ! grep -q "^done: .* to t = 0.02 " <(sed 's/^\[ *[0-9.]* s\] //' res.log); then
      echo "FAIL disk full after $bytes bytes: the restart file does not resume the run"; tail -3 res.log; fail=1
    elif ! "$PYTHON" - 5 <<'PY'
import sys
import h5py
import numpy as np
for j in range(int(sys.argv[1])):
    with h5py.File(f"ref/snapshot_{j:04d}.hdf5") as a, h5py.File(f"full/snapshot_{j:04d}.hdf5") as b:
        for name in a["PartType0"]:
            if not np.array_equal(a["PartType0"][name][...], b["PartType0"][name][...]):
                sys.exit(f"snapshot {j}: {name} differs")
PY
    then
      echo "FAIL disk full after $bytes bytes: the resumed run's snapshots differ from the uninterrupted run's"; fail=1
    else
      echo "ok   disk full after $bytes bytes: $(cat err.txt); resumed to the end, every snapshot identical"
    fi
  done
done
exit $fail
