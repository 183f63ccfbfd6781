#!/usr/bin/env python3
"""SPH:h_evolution (issue 24 item 4): the smoothing length of a graded body
from the neighbour-number iteration (iterate, the default) or from
dh/dt = -h/(3 rho) drho/dt (continuity), theory/sph.md section 2.

A graded body: a periodic box holds a slab of fine particles (a cubic
lattice of spacing d, mass rho0 d^3, 16 x NY x NY) next to a slab of coarse
ones (spacing 2 d, mass 8 rho0 d^3, 8 x NY/2 x NY/2), so that the box has
two interfaces with a size jump of 2 and no free surface.  A weakly
compressible liquid (rho0 = 1, c0 = 10) with density: continuity; h starts
at eta (m/rho0)^(1/3), eta SPH:resolution_eta's default.  Two cases, each
run to t = 0.01 (about ten steps) under each option: at rest, and with a
velocity wave v_x = VWAVE sin(2 pi x / L) (|rho/rho0 - 1| reaches 7%).

Asserts, for both options (h* = eta (m/rho)^(1/3), rho the snapshot's):
  - at rest the body stays at rest: every |v| <= 1e-12 c0 (rho stays rho0,
    P = 0); the wave compresses by more than 1%;
  - continuity: |h/h* - 1| <= 1e-12 at rest (dh/dt = 0), <= BOUND_WAVE
    (1e-3; measured 3.6e-4) in the wave, for every particle; a wrong sign or
    factor in dh/dt = -h/(3 rho) drho/dt would be off by several %;
  - iterate: |h/h* - 1| <= 1% for the particles more than 2 x 2 eta d (a
    coarse support; kernel_gamma < 2) from the interfaces (the lattice's
    neighbour number; measured 8e-4), and <= BOUND_IFACE (30%) for all: the
    iteration solves for the number density n = sum_j W_ij, not for m/rho,
    so near an interface a coarse particle counts the fine ones and takes a
    smaller h, a fine particle a larger one (measured with Wendland C2:
    -26.5% on the first coarse layer, +10.6% on the first fine one)."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

build = os.environ.get("BOLIDE_BUILDDIR", ".")
bolide = os.path.join(build, "bolide")
ic = os.path.join(build, "bolide-ic")
NY = 24
D = 1.0 / 16
RHO0, C0 = 1.0, 10.0
BOUND_BULK = 0.01
BOUND_IFACE = 0.30
BOUND_WAVE = 1e-3
VWAVE = 2.0


def eta_default():
    out = subprocess.run([ic, "import-mesh", "--help"], capture_output=True, text=True).stdout
    return float(out.split("SPH:resolution_eta's, ")[1].split(")")[0])


def make_ic(path, eta, vamp=0.0):
    f1 = (np.arange(16) + 0.5) * D
    fy = (np.arange(NY) + 0.5) * D
    fine = np.stack(np.meshgrid(f1, fy, fy, indexing="ij"), -1).reshape(-1, 3)
    c1 = 16 * D + (np.arange(8) + 0.5) * 2 * D
    cy = (np.arange(NY // 2) + 0.5) * 2 * D
    coarse = np.stack(np.meshgrid(c1, cy, cy, indexing="ij"), -1).reshape(-1, 3)
    pos = np.concatenate([fine, coarse])
    V = np.concatenate([np.full(len(fine), D**3), np.full(len(coarse), 8 * D**3)])
    N = len(pos)
    with h5py.File(path, "w") as f:
        h = f.create_group("Header")
        h.attrs["BoxSize"] = [32 * D, NY * D, NY * D]
        h.attrs["NumPart_Total"] = [N, 0, 0, 0, 0, 0]
        h.attrs["Dimension"] = 3
        p = f.create_group("PartType0")
        p["Coordinates"] = pos
        vel = np.zeros_like(pos)
        vel[:, 0] = vamp * np.sin(2 * np.pi * pos[:, 0] / (32 * D))
        p["Velocities"] = vel
        p["Masses"] = RHO0 * V
        p["SmoothingLengths"] = eta * np.cbrt(V)
        p["InternalEnergies"] = np.zeros(N)
        p["Densities"] = np.full(N, RHO0)
        p["ParticleIDs"] = np.arange(1, N + 1)
        p["MaterialIDs"] = np.zeros(N, dtype=np.int32)
    return pos


PARAMS = """
InitialConditions: {{file_name: {case}.hdf5, periodic: true}}
TimeIntegration: {{time_end: 0.01}}
Snapshots: {{basename: graded, subdir: out_{case}_{mode}, delta_time: 0.01}}
SPH:
  density: continuity
  h_evolution: {mode}
