#!/usr/bin/env bash
# Porosity in the engine (P-alpha, Jutzi et al. 2008): a porous cube
# (distention alpha_0 = 1.8, bulk density rho0/1.8) squeezed isotropically,
# v = -3000/s x, until its core is fully compacted, once with a Murnaghan and
# once with a Tillotson matrix; the crush curve is the one of the model test
# (tests/unit/test_porosity.c: p_e = 1 MPa, p_t = 50 MPa, p_s = 200 MPa, alpha_t
# = 1.3, n1 = 6, n2 = 3), written again here.  A snapshot after every step.
# Asserts, for the core (initially |x| < 0.2 m, compressed homogeneously
# until the release from the faces arrives):
#  - every step on the crush curve: alpha_cc(P_n) lies between alpha_n and
#    alpha_(n-1) (P_n: the pressure of step n, at the predicted state inside
#    the step; alpha_n: the distention at its end; the curve is monotone)
#    for particles compacting in steps n-1 and n;
#  - full compaction: alpha = 1 exactly once P >= p_s, and there the
#    pressure is the matrix EOS at the bulk density (Murnaghan, 1e-12);
# for every particle: alpha never increases, 1 <= alpha <= alpha_0.
# Also: alpha is in the restart files (a run stopped and resumed with -t 1
# and Scheduler:deterministic ends bit for bit like the straight one), and
# an IC whose density times alpha is not the matrix density stops at
# start-up with one line naming the file.
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
cube="$PYTHON ${BOLIDE_SRCDIR:?}/tests/helpers/porous_cube.py"
$cube block.hdf5 1500 3000                 # 2700 / 1.8
$cube wrong.hdf5 1600 3000                 # 1600 x 1.8 = 2880, not 2700
$cube given.hdf5 1800 3000 1.5             # Distentions in the file: 2700 / 1.5
crush='porosity: {model: palpha, alpha_0: 1.8, alpha_t: 1.3, p_e: 1e6, p_t: 5e7, p_s: 2e8, n1: 6, n2: 3}'
for matrix in murnaghan tillotson; do
  if [ $matrix = murnaghan ]; then
    mat="{name: porous, eos: murnaghan, rho0: 2700, K0: 2e10, n: 4, $crush}"
  else
    mat="{name: basalt, $crush}"
  fi
  cat >$matrix.yml <<YML
InitialConditions:
  file_name: block.hdf5
TimeIntegration:
  time_end: 7.5e-5
Snapshots:
  subdir: $matrix
  delta_time: 2.5e-6
SPH:
  density: continuity
Materials:
  0: $mat
YML
done
fail=0
for matrix in murnaghan tillotson; do
  "$B/bolide" -t 2 $matrix.yml >$matrix.log 2>&1 || { echo "FAIL: $matrix run"; tail -3 $matrix.log; exit 1; }
done
"$PYTHON" - <<'PY' || fail=1
import sys, glob, h5py, numpy as np
pe, pt, ps, a0, at, n1, n2 = 1e6, 5e7, 2e8, 1.8, 1.3, 6.0, 3.0
def alpha_cc(P):      # crush curve PA2 (Jutzi et al. 2009 eq. 1), alpha_e = alpha_0
    P = np.asarray(P, float)
    a = np.where(P <= pe, a0, 1.0)
    m = (P > pe) & (P < ps)
    x = 1 + (at - 1) * ((ps - P[m]) / (ps - pe))**n2
    x = np.where(P[m] < pt, x + (a0 - at) * ((pt - np.minimum(P[m], pt)) / (pt - pe))**n1, x)
    a[m] = x
    return a
