#!/usr/bin/env bash
# epsilon-alpha porosity in the engine (Wuennemann et al. 2006, Collins et
# al. 2011; theory/porosity.md EA1-EA8): the porous cube of
# test_porosity_run.sh (alpha_0 = 1.8, bulk density 2700/1.8, squeezed
# isotropically at v = -3000/s x) with a Murnaghan matrix and the
# epsilon-alpha curve eps_e = -0.05, eps_x = -0.3, kappa = 1.2, chi = 0.5
# (elastic compaction too).  A snapshot every 2.5 us.  Asserts:
#  - alpha follows the strain: for core particles (initially |x| < 0.2 m)
#    compacting between snapshots n-1, n and n+1, alpha_n lies between
#    alpha(eps(rho_(n+1))) and alpha(eps(rho_n)), eps(rho) = ln(rho_00/rho),
#    rho_00 = 2700/1.8 (rho_n: the snapshot's density, that of the last
#    predicted state, which lies between the densities at the ends of the
#    step; alpha_n is that of the end of the step), bound 1e-12;
#  - every regime is visited (elastic, exponential, power law, compacted);
#  - alpha never increases, 1 <= alpha <= alpha_0;
#  - the compacted core has alpha = 1 exactly and the pressure of the
#    matrix at the bulk density (Murnaghan, 1e-12).
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$PYTHON" "${BOLIDE_SRCDIR:?}/tests/helpers/porous_cube.py" block.hdf5 1500 3000   # 2700 / 1.8
cat >params.yml <<'YML'
InitialConditions:
  file_name: block.hdf5
TimeIntegration:
  time_end: 7.5e-5
Snapshots:
  subdir: out
  delta_time: 2.5e-6
SPH:
  density: continuity
Materials:
  0: {name: porous, eos: murnaghan, rho0: 2700, K0: 2e10, n: 4,
      porosity: {model: epsalpha, alpha_0: 1.8, eps_e: -0.05, eps_x: -0.3, kappa: 1.2, chi: 0.5}}
YML
"$B/bolide" -t 2 params.yml >run.log 2>&1 || { echo "FAIL: run"; tail -3 run.log; exit 1; }
grep -q "epsilon-alpha" run.log || { echo "FAIL: no porosity line in the log"; exit 1; }
"$PYTHON" - <<'PY'
import sys, glob, h5py, numpy as np
a0, ee, ex, ka, chi = 1.8, -0.05, -0.3, 1.2, 0.5
ae = a0 * np.exp(chi * ka * ee); ax = ae * np.exp(ka * (ex - ee)); ec = ex + 2 * (1 - ax) / (ka * ax)
def alpha_eps(e):            # EA1-EA3, written again from theory/porosity.md
    e = np.asarray(e, float)
    return np.where(e >= 0, a0, np.where(e >= ee, a0 * np.exp(chi * ka * e),
           np.where(e >= ex, ae * np.exp(ka * (e - ee)),
           np.where(e > ec, 1 + (ax - 1) * ((ec - e) / (ec - ex))**2, 1.0))))
rho00 = 2700.0 / a0
snaps = sorted(glob.glob("out/snapshot_*.hdf5"))
A, P, R = [], [], []
for f in snaps:
    g = h5py.File(f, "r")["PartType0"]
    o = np.argsort(g["ParticleIDs"][:])
    A.append(g["Distentions"][:][o]); P.append(g["Pressures"][:][o]); R.append(g["Densities"][:][o])
    if len(A) == 1: core = np.abs(g["Coordinates"][:][o] - 2.0).max(axis=1) < 0.2
A, P, R = map(np.array, (A, P, R))
E = np.log(rho00 / R)
fail = 0
lo = hi = 0.0; checked = 0; regimes = set()
for k in range(1, len(A) - 1):
    load = core & (R[k + 1] > R[k]) & (R[k] > R[k - 1]) & (A[k] > 1.0)
    up = alpha_eps(E[k][load]); down = alpha_eps(E[k + 1][load])
    hi = max(hi, (A[k][load] - up * (1 + 1e-12)).max(initial=0.0))     # alpha_n <= alpha(eps(rho_n))
    lo = max(lo, (down * (1 - 1e-12) - A[k][load]).max(initial=0.0))   # alpha(eps(rho_(n+1))) <= alpha_n
    checked += load.sum()
    e = E[k][load]
    for name, m in (("elastic", e >= ee), ("exponential", (e < ee) & (e >= ex)), ("power law", (e < ex) & (e > ec))):
        if m.any(): regimes.add(name)
print("%d snapshots, %d core particle-snapshots compacting checked; regimes seen: %s" % (len(A), checked, ", ".join(sorted(regimes))))
print("  alpha_n above alpha(eps(rho_n)) by at most %.3e, below alpha(eps(rho_(n+1))) by at most %.3e (<= 1e-12 relative)" % (hi, lo))
if checked < 1000 or hi > 0 or lo > 0 or len(regimes) < 3:
    print("FAIL: alpha does not follow the strain"); fail = 1
rise = np.diff(A, axis=0).max()
print("  largest increase of alpha between snapshots: %.3e; alpha in [%.6f, %.6f]" % (rise, A.min(), A.max()))
if rise > 0 or A.min() < 1.0 or A.max() > a0:
    print("FAIL: alpha increased or left [1, alpha_0]"); fail = 1
full = core & (A[-1] == 1.0) & (A[-2] == 1.0)
Pm = 2e10 / 4 * ((R[-1][full] / 2700.0)**4 - 1)
e = np.abs(P[-1][full] / Pm - 1).max() if full.any() else np.inf
print("  compacted core: %d of %d particles at alpha = 1; P against the Murnaghan matrix at the bulk density: %.2e (<= 1e-12)" % (full.sum(), core.sum(), e))
if full.sum() < core.sum() // 2 or not e <= 1e-12:
    print("FAIL: the core is not compacted to alpha = 1 with the matrix pressure"); fail = 1
sys.exit(fail)
PY