Materials:
  0: {{name: water, eos: liquid, rho0: 1.0, c0: 10.0}}
"""


def run(d, case, mode):
    with open(os.path.join(d, f"{case}_{mode}.yml"), "w") as f:
        f.write(PARAMS.format(case=case, mode=mode))
    r = subprocess.run([bolide, "-t", "2", f"{case}_{mode}.yml"], cwd=d, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-2000:])
        sys.exit(1)
    with h5py.File(os.path.join(d, f"out_{case}_{mode}", "graded_0001.hdf5"), "r") as f:
        g = f["PartType0"]
        o = np.argsort(g["ParticleIDs"][:])
        t = float(np.ravel(f["Header"].attrs["Time"])[0])
        return t, {k: g[k][:][o] for k in ("Velocities", "SmoothingLengths", "Masses", "Densities")}


def main():
    eta = eta_default()
    bad = 0

    def check(c, msg):
        nonlocal bad
        print(("ok   " if c else "FAIL ") + msg)
        bad += not c

    with tempfile.TemporaryDirectory() as d:
        pos = make_ic(os.path.join(d, "rest.hdf5"), eta)
        make_ic(os.path.join(d, "wave.hdf5"), eta, VWAVE)
        # distance to the nearer interface (x = 0 = 32 d and x = 16 d)
        xi = pos[:, 0]
        dist = np.minimum.reduce([np.abs(xi), np.abs(xi - 16 * D), np.abs(xi - 32 * D)])
        bulk = dist > 2.0 * 2 * eta * D  # a coarse support: kernel_gamma < 2 for every kernel
        for case in ("rest", "wave"):
            for mode in ("iterate", "continuity"):
                t, s = run(d, case, mode)
                v = np.abs(s["Velocities"]).max()
                hstar = eta * np.cbrt(s["Masses"] / s["Densities"])
                e = s["SmoothingLengths"] / hstar - 1
                fine = s["Masses"] < 2 * RHO0 * D**3
                drho = np.abs(s["Densities"] / RHO0 - 1).max()
                print(f"{case}, {mode}: t = {t:.4g}, max |v| = {v:.3g}, max |rho/rho0 - 1| = "
                      f"{drho:.3g}, h/h* - 1: fine [{e[fine].min():+.4f}, {e[fine].max():+.4f}], "
                      f"coarse [{e[~fine].min():+.4f}, {e[~fine].max():+.4f}], "
                      f"bulk ({bulk.sum()}) max |.| {np.abs(e[bulk]).max():.2e}")
                for lo, hi in ((0, 1), (1, 2), (2, 4), (4, 8)):
                    sel = (dist >= lo * D) & (dist < hi * D)
                    for name, m in (("fine", sel & fine), ("coarse", sel & ~fine)):
                        if m.any():
                            print(f"   {lo}-{hi} d from an interface, {name:6s}: h/h* - 1 in "
                                  f"[{e[m].min():+.4f}, {e[m].max():+.4f}]")
                check(t > 0.0099, f"{case}, {mode}: ran to t = 0.01")
                if case == "rest":
                    check(v <= 1e-12 * C0, f"{case}, {mode}: at rest (max |v| {v:.3g})")
                else:
                    check(drho > 0.01, f"{case}, {mode}: the wave compresses (|drho/rho| {drho:.3g} > 1%)")
                if mode == "continuity":
                    bound = 1e-12 if case == "rest" else BOUND_WAVE
                    check(np.abs(e).max() <= bound,
                          f"{case}, {mode}: |h/h* - 1| = {np.abs(e).max():.2e} <= {bound:g} everywhere")
                else:
                    check(np.abs(e[bulk]).max() <= BOUND_BULK and np.abs(e).max() <= BOUND_IFACE,
                          f"{case}, {mode}: |h/h* - 1| = {np.abs(e[bulk]).max():.2e} <= {BOUND_BULK:g} "
                          f"in the bulk, {np.abs(e).max():.3f} <= {BOUND_IFACE:g} everywhere")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
