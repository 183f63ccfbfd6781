#!/usr/bin/env python3
"""Viscous decay of a shear wave through bolide (theory/fluids.md, "Tests").

A weakly compressible liquid (rho0 = 1, bulk modulus K0 = 100, so c0 = 10,
density: continuity) fills a periodic box of side 1 (an n x n x 8 cubic
lattice, dx = 1/n) and carries the shear wave v_x = V sin(k y), k = 2 pi,
V = 0.05.  The wave has div v = 0: the Navier-Stokes equations reduce to
the diffusion equation dv_x/dt = nu d^2 v_x/dy^2, whose solution keeps the
shape and decays as V exp(-nu k^2 t).  With dynamic viscosity eta = 0.02
(nu = 0.02, nu k^2 = 0.790) the run goes to t = 1 (amplitude down to 0.45).
Artificial viscosity is off (viscosity_alpha: 0) so that only the Newtonian
stress acts.  The density stays at rho0 and the pressure at the fluid's
floor 0, where the EOS's sound speed is 0 (material_eos): the time step is
the viscous diffusion limit (viscosity.h), whose stability this also checks.

Asserts, at n = 16 and n = 24:
  - the decay rate fitted to ln A(t) (A = 2/N sum v_x sin(k y), 11
    snapshots) is within 10% (n = 16, k h = 0.49) and 5% (n = 24,
    k h = 0.32) of nu k^2 (measured -5.9% and -2.8%: the SPH operator
    damps the wave's second derivative by O((k h)^2)), and the error falls
    at least as fast as 0.6 from n = 16 to n = 24 (second order: 0.44,
    measured 0.49);
  - the wave keeps its shape: the residual of v_x against A(t) sin(k y)
    stays below 1% of A and the velocity across it (v_y, v_z) below 1% of V
    (measured 3e-4 and 1.1e-3);
  - the kinetic energy lost is found as heat: the statistics' |dE| stays
    below 1% of it (measured 1e-4);
  - the inviscid control (eta = 0, n = 16) keeps its amplitude: the fitted
    rate is below 1% of nu k^2, so the decay is the viscosity's, not the
    scheme's."""
import glob
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

build = os.environ.get("BOLIDE_BUILDDIR", ".")
bolide = os.path.join(build, "bolide")
NZ = 8
V0, K, ETA, T_END = 0.05, 2.0 * np.pi, 0.02, 1.0


def make_ic(path, N1):
    DX = 1.0 / N1
    g = (np.arange(N1) + 0.5) * DX
    gz = (np.arange(NZ) + 0.5) * DX
    x, y, z = np.meshgrid(g, g, gz, indexing="ij")
    pos = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    N = len(pos)
    vel = np.zeros_like(pos)
    vel[:, 0] = V0 * np.sin(K * pos[:, 1])
    with h5py.File(path, "w") as f:
        h = f.create_group("Header")
        h.attrs["BoxSize"] = [1.0, 1.0, NZ * DX]
        h.attrs["NumPart_Total"] = [N, 0, 0, 0, 0, 0]
        h.attrs["Dimension"] = 3
        p = f.create_group("PartType0")
        p["Coordinates"] = pos
        p["Velocities"] = vel
        p["Masses"] = np.full(N, DX**3)
        p["SmoothingLengths"] = np.full(N, 1.2348 * DX)
        p["InternalEnergies"] = np.zeros(N)
        p["Densities"] = np.ones(N)
        p["ParticleIDs"] = np.arange(1, N + 1)
        p["MaterialIDs"] = np.zeros(N, dtype=np.int32)
    return N


PARAMS = """
InitialConditions: {{file_name: {ic}, periodic: true}}
TimeIntegration: {{time_end: {t_end}}}
Snapshots: {{basename: wave, subdir: out_{tag}, delta_time: {dt_snap}}}
Statistics: {{delta_time: {dt_snap}}}
SPH:
  density: continuity
  # h of 1.2348 spacings whatever the build's kernel: k h at the two
  # resolutions (0.35 and 0.23) is what the bounds below were set for; the
  # default Wendland C2 eta 1.7 widens h by 1.38 and needs 1.38 times the
  # particles per wavelength for the same smoothing error
  resolution_eta: 1.2348
  viscosity_alpha: 0.0
Materials:
  0: {{name: fluid, eos: liquid, rho0: 1.0, K0: 100.0, viscosity: {eta}}}
"""


def run(d, N1, eta, tag):
    ic = f"wave{N1}.hdf5"
    make_ic(os.path.join(d, ic), N1)
    with open(os.path.join(d, f"{tag}.yml"), "w") as f:
        f.write(PARAMS.format(ic=ic, t_end=T_END, tag=tag, dt_snap=T_END / 10, eta=eta))
    r = subprocess.run([bolide, "-t", "2", f"{tag}.yml"], cwd=d, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-2000:])
        sys.exit(1)
    t, A, shape, normal = [], [], 0.0, 0.0
    for fn in sorted(glob.glob(os.path.join(d, f"out_{tag}", "wave_*.hdf5"))):
        with h5py.File(fn, "r") as f:
            time = f["Header"].attrs["Time"]
            time = float(np.ravel(time)[0])
            pos = f["PartType0/Coordinates"][:]
            vel = f["PartType0/Velocities"][:]
        s = np.sin(K * pos[:, 1])
        a = 2.0 * np.mean(vel[:, 0] * s)
        t.append(time)
        A.append(a)
        shape = max(shape, np.max(np.abs(vel[:, 0] - a * s)) / abs(a))
        normal = max(normal, np.max(np.abs(vel[:, 1:])) / V0)
    t, A = np.array(t), np.array(A)
    rate = -np.polyfit(t, np.log(A), 1)[0]
    st = np.loadtxt(os.path.join(d, f"out_{tag}", "statistics.txt"))
    dEkin = st[0, 10] - st[-1, 10]
    dE = np.max(np.abs(st[:, 26]))
    return rate, shape, normal, dEkin, dE, int(st[-1, 0])


def main():
    exact = ETA / 1.0 * K**2
    ok = True
    errs = {}
    with tempfile.TemporaryDirectory() as d:
        for n1, bound in ((16, 0.10), (24, 0.05)):
            rate, shape, normal, dEkin, dE, steps = run(d, n1, ETA, f"visc{n1}")
            err = errs[n1] = rate / exact - 1.0
            print(f"shear wave, {n1} x {n1} x {NZ} = {n1 * n1 * NZ} particles, k h = {K * 1.2348 / n1:.3f}, "
                  f"{steps} steps:")
            print(f"  decay rate {rate:.5f}, nu k^2 = {exact:.5f}, relative error {err:+.4f} (bound {bound})")
            print(f"  shape residual {shape:.2e} of A (bound 1e-2), normal velocity {normal:.2e} V (bound 1e-2)")
            print(f"  kinetic energy lost {dEkin:.4e}, energy budget |dE| {dE:.2e} (bound 1% of the loss)")
            ok &= abs(err) < bound and shape < 1e-2 and normal < 1e-2 and dEkin > 0.0 and dE < 0.01 * dEkin
        rate0, _, _, _, _, steps0 = run(d, 16, 0.0, "inviscid")
    conv = abs(errs[24]) / abs(errs[16])
    print(f"error ratio 24 / 16: {conv:.3f} (second order: 0.44; bound 0.6)")
    print(f"inviscid control, 16 x 16 x {NZ}, {steps0} steps: decay rate {rate0:.2e} "
          f"({rate0 / exact:.2e} nu k^2, bound 1e-2)")
    ok &= conv < 0.6 and abs(rate0) < 0.01 * exact
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
