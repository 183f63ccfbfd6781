#!/usr/bin/env bash
# Restart files with damage: a basalt sphere in tension (Weibull flaws, Grady-
# Kipp damage) run straight to the end, and stopped after 10 steps and resumed
# with --restart, with one thread and Scheduler:deterministic (fixed task
# order).  The restart file carries the flaws (flat array + offsets) and the
# damage state, and the run rebuilds its cells where it writes one, as the
# resumed run does: the two final snapshots must be identical bit for bit in
# every dataset.  Also: flaws stored in the ICs by bolide-flaws are the ones
# the engine uses (not redrawn from Damage:seed).
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$PYTHON" "${BOLIDE_SRCDIR:?}/tests/helpers/tension_sphere.py" sphere.hdf5 16 --reverse-ids >/dev/null
cat >p.yml <<'YML'
InitialConditions:
  file_name: sphere.hdf5
TimeIntegration:
  time_end: 3e-6
Snapshots:
  subdir: A
  delta_time: 3e-6
Materials:
  0: {name: basalt, weibull_k: 5e34, weibull_m: 8}
SPH:
  viscosity_alpha: 1.0
Damage:
  seed: 7
Scheduler:
  deterministic: true
Restarts:
  enable: true
  delta_hours: 0     # a restart file after every step
  subdir: A/restart
YML
fail=0
"$B/bolide" -t 1 p.yml >a.log 2>&1 || { echo "FAIL: uninterrupted run"; tail -3 a.log; exit 1; }
set -- -P Snapshots:subdir:B -P Restarts:subdir:B/restart
"$B/bolide" -t 1 -n 10 "$@" p.yml >b1.log 2>&1 || { echo "FAIL: first part"; tail -3 b1.log; exit 1; }
"$B/bolide" -t 1 --restart "$@" p.yml >b2.log 2>&1 || { echo "FAIL: resumed run"; tail -3 b2.log; exit 1; }
grep -q "Weibull flaws .* from the restart file" b2.log || { echo "FAIL: flaws not taken from the restart file"; fail=1; }
grep "Weibull flaws" b2.log
"$PYTHON" - <<'PY' || fail=1
import sys, h5py, numpy as np
a = h5py.File("A/snapshot_0001.hdf5", "r")["PartType0"]
b = h5py.File("B/snapshot_0001.hdf5", "r")["PartType0"]
ia, ib = np.argsort(a["ParticleIDs"][:]), np.argsort(b["ParticleIDs"][:])
bad = 0
for k in sorted(a.keys()):
    x, y = a[k][:][ia], b[k][:][ib]
    same = x.shape == y.shape and np.array_equal(x.view(np.uint8), y.view(np.uint8))
    d = np.abs(x.astype(float) - y.astype(float)).max() if x.shape == y.shape else np.inf
    print("%-18s %s (max difference %.3e)" % (k, "bit-identical" if same else "DIFFERS", d))
    bad += not same
d = a["Damage"][:]
print("damaged particles (d > 0.01): %d of %d, active flaws %d" % ((d > 0.01).sum(), len(d), a["ActiveFlaws"][:].sum()))
if not (d > 0.01).sum() > 0:
    print("FAIL: no damage: the test would not see the damage state"); bad += 1
sys.exit(1 if bad else 0)
PY
# flaws stored in the ICs are used as they are
"$B/bolide-flaws" sphere.hdf5 flawed.hdf5 --mat 0 --k 5e34 --m 8 --seed 99 >/dev/null || { echo "FAIL: bolide-flaws"; exit 1; }
"$B/bolide" -t 1 -n 1 -P InitialConditions:file_name:flawed.hdf5 -P Snapshots:subdir:D \
  -P Restarts:enable:false p.yml >d.log 2>&1 || { echo "FAIL: run with IC flaws"; tail -3 d.log; exit 1; }
grep -q "Weibull flaws .* from the initial conditions" d.log || { echo "FAIL: IC flaws not used"; fail=1; }
"$PYTHON" - <<'PY' || fail=1
import sys, h5py, numpy as np
f = h5py.File("flawed.hdf5", "r")["PartType0"]
off = f["FlawOffsets"][:]
want = dict(zip(f["ParticleIDs"][:], np.diff(off)))
g = h5py.File("D/snapshot_0000.hdf5", "r")["PartType0"]
got = dict(zip(g["ParticleIDs"][:], g["NumberOfFlaws"][:]))
ok = want == got
print("flaw counts from the ICs (bolide-flaws --seed 99): %s" % ("used" if ok else "NOT used"))
sys.exit(0 if ok else 1)
PY
exit $fail
