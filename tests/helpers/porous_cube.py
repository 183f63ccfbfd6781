"""Initial conditions of the porous-cube tests (test_porosity_run.sh,
test_epsalpha_run.sh, test_gpu_run.sh): a 16^3 cubic lattice filling a 1 m
cube centred in a 4 m open box, squeezed isotropically (v = -RATE x), bulk
density RHO, u = 0, material 0, optional Distentions.

Usage: porous_cube.py OUT.hdf5 RHO RATE [ALPHA]"""
import sys

import h5py
import numpy as np


def write(name, rho, rate, alpha=None, n=16, L=1.0):
    dx = L / n
    g = (np.arange(n) + 0.5) * dx - 0.5 * L
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    pos = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    N = len(pos)
    with h5py.File(name, "w") as f:
        h = f.create_group("Header")
        h.attrs["BoxSize"] = [4.0, 4.0, 4.0]
        h.attrs["NumPart_Total"] = [N, 0, 0, 0, 0, 0]
        p = f.create_group("PartType0")
        p["Coordinates"] = pos + 2.0
        p["Velocities"] = -rate * pos
        p["Masses"] = np.full(N, rho * dx**3)
        p["SmoothingLengths"] = np.full(N, 1.2348 * dx)
        p["InternalEnergies"] = np.full(N, 0.0)
        p["Densities"] = np.full(N, rho)
        p["ParticleIDs"] = np.arange(1, N + 1)
        p["MaterialIDs"] = np.zeros(N, dtype=np.int32)
        if alpha is not None:
            p["Distentions"] = np.full(N, alpha)


if __name__ == "__main__":
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    write(sys.argv[1], float(sys.argv[2]), float(sys.argv[3]),
          float(sys.argv[4]) if len(sys.argv) == 5 else None)
