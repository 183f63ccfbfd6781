#!/usr/bin/env bash
# Restart files: a run stopped after 4 steps and resumed with --restart ends
# in the same state as the run that was never stopped (to round-off: the
# order of the sums over neighbours may differ), and the resumed run appends
# to the statistics file; a corrupt restart file is refused with one line.
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$B/bolide-ic" sod --nx 32 --size 2,0.5,0.5 -o sod.hdf5 >/dev/null
cat >p.yml <<'YML'
InitialConditions:
  file_name: sod.hdf5
  periodic: true
TimeIntegration:
  time_end: 0.05
Snapshots:
  subdir: A
  delta_time: 0.05
Restarts:
  enable: true
  subdir: A/restart
YML
fail=0
"$B/bolide" -t 2 p.yml >a.log 2>&1 || { echo "FAIL: uninterrupted run"; tail -3 a.log; exit 1; }
set -- -P Snapshots:subdir:B -P Restarts:subdir:B/restart
"$B/bolide" -t 2 -n 4 "$@" p.yml >b1.log 2>&1 || { echo "FAIL: first half"; tail -3 b1.log; exit 1; }
"$B/bolide" -t 2 --restart "$@" p.yml >b2.log 2>&1 || { echo "FAIL: resumed run"; tail -3 b2.log; exit 1; }
grep -q "resumed from" b2.log || { echo "FAIL: no resume message"; fail=1; }
# appended: one table, no comment line among the data (swiftsimio reads it)
[ "$(grep -v '^#' B/statistics.txt | head -1 | cut -d' ' -f1)" = 0 ] && ! sed -n '/^[^#]/,$p' B/statistics.txt | grep -q '^#' ||
  { echo "FAIL: statistics not appended as one table"; fail=1; }
"$PYTHON" - <<'PY' || fail=1
import sys, h5py, numpy as np
a = h5py.File("A/snapshot_0001.hdf5", "r")["PartType0"]
b = h5py.File("B/snapshot_0001.hdf5", "r")["PartType0"]
ia, ib = np.argsort(a["ParticleIDs"][:]), np.argsort(b["ParticleIDs"][:])
worst = 0.0
for k in ("Coordinates", "Velocities", "Densities", "InternalEnergies", "SmoothingLengths"):
    x, y = a[k][:][ia], b[k][:][ib]
    d = np.abs(x - y).max() / np.abs(x).max()
    print("%-18s max relative difference %.2e" % (k, d))
    worst = max(worst, d)
sys.exit(0 if worst < 1e-12 else 1)
PY
# truncated restart files (the newest and the previous one): one line, non-zero exit
for f in restart.bin restart.prev.bin; do
  head -c 1000 B/restart/$f >B/restart/cut && mv B/restart/cut B/restart/$f
done
"$B/bolide" --restart "$@" p.yml >c.log 2>err.txt
rc=$?
if [ $rc -eq 0 ] || [ "$(wc -l <err.txt)" -ne 1 ] || ! grep -q "restart.bin" err.txt; then
  echo "FAIL: truncated restart file accepted (exit $rc)"; cat err.txt; fail=1
else
  echo "ok: $(cat err.txt)"
fi
exit $fail
