#!/usr/bin/env python3
"""Initial conditions of the Boss & Bodenheimer (1979) rotating, isothermal
cloud in the form of the "standard isothermal test case" (Burkert &
Bodenheimer 1993; Bate & Burkert 1997): M = 1 solar mass, R0 = 3.2e14 m,
rho0 = 1.44e-14 kg m^-3 (so M = 4/3 pi R0^3 rho0), solid-body rotation
Omega = 1.6e-12 s^-1 about z, and an m = 2 perturbation of amplitude 0.5
carried by the particle masses: m_i = m0 (1 + 0.5 cos 2 phi_i).  SI units.
Usage: make_ic.py N_ACROSS OUT.hdf5   (lattice points across the diameter;
40 gives about 33,500 particles)."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import ichelpers  # noqa: E402  (examples/common/ichelpers.py)

R0 = 3.2e14
RHO0 = 1.44e-14
OMEGA = 1.6e-12
AMP = 0.5


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: make_ic.py N_ACROSS OUT.hdf5")
    n = int(sys.argv[1])
    x, y, z, dx = ichelpers.centred_grid(n, R0)
    keep = x * x + y * y + z * z < R0 * R0
    pos = np.stack([x[keep], y[keep], z[keep]], axis=1)
    N = len(pos)
    mass = 4.0 / 3.0 * np.pi * R0 ** 3 * RHO0
    phi = np.arctan2(pos[:, 1], pos[:, 0])
    m = (1.0 + AMP * np.cos(2.0 * phi))
    m *= mass / m.sum()
    vel = np.zeros_like(pos)
    vel[:, 0] = -OMEGA * pos[:, 1]
    vel[:, 1] = OMEGA * pos[:, 0]
    box = 8.0 * R0
    ichelpers.write_ic(sys.argv[2], [box, box, box], {
        "Coordinates": pos + 0.5 * box,
        "Velocities": vel,
        "Masses": m,
        "SmoothingLengths": np.full(N, 1.2348 * dx),
        "InternalEnergies": np.zeros(N),
        "ParticleIDs": np.arange(1, N + 1, dtype=np.int64),
        "MaterialIDs": np.zeros(N, dtype=np.int32),
    })
    print("wrote %s: %d particles, M = %.4e kg" % (sys.argv[2], N, mass))


if __name__ == "__main__":
    main()