fail = 0
for matrix in ("murnaghan", "tillotson"):
    snaps = sorted(glob.glob(matrix + "/snapshot_*.hdf5"))
    A, P, R, dt = [], [], [], []
    for f in snaps:
        F = h5py.File(f, "r"); g = F["PartType0"]
        o = np.argsort(g["ParticleIDs"][:])
        A.append(g["Distentions"][:][o]); P.append(g["Pressures"][:][o]); R.append(g["Densities"][:][o])
        if len(A) == 1: core = np.abs(g["Coordinates"][:][o] - 2.0).max(axis=1) < 0.2
    A, P, R = map(np.array, (A, P, R))
    worst_lo = worst_hi = 0.0; checked = 0
    for k in range(2, len(A)):
        load = core & (A[k] < A[k - 1]) & (A[k - 1] < A[k - 2])
        c = alpha_cc(P[k][load])
        worst_lo = max(worst_lo, (A[k][load] - c).max(initial=0.0))      # alpha_n <= alpha_cc
        worst_hi = max(worst_hi, (c - A[k - 1][load]).max(initial=0.0))  # alpha_cc <= alpha_(n-1)
        checked += load.sum()
    print("%s: %d snapshots, %d core particle-steps on the crush curve checked" % (matrix, len(A), checked))
    print("  alpha_n - alpha_cc(P_n), largest: %.3e (must be <= 1e-12)" % worst_lo)
    print("  alpha_cc(P_n) - alpha_(n-1), largest: %.3e (must be <= 1e-12)" % worst_hi)
    if checked < 1000 or worst_lo > 1e-12 or worst_hi > 1e-12:
        print("FAIL: the core does not follow the crush curve"); fail = 1
    rise = np.diff(A, axis=0).max()
    print("  largest increase of alpha in a step: %.3e; alpha in [%.6f, %.6f]" % (rise, A.min(), A.max()))
    if rise > 0 or A.min() < 1.0 or A.max() > a0:
        print("FAIL: alpha increased or left [1, alpha_0]"); fail = 1
    full = core & (P[-1] >= ps)
    print("  core particles beyond p_s at the end: %d of %d, alpha - 1 there: %.3e"
          % (full.sum(), core.sum(), np.abs(A[-1][full] - 1).max(initial=0.0)))
    if full.sum() < core.sum() or np.any(A[-1][full] != 1.0):
        print("FAIL: the core is not fully compacted to alpha = 1"); fail = 1
    if matrix == "murnaghan":   # P = K0/n ((rho/rho0)^n - 1) at alpha = 1 (Densities: the EOS's density)
        both = core & (A[-1] == 1.0) & (A[-2] == 1.0)
        Pm = 2e10 / 4 * ((R[-1][both] / 2700.0)**4 - 1)
        e = np.abs(P[-1][both] / Pm - 1).max()
        print("  compacted core: P against the Murnaghan matrix at the bulk density: %.2e (<= 1e-12)" % e)
        if not e <= 1e-12: fail = 1
sys.exit(fail)
PY
# restarts carry alpha: stop after 8 steps, resume, compare bit for bit
set -- -t 1 -P Scheduler:deterministic:true -P Restarts:enable:true -P Restarts:delta_hours:0 \
  -P TimeIntegration:time_end:3e-5 -P Snapshots:delta_time:3e-5
"$B/bolide" "$@" -P Snapshots:subdir:S -P Restarts:subdir:S/r murnaghan.yml >s.log 2>&1 || { echo "FAIL: straight run"; exit 1; }
"$B/bolide" "$@" -n 8 -P Snapshots:subdir:R -P Restarts:subdir:R/r murnaghan.yml >r1.log 2>&1 || { echo "FAIL: first part"; exit 1; }
"$B/bolide" "$@" --restart -P Snapshots:subdir:R -P Restarts:subdir:R/r murnaghan.yml >r2.log 2>&1 || { echo "FAIL: resumed"; exit 1; }
"$PYTHON" - <<'PY' || fail=1
import sys, h5py, numpy as np
a = h5py.File("S/snapshot_0001.hdf5", "r")["PartType0"]; b = h5py.File("R/snapshot_0001.hdf5", "r")["PartType0"]
ia, ib = np.argsort(a["ParticleIDs"][:]), np.argsort(b["ParticleIDs"][:])
diff = [k for k in a.keys() if not np.array_equal(a[k][:][ia], b[k][:][ib])]
moved = a["Distentions"][:].min() < 1.8
print("resumed run: %s; distentions changed in the run: %s" % ("bit-identical" if not diff else "differs in " + " ".join(diff), moved))
sys.exit(0 if not diff and moved else 1)
PY
# IC checks: given Distentions are used; a wrong density stops with one line
"$B/bolide" -n 0 -P InitialConditions:file_name:given.hdf5 -P Snapshots:subdir:G murnaghan.yml >g.log 2>&1 \
  || { echo "FAIL: IC with Distentions refused"; tail -2 g.log; fail=1; }
grep -q "distentions from the initial conditions" g.log || { echo "FAIL: IC Distentions not used"; fail=1; }
"$B/bolide" -n 0 -P InitialConditions:file_name:wrong.hdf5 -P Snapshots:subdir:W murnaghan.yml >w.log 2>err.txt
rc=$?
if [ $rc -eq 0 ] || [ "$(wc -l <err.txt)" -ne 1 ] || ! grep -q "wrong.hdf5: .*matrix density" err.txt; then
  echo "FAIL: inconsistent porous IC accepted (exit $rc)"; cat err.txt; fail=1
else
  echo "ok: $(cat err.txt)"
fi
exit $fail
