#!/usr/bin/env bash
# The conservation budget with the defaults (theory/sph.md, "Conservation
# budget"; issue 17): no floor or clamp may create energy in a
# strengthless planetary run (tests/unit/test_budget.c checks the counting of
# the one that may, the kick's floor on u of ideal gases and tables).
#
# 1. A jittered-lattice sphere of Tillotson granite (2,000 particles, SWIFT
#    id 101 with the library's defaults, u = 237 kJ/kg, no gravity) left to
#    expand for 200 s.  With the defaults (no tension without strength) the
#    energy E_tot = E_kin + E_int must stay within 5e-4 of E(0) and E_clamp
#    must be 0 (measured: 2.9e-4 with the default kernel, Wendland C2 at
#    eta 1.7; 1.9e-4 with the cubic spline at 1.2348; 0 with both).  With
#    the EOS's tension kept (P_min: -1e30) the surface particles oscillate between tension and
#    compression and their energy goes below 0; the kick used to halve it
#    instead, and the energy grew by 17% of E(0) (4.8% for 22,000 particles
#    of the reference impact, the fault of issue 17).  Now Tillotson takes
#    u < 0 as u = 0 and the kick keeps it: within 2e-2 of E(0), an order
#    of magnitude below what the floor made (measured: at most 5.2e-3
#    during the run, 5.7e-3 with the cubic spline, the time-integration
#    error of the oscillating surface), E_clamp 0.
# 2. The planetary reference impact in small (bolide-ic impact: granite
#    spheres of 2,000 and 200 particles, 2 km/s at 45 degrees, hydro +
#    self-gravity, the defaults, box for --time-end) to t = 4000 s: the
#    issue's bounds |dE| <= 5e-4 |E_pot(0)| (no term subtracted: E_tot plus
#    what left the box) and |dL| / |L| <= 1e-4 (measured 3.6e-4, 2.0e-7
#    with Wendland C2 at eta 1.7, 2.9e-4, 6.8e-7 with the cubic spline at
#    1.2348, commit 418a1e6; SWIFT's 5.6e-4 at 22,000 particles).
# 3. The same impact in time bins with TimeIntegration:limiter_wake:
#    density (issue 20): the energy within the same 5e-4 (measured 2.0e-4,
#    one thread; with the force loop's wake, the default, 8.3e-4: the
#    bound sees the difference), the angular momentum about the start's
#    centre of mass within 1e-3 and the momentum within 2e-3 of
#    sum m|v|(0) (measured 2.0e-4 and 7.7e-4: time bins do not exchange
#    the pairs' impulses at once, theory/sph.md section 8; SWIFT's bins lose
#    4e-4 to 7e-4 of the impactor's momentum at 22,000 particles).
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; exit 1; }

"${PYTHON:?}" - <<'PY' || fail "lattice sphere"
import numpy as np, h5py
n, R, rho0, u0 = 2000, 1.0e6, 2680.0, 237000.0
rng = np.random.default_rng(1)
dx = (4.0 / 3.0 * np.pi * R**3 / n) ** (1.0 / 3.0)
k = int(np.ceil(R / dx)) + 2
g = (np.arange(-k, k + 1) + 0.5) * dx
X = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
X = X[np.argsort(np.linalg.norm(X, axis=1), kind="stable")[:n]]
X += rng.uniform(-0.05, 0.05, X.shape) * dx
L = 40 * R
with h5py.File("lattice.hdf5", "w") as f:
    h = f.create_group("Header")
    h.attrs["BoxSize"] = [L, L, L]
    h.attrs["NumPart_Total"] = [n, 0, 0, 0, 0, 0]
    h.attrs["Time"] = 0.0
    p = f.create_group("PartType0")
    p["Coordinates"] = X + L / 2
    p["Velocities"] = np.zeros((n, 3))
    p["Masses"] = np.full(n, rho0 * dx**3)
    p["SmoothingLengths"] = np.full(n, 1.2348 * dx)
    p["InternalEnergies"] = np.full(n, u0)
    p["MaterialIDs"] = np.full(n, 101, dtype=np.int32)
    p["ParticleIDs"] = np.arange(1, n + 1, dtype=np.int64)
PY
cat >sphere.yml <<'YML'
InitialConditions:
  file_name: lattice.hdf5
TimeIntegration:
  time_end: 200
Snapshots:
  subdir: default
  delta_time: 1e30
Statistics:
  delta_time: 20
Materials:
  101: {}
SPH:
  resolution_eta: 1.2348
YML
"$B/bolide" --no-gpu -t 2 sphere.yml >default.log 2>&1 || { tail -3 default.log; fail "default run"; }
sed -e 's/101: {}/101: {P_min: -1e30}/' -e 's/subdir: default/subdir: tension/' sphere.yml >tension.yml
"$B/bolide" --no-gpu -t 2 tension.yml >tension.log 2>&1 || { tail -3 tension.log; fail "run with tension"; }

# columns by the names of the header line
"$PYTHON" - <<'PY' || fail "budget"
import numpy as np

def read(path):
    names = None
    for line in open(path):
        if line.startswith("# step"):
            names = line[1:].split()
    d = np.loadtxt(path, comments="#", ndmin=2)
    return {k: d[:, i] for i, k in enumerate(names)}

