#!/usr/bin/env python3
"""Initial conditions of the colliding rubber rings (Gray, Monaghan & Swift
2001, CMAME 190, 6641, Sec. 5.3; theory/validation.md): two rings of
inner radius 3 cm and outer radius 4 cm, here short tubes of a given
thickness in z (the paper is 2D), on a cubic lattice of spacing dx, moving
towards each other at +-0.059 c0 (c0 = 852 m/s), rho = rho0 = 1010 kg/m^3,
material id 0 (the `rubber` entry of examples/materials.yml).

With --periodic-z the box is periodic and exactly one ring thickness tall
in z, so that the tubes have no free faces in z: plane strain, the 2D
problem of the paper (the thickness must then exceed twice the kernel
radius, 2.3 dx with the default eta).

Usage: make_ic.py [--dx 0.0025] [--thickness 0.01] [--periodic-z] [-o rings.hdf5]
(SI units; an example input, not part of bolide-ic)."""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import ichelpers  # noqa: E402  (examples/common/ichelpers.py)

RHO0 = 1010.0
C0 = 852.0
R_IN, R_OUT = 0.03, 0.04


def ring(dx, thickness):
    n = int(np.ceil(R_OUT / dx)) + 1
    g = (np.arange(-n, n + 1)) * dx
    nz = max(1, int(round(thickness / dx)))
    gz = (np.arange(nz) - 0.5 * (nz - 1)) * dx
    x, y, z = np.meshgrid(g, g, gz, indexing="ij")
    pos = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    r = np.hypot(pos[:, 0], pos[:, 1])
    return pos[(r >= R_IN) & (r < R_OUT)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dx", type=float, default=0.0025, help="lattice spacing [m]")
    ap.add_argument("--thickness", type=float, default=0.01, help="ring thickness in z [m]")
    ap.add_argument("--speed", type=float, default=0.059, help="speed of each ring in units of c0")
    ap.add_argument("--eta", type=float, default=1.2348, help="h = eta dx")
    ap.add_argument("--periodic-z", action="store_true",
                    help="periodic box one thickness tall in z (plane strain; run with InitialConditions:periodic: true)")
    ap.add_argument("-o", "--output", default="rings.hdf5")
    a = ap.parse_args()
    one = ring(a.dx, a.thickness)
    # centres 2 R_OUT + dx apart: the rings start one lattice spacing apart
    xc = R_OUT + 0.5 * a.dx
    box = np.array([0.6, 0.2, 0.1])  # room for the rebound: no particle leaves the open box by 4 ms
    if a.periodic_z:
        box[2] = max(1, int(round(a.thickness / a.dx))) * a.dx
    pos = np.concatenate([one + [-xc, 0, 0], one + [xc, 0, 0]]) + 0.5 * box
    n1 = len(one)
    vel = np.zeros_like(pos)
    vel[:n1, 0] = a.speed * C0
    vel[n1:, 0] = -a.speed * C0
    N = len(pos)
    ichelpers.write_ic(a.output, box, {
        "Coordinates": pos,
        "Velocities": vel,
        "Masses": np.full(N, RHO0 * a.dx**3),
        "SmoothingLengths": np.full(N, a.eta * a.dx),
        "InternalEnergies": np.zeros(N),
        "Densities": np.full(N, RHO0),
        "ParticleIDs": np.arange(1, N + 1),
        "MaterialIDs": np.zeros(N, dtype=np.int32),
    })
    print(f"{a.output}: {N} particles ({n1} per ring), dx = {a.dx} m, ring speed {a.speed * C0:.1f} m/s")


if __name__ == "__main__":
    main()
