#!/usr/bin/env python3
"""Initial conditions of the aluminium sphere on a plate (Hiermaier et al.
1997; theory/validation.md): an Al 6061-T6 sphere of 1 cm diameter at
6180 m/s, normal incidence, onto an Al 6061-T6 plate 0.4 cm thick, both on a
cubic lattice of spacing dx, rho = rho0 = 2710 kg/m^3, u = 0.  The plate is
a square of half-width `--half-width` (a full 3D plate: the code has no
symmetry planes); its top face is at z = 0 and the sphere starts one
lattice spacing above it, moving in -z.  Material ids: 0 plate,
1 projectile (both the `aluminium_6061` library entry).

The projectile's particle masses are scaled so that it has the mass of
the true sphere (the lattice sphere of a coarse run can be 20% heavier);
--lattice-mass keeps rho0 dx^3.

Usage: make_ic.py [--dx 0.0008] [-o plate.hdf5]  (SI units; an example
input, not part of bolide-ic)."""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import ichelpers  # noqa: E402  (examples/common/ichelpers.py)

RHO0 = 2710.0
R_P = 0.005
THICK = 0.004


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dx", type=float, default=0.0008, help="lattice spacing [m] (0.004 / dx layers)")
    ap.add_argument("--half-width", type=float, default=0.04, help="half-width of the plate [m]")
    ap.add_argument("--speed", type=float, default=6180.0, help="impact speed [m/s]")
    ap.add_argument("--eta", type=float, default=1.2348, help="h = eta dx")
    ap.add_argument("--lattice-mass", action="store_true",
                    help="keep rho0 dx^3 for the projectile's particles (default: scale them to the true sphere's mass)")
    ap.add_argument("-o", "--output", default="plate.hdf5")
    a = ap.parse_args()
    dx = a.dx
    nw = int(round(a.half_width / dx))
    nl = int(round(THICK / dx))
    # plate: cell-centred layers between z = -THICK and 0
    plate = ichelpers.lattice((-nw, -nw, -nl), (nw, nw, -1), dx) + [0, 0, 0.5 * dx]
    pj = ichelpers.lattice_ball(R_P, dx, 0.5 * dx)  # centred between lattice planes
    pj[:, 2] += R_P + dx
    pos = np.concatenate([plate, pj])
    n0, n1 = len(plate), len(pj)
    npp = n1
    vel = np.zeros_like(pos)
    vel[n0:, 2] = -a.speed
    mat = np.r_[np.zeros(n0, dtype=np.int32), np.ones(n1, dtype=np.int32)]
    span = 2 * a.half_width + 0.3
    box = np.array([span, span, 0.4])
    shift = np.array([0.5 * span, 0.5 * span, 0.3])
    pos += shift
    N = len(pos)
    fields = ichelpers.solid_fields(pos, vel, mat, RHO0, dx, a.eta, npp, R_P, a.lattice_mass)
    ichelpers.write_ic(a.output, box, fields)
    print(f"{a.output}: {N} particles ({n0} plate, {n1} projectile), dx = {dx} m, "
          f"{nl} layers, plate {2 * a.half_width * 100:.1f} cm wide")


if __name__ == "__main__":
    main()