d = read("default/statistics.txt")
E0 = d["E_tot"][0]
drift = np.max(np.abs(d["E_tot"] + d["E_removed"] - E0)) / abs(E0)
clamp = np.max(np.abs(d["E_clamp"])) / abs(E0)
print(f"defaults: max |E_tot - E(0)| / E(0) = {drift:.3e} (bound 5e-4), E_clamp / E(0) = {clamp:.3e} (must be 0)")
assert drift <= 5e-4 and clamp == 0.0

t = read("tension/statistics.txt")
E0 = t["E_tot"][0]
drift = np.max(np.abs(t["E_tot"] + t["E_removed"] - E0)) / abs(E0)
clamp = np.max(np.abs(t["E_clamp"])) / abs(E0)
print(f"tension kept: max |E_tot - E(0)| / E(0) = {drift:.3e} (bound 2e-2; 0.17 with the old floor on u), "
      f"E_clamp / E(0) = {clamp:.3e} (must be 0)")
assert drift <= 2e-2 and clamp == 0.0
assert np.allclose(t["dE"], t["E_tot"] + t["E_removed"] - t["E_clamp"] - E0, rtol=1e-6,
                   atol=1e-9 * abs(E0)), "column dE is not E_tot + E_removed - E_clamp - E_tot(0)"
PY

"$B/bolide-ic" impact --target sphere,material=granite,radius=1e6,n=2000,u=237000 \
  --impactor sphere,material=granite,radius=4.642e5,n=200,u=237000 --v-contact 2000 --angle 45 \
  --separation 1.52e6 --time-end 4000 -o impact.hdf5 >ic.log 2>&1 || { tail -3 ic.log; fail "bolide-ic impact"; }
grep -q "impact: box .* for --time-end 4000 s" ic.log || fail "bolide-ic impact does not state its box"
cat >impact.yml <<'YML'
InitialConditions:
  file_name: impact.hdf5
TimeIntegration:
  time_end: 4000
Snapshots:
  subdir: impact
  delta_time: 1e30
Statistics:
  delta_time: 200
Materials:
  101: {}
SPH:
  resolution_eta: 1.2348
  CFL_condition: 0.2
  viscosity_alpha: 1.5
Gravity:
  enabled: true
  theta_cr: 0.5
  softening: 1.28e5
YML
# the budget of the impact run in SUBDIR (its log LOG): the global step's
# bounds, or (MODE bins) those of time bins with limiter_wake: density
cat >impact_budget.py <<'PY'
import re
import sys
import numpy as np
subdir, log, mode = sys.argv[1:4]
names = None
for line in open(subdir + "/statistics.txt"):
    if line.startswith("# step"):
        names = line[1:].split()
d = np.loadtxt(subdir + "/statistics.txt", comments="#", ndmin=2)
c = {k: d[:, i] for i, k in enumerate(names)}
assert abs(c["time"][-1] - 4000) < 1e-6, "the run did not reach t = 4000 s"
Epot0 = abs(c["E_pot"][0])
dE = np.max(np.abs(c["E_tot"] + c["E_removed"] - c["E_tot"][0])) / Epot0
if mode == "global":
    L = np.stack([c["Lx"] + c["Lx_removed"], c["Ly"] + c["Ly_removed"], c["Lz"] + c["Lz_removed"]], 1)
    dL = np.max(np.linalg.norm(L - L[0], axis=1)) / np.linalg.norm(L[0])
    print(f"reference impact, 2,200 particles, to 4000 s: max |dE| / |E_pot(0)| = {dE:.3e} (bound 5e-4), "
          f"max |dL| / |L| = {dL:.3e} (bound 1e-4), {int(c['n_removed'][-1])} particles left the box")
    assert dE <= 5e-4 and dL <= 1e-4
else:
    text = open(log).read()
    dLc = float(re.search(r"\|dL\| / \|L\(0\)\| = ([0-9.e+-]+) about the centre of mass", text).group(1))
    dp = float(re.search(r"\|dp\| / sum m\|v\|\(0\) = ([0-9.e+-]+)", text).group(1))
    print(f"reference impact in time bins (limiter_wake density): max |dE| / |E_pot(0)| = {dE:.3e} "
          f"(bound 5e-4), |dL| / |L| about the centre of mass {dLc:.3e} (bound 1e-3), |dp| / sum m|v| "
          f"{dp:.3e} (bound 2e-3)")
    assert dE <= 5e-4 and dLc <= 1e-3 and dp <= 2e-3
PY
"$B/bolide" --no-gpu -t 2 impact.yml >impact.log 2>&1 || { tail -3 impact.log; fail "impact run"; }
grep "conservation budget" impact.log
grep -q "conservation budget against the start: dE / |E_pot(0)|" impact.log || fail "no budget summary"
"$PYTHON" impact_budget.py impact impact.log global || fail "impact budget"

"$B/bolide" --no-gpu -t 2 impact.yml -P TimeIntegration:global_step:false \
  -P TimeIntegration:limiter_wake:density -P Snapshots:subdir:impact_bins >bins.log 2>&1 ||
  { tail -3 bins.log; fail "impact run in time bins"; }
grep -q "time bins: .* particle updates" bins.log || fail "the bins run did not run in time bins"
grep "conservation budget" bins.log
"$PYTHON" impact_budget.py impact_bins bins.log bins || fail "impact budget in time bins"
echo PASS
