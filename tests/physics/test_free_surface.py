#!/usr/bin/env python3
"""Free-surface detection through bolide (theory/fluids.md, "Free surface").

A cube of weakly compressible liquid (rho0 = 1, c0 = 10), a 12 x 12 x 12
cubic lattice (dx = 1/12) in an open box, starts at rest, slightly
compressed: the initial conditions give it the density 1.01 rho0, so that
with density: continuity every particle has P = c0^2 (0.01 rho0) = 1 > 0.
One step is run with SPH:free_surface on and once with it off; the pressures
of the snapshot at the end (those the force loop used) are compared.

Asserts:
  - with the detection on, every particle of the outer layer (the faces,
    edges and corners of the lattice, 728 particles) has P = 0 exactly;
  - no particle below the outer layer (depth >= 1 lattice spacing, 1000
    particles, whose kernel sum is about 1) has P = 0, and every one keeps
    P within 1% of 1;
  - with the detection off (the default) no particle has P = 0.
The kernel sums of the layers on a lattice (cubic spline, eta = 1.2348):
at the initial h, faces 0.81, edges 0.66, corners 0.53, one layer deep
1.002; after the h iteration (larger h at the surface) the faces are
between 0.75 and 0.8 (the whole outer layer is marked at a threshold of
0.8, only edges and corners at 0.75).  The default threshold 0.9 is used."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

build = os.environ.get("BOLIDE_BUILDDIR", ".")
bolide = os.path.join(build, "bolide")
N1 = 12
DX = 1.0 / N1


def make_ic(path):
    g = (np.arange(N1) + 0.5) * DX + 0.5
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    pos = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    N = len(pos)
    with h5py.File(path, "w") as f:
        h = f.create_group("Header")
        h.attrs["BoxSize"] = [2.0, 2.0, 2.0]
        h.attrs["NumPart_Total"] = [N, 0, 0, 0, 0, 0]
        h.attrs["Dimension"] = 3
        p = f.create_group("PartType0")
        p["Coordinates"] = pos
        p["Velocities"] = np.zeros_like(pos)
        p["Masses"] = np.full(N, 1.01 * DX**3)
        p["SmoothingLengths"] = np.full(N, 1.2348 * DX)
        p["InternalEnergies"] = np.zeros(N)
        p["Densities"] = np.full(N, 1.01)
        p["ParticleIDs"] = np.arange(1, N + 1)
        p["MaterialIDs"] = np.zeros(N, dtype=np.int32)
    # depth of each particle below the surface, in lattice spacings
    k = np.rint((pos - 0.5) / DX - 0.5).astype(int)
    return np.minimum(k, N1 - 1 - k).min(axis=1)


PARAMS = """
InitialConditions: {{file_name: block.hdf5, periodic: false}}
TimeIntegration: {{time_end: 1e-3}}
Snapshots: {{basename: block, subdir: out_{tag}, delta_time: 1e-3}}
SPH:
  density: continuity
  free_surface: {on}
Materials:
  0: {{name: water, eos: liquid, rho0: 1.0, c0: 10.0}}
"""


def run(d, on):
    tag = "on" if on else "off"
    with open(os.path.join(d, f"{tag}.yml"), "w") as f:
        f.write(PARAMS.format(tag=tag, on="true" if on else "false"))
    r = subprocess.run([bolide, "-t", "2", f"{tag}.yml"], cwd=d, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-2000:])
        sys.exit(1)
    with h5py.File(os.path.join(d, f"out_{tag}", "block_0001.hdf5"), "r") as f:
        ids = f["PartType0/ParticleIDs"][:]
        P = f["PartType0/Pressures"][:]
    out = np.empty_like(P)
    out[ids - 1] = P
    return out


def main():
    with tempfile.TemporaryDirectory() as d:
        depth = make_ic(os.path.join(d, "block.hdf5"))
        P_on = run(d, True)
        P_off = run(d, False)
    surf, inner = depth == 0, depth >= 1
    print(f"free surface, {N1}^3 block: {surf.sum()} particles in the outer layer, {inner.sum()} below it")
    for dd in range(0, 4):
        sel = depth == dd
        print(f"  depth {dd}: {np.sum(P_on[sel] == 0.0):4d} of {sel.sum():4d} with P = 0; "
              f"P in [{P_on[sel].min():.5f}, {P_on[sel].max():.5f}]")
    print(f"  detection off: {np.sum(P_off == 0.0)} with P = 0, P in [{P_off.min():.5f}, {P_off.max():.5f}]")
    ok = (np.all(P_on[surf] == 0.0) and not np.any(P_on[inner] == 0.0)
          and np.all(np.abs(P_on[inner] - 1.0) < 0.01) and not np.any(P_off == 0.0))
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
