#!/usr/bin/env python3
"""Initial conditions of the Evrard (1988) collapse: a cold, adiabatic gas
sphere of mass M = 1 and radius R = 1 (G = 1) with density rho = M / (2 pi R^2 r),
at rest, u = 0.05 G M / R, gamma = 5/3.

Particles of equal mass: a cubic lattice cut to a unit sphere, each radius
r0 mapped to r = R (r0 / R)^(3/2) so that the enclosed mass M(r) = M r^2 / R^2
of the 1/r profile holds (the mapping keeps the angular order of the lattice).
Usage: make_ic.py N_ACROSS OUT.hdf5   (N_ACROSS lattice points across the
diameter; 40 gives about 33,500 particles)."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import ichelpers  # noqa: E402  (examples/common/ichelpers.py)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: make_ic.py N_ACROSS OUT.hdf5")
    n = int(sys.argv[1])
    out = sys.argv[2]
    x, y, z, dx = ichelpers.centred_grid(n, 1.0)
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
    ichelpers.write_ic(out, [box, box, box], {
        "Coordinates": pos + 0.5 * box,
        "Velocities": np.zeros_like(pos),
        "Masses": m,
        "SmoothingLengths": h,
        "InternalEnergies": np.full(N, 0.05),
        "Densities": rho,
        "ParticleIDs": np.arange(1, N + 1, dtype=np.int64),
        "MaterialIDs": np.zeros(N, dtype=np.int32),
    })
    print("wrote %s: %d particles" % (out, N))


if __name__ == "__main__":
    main()
