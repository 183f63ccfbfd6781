#!/usr/bin/env bash
# Continuity density of a particle whose neighbours fly apart
# (theory/sph.md section 6, tasks/ghost/continuity_floor.h).
#
# A 10^3 lattice of equal-mass basalt particles (2700 kg/m^3) with one ice
# particle (917 kg/m^3, the same mass) at its centre expands homologously,
# v = H r, with no pressure (P_min = 0, cold, no strength): every density
# should fall as 1/(1 + H t)^3.  The rate dρ_i/dt = Σ m_j v_ij·∇W_ij of the
# ice particle is that of the basalt around it, three times its own, so its
# continuity density reaches zero at 1 + H t = (1 - 917/2700)^(-1/3) = 1.148
# (the failure of examples/CeresHitAndRun at contact); without a floor the
# relative-change time-step limit then collapses and the run stops at dt_min.
# Asserts: the run reaches 1 + H t = 2; every density is finite and at or
# above SPH:continuity_min_density_ratio (0.01) x rho0 of its material; the
# ice particle sits on its floor (the case was exercised); the inner basalt
# keeps following 2700/(1 + H t)^3 within 5%.
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$PYTHON" - <<'PY'
import h5py, numpy as np
n, dx, H = 10, 1.0, 1.0
g = (np.arange(n) - (n - 1) / 2) * dx
x, y, z = np.meshgrid(g, g, g, indexing="ij")
pos = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
N = len(pos)
mat = np.ones(N, dtype=np.int32)
ice = np.argmin(np.sum((pos - 0.25 * dx) ** 2, axis=1))  # one of the 8 central particles
mat[ice] = 2
rho = np.where(mat == 2, 917.0, 2700.0)
with h5py.File("lattice.hdf5", "w") as f:
    h = f.create_group("Header")
    h.attrs["BoxSize"] = [100.0, 100.0, 100.0]
    h.attrs["NumPart_Total"] = [N, 0, 0, 0, 0, 0]
    p = f.create_group("PartType0")
    p["Coordinates"] = pos + 50.0
    p["Velocities"] = H * pos
    p["Masses"] = np.full(N, 2700.0 * dx**3)
    p["SmoothingLengths"] = np.full(N, 1.2348 * dx)
    p["InternalEnergies"] = np.zeros(N)
    p["Densities"] = rho
    p["ParticleIDs"] = np.arange(1, N + 1)
    p["MaterialIDs"] = mat
PY
cat >p.yml <<'YML'
InitialConditions:
  file_name: lattice.hdf5
  periodic: false
TimeIntegration:
  time_end: 1.0
  dt_max: 0.01
  dt_min: 1e-6
Snapshots:
  basename: out
  delta_time: 0.5
SPH:
  density: continuity
  max_relative_change: 0.1
  viscosity_alpha: 1.0
Materials:
  1: {name: basalt, strength: none, P_min: 0}
  2: {name: ice, strength: none, P_min: 0}
YML
"$B/bolide" -t 2 p.yml >run.log 2>&1 || { echo "FAIL: run stopped"; tail -3 run.log; exit 1; }
"$PYTHON" - <<'PY'
import sys, h5py, numpy as np
f = h5py.File("out_0002.hdf5", "r")
t = f["Header"].attrs["Time"]
t = float(np.ravel(t)[0])
g = f["PartType0"]
rho, mat, pos = g["Densities"][:], g["MaterialIDs"][:], g["Coordinates"][:]
fail = 0
if abs(t - 1.0) > 1e-6:
    print(f"FAIL: last snapshot at t = {t}, not 1"); fail = 1
if not np.all(np.isfinite(rho)):
    print("FAIL: non-finite densities"); fail = 1
floor = np.where(mat == 2, 0.01 * 917.0, 0.01 * 2700.0)
low = rho < floor * (1 - 1e-12)
print(f"smallest density / floor: {np.min(rho / floor):.6g}; ice particle {rho[mat == 2][0]:.6g} kg/m^3 "
      f"(floor {0.01 * 917.0:g})")
if np.any(low):
    print(f"FAIL: {low.sum()} densities below the floor, smallest {rho[low].min():.3g}"); fail = 1
if not abs(rho[mat == 2][0] / (0.01 * 917.0) - 1.0) < 1e-9:
    print("FAIL: the ice particle did not reach its floor (case not exercised)"); fail = 1
c = np.mean(pos, axis=0)
r = np.linalg.norm(pos - c, axis=1)
inner = (mat == 1) & (r < 4.0)   # 1 + H t = 2: inside the original radius 2 dx
expect = 2700.0 / 8.0
dev = np.max(np.abs(rho[inner] / expect - 1.0))
print(f"inner basalt ({inner.sum()} particles): density / (2700/8) - 1 up to {dev:.3g}")
if inner.sum() < 8 or not dev < 0.05:
    print("FAIL: inner basalt does not follow 2700/(1 + H t)^3 within 5%"); fail = 1
sys.exit(fail)
PY
