#!/usr/bin/env bash
# Damage in a run: a basalt sphere (Benz & Asphaug 1999 basalt, von Mises
# strength, Weibull k = 5e34 m^-3, m = 8 as in the Nakamura set-up) expanding
# radially, so in tension.  Asserts: flaws drawn at start-up (about ln N + 0.58
# per particle); damage appears; no particle's damage ever decreases between
# snapshots; every particle's d stays within its limiter d <= n_act / n_flaws;
# damaged particles exist only where flaws were activated.  Then with
# Damage:start_time 2e-6: no flaw active and no damage at the snapshots
# before it, damage after it.
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$PYTHON" "${BOLIDE_SRCDIR:?}/tests/helpers/tension_sphere.py" sphere.hdf5 20
cat >p.yml <<'YML'
InitialConditions:
  file_name: sphere.hdf5
TimeIntegration:
  time_end: 4e-6
Snapshots:
  delta_time: 1e-6
Materials:
  0: {name: basalt, weibull_k: 5e34, weibull_m: 8}
SPH:
  viscosity_alpha: 1.0
Damage:
  seed: 7
YML
"$B/bolide" -t 2 p.yml >run.log 2>&1 || { echo "FAIL: run"; tail -5 run.log; exit 1; }
grep "Weibull flaws" run.log
"$PYTHON" - <<'PY'
import sys, glob, h5py, numpy as np
files = sorted(glob.glob("snapshot_*.hdf5"))
fail = 0
prev = None
for f in files:
    g = h5py.File(f, "r")["PartType0"]
    o = np.argsort(g["ParticleIDs"][:])
    d = g["Damage"][:][o]; na = g["ActiveFlaws"][:][o]; nf = g["NumberOfFlaws"][:][o]
    t = float(np.ravel(h5py.File(f, "r")["Header"].attrs["Time"])[0])
    lim = np.where(nf > 0, na / np.maximum(nf, 1), 0.0)
    print("t = %.2e s: mean damage %.4f, max %.4f, damaged (d > 0.01) %.1f%%, active flaws %d"
          % (t, d.mean(), d.max(), 100 * np.mean(d > 0.01), na.sum()))
    if np.any(d > lim * (1 + 1e-12) + 1e-15):
        print("FAIL: damage above its limiter n_act/n_flaws"); fail = 1
    if np.any((d > 0) & (na == 0)):
        print("FAIL: damage without activated flaws"); fail = 1
    if prev is not None and np.any(d < prev - 1e-15):
        print("FAIL: damage decreased"); fail = 1
    prev = d
N = len(prev)
mean_flaws = nf.mean()
print("flaws per particle %.2f (ln N + 0.577 = %.2f)" % (mean_flaws, np.log(N) + 0.5772))
if abs(mean_flaws - (np.log(N) + 0.5772)) > 0.15 * (np.log(N) + 0.5772):
    print("FAIL: flaw count"); fail = 1
if not prev.max() > 0.1:
    print("FAIL: no damage grew in tension"); fail = 1
sys.exit(fail)
PY
[ $? -eq 0 ] || exit 1
# Damage:start_time: the same run, damage only from t = 2e-6
mkdir -p late && cd late
sed 's|file_name: sphere.hdf5|file_name: ../sphere.hdf5|' ../p.yml >p.yml
"$B/bolide" -t 2 -P Damage:start_time:2e-6 p.yml >run.log 2>&1 ||
  { echo "FAIL: run with Damage:start_time"; tail -5 run.log; exit 1; }
grep -q "before t = 2e-06 (Damage:start_time)" run.log || { echo "FAIL: no start-time line in the log"; exit 1; }
"$PYTHON" - <<'PY'
import sys, glob, h5py, numpy as np
fail = 0
for f in sorted(glob.glob("snapshot_*.hdf5")):
    F = h5py.File(f, "r"); g = F["PartType0"]
    t = float(np.ravel(F["Header"].attrs["Time"])[0])
    d = g["Damage"][:]; na = g["ActiveFlaws"][:]
    print("Damage:start_time 2e-6: t = %.2e s: max damage %.4f, active flaws %d" % (t, d.max(), na.sum()))
    if t < 2e-6 * (1 - 1e-9) and (d.max() > 0 or na.sum() > 0):
        print("FAIL: damage before Damage:start_time"); fail = 1
    if t > 3.5e-6 and not d.max() > 0.01:
        print("FAIL: no damage after Damage:start_time"); fail = 1
sys.exit(fail)
PY
