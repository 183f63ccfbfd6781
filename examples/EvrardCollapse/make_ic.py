#!/usr/bin/env python3
"""Initial conditions of the Evrard (1988) collapse: a cold, adiabatic gas
sphere of mass M = 1 and radius R = 1 (G = 1) with density rho = M / (2 pi R^2 r),
at rest, u = 0.05 G M / R, gamma = 5/3.

Particles of equal mass: a cubic lattice cut to a unit sphere, each radius
r0 mapped to r = R (r0 / R)^(3/2) so that the enclosed mass M(r) = M r^2 / R^2
of the 1/r profile holds (the mapping keeps the angular order of the lattice).
Usage: make_ic.py N_ACROSS OUT.hdf5   (N_ACROSS lattice points across the
diameter; 40 gives about 33,500 particles)."""
import sys

import h5py
import numpy as np


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: make_ic.py N_ACROSS OUT.hdf5")
    n = int(sys.argv[1])
    out = sys.argv[2]
    dx = 2.0 / n
    g = (np.arange(n) + 0.5) * dx - 1.0
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    r0 = np.sqrt(x * x + y * y + z * z)
    keep = r0 < 1.0
    pos0 = np.stack([x[keep], y[keep], z[keep]], axis=1)
    r0 = r0[keep]
    r = r0 ** 1.5
    pos = pos0 * (r / r0)[:, None]
    N = len(pos)
    m = np.full(N, 1.0 / N)
    rho = 1.0 / (2.0 * np.pi * np.maximum(r, 1e-3))
    h = 1.2348 * (m / rho) ** (1.0 / 3.0)
    box = 24.0  # wide: the outgoing shock throws gas beyond r = 4 after t = 2
    with h5py.File(out, "w") as f:
        hd = f.create_group("Header")
        hd.attrs["BoxSize"] = [box, box, box]
        hd.attrs["NumPart_Total"] = [N, 0, 0, 0, 0, 0]
        hd.attrs["Dimension"] = 3
        p = f.create_group("PartType0")
        p["Coordinates"] = pos + 0.5 * box
        p["Velocities"] = np.zeros_like(pos)
        p["Masses"] = m
        p["SmoothingLengths"] = h
        p["InternalEnergies"] = np.full(N, 0.05)
        p["Densities"] = rho
        p["ParticleIDs"] = np.arange(1, N + 1, dtype=np.int64)
        p["MaterialIDs"] = np.zeros(N, dtype=np.int32)
    print("wrote %s: %d particles" % (out, N))


if __name__ == "__main__":
    main()
