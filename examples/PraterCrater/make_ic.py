#!/usr/bin/env python3
"""Initial conditions of the Prater crater (Prater 1970;
theory/validation.md, "Prater crater"; Pierazzo et al. 2008): an Al 6061 sphere of 6.35 mm
diameter (the 1/4-inch ball of the experiments; `--radius`, default
3.175 mm) at 7 km/s, normal incidence, onto a block of aluminium, both on a cubic lattice of spacing dx,
rho = rho0 = 2700 kg/m^3, u = 0.  The target is a block of half-width
`--half-width` and depth `--depth` (a full 3D block: the code has no
symmetry planes); its top face is at z = 0 and the sphere starts one lattice
spacing above it, moving in -z.  Material ids: 0 target, 1 projectile (the
same Tillotson Al 6061; separate ids only to tell them apart afterwards).

The projectile's particle masses are scaled so that it has the mass of
the true sphere (the lattice sphere of a coarse run can be 20% heavier);
--lattice-mass keeps rho0 dx^3.

Usage: make_ic.py [--dx 0.002] [-o crater.hdf5]  (SI units; an example
input, not part of bolide-ic)."""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import ichelpers  # noqa: E402  (examples/common/ichelpers.py)

RHO0 = 2700.0
R_P = 3.175e-3  # 6.35 mm diameter (README.md: the projectile size)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dx", type=float, default=0.002, help="lattice spacing [m]")
    ap.add_argument("--half-width", type=float, default=0.035, help="half-width of the target block [m]")
    ap.add_argument("--depth", type=float, default=0.045, help="depth of the target block [m]")
    ap.add_argument("--speed", type=float, default=7000.0, help="impact speed [m/s]")
    ap.add_argument("--radius", type=float, default=R_P, help="projectile radius [m]")
    ap.add_argument("--eta", type=float, default=1.2348, help="h = eta dx")
    ap.add_argument("--lattice-mass", action="store_true",
                    help="keep rho0 dx^3 for the projectile's particles (default: scale them to the true sphere's mass)")
    ap.add_argument("-o", "--output", default="crater.hdf5")
    a = ap.parse_args()
    dx = a.dx
    rp = a.radius
    nw = int(round(a.half_width / dx))
    nd = int(round(a.depth / dx))
    # target: cells centred on the lattice, top layer at z = -dx/2
    tgt = ichelpers.lattice((-nw, -nw, -nd), (nw, nw, -1), dx) + [0, 0, 0.5 * dx]
    # projectile: lattice points within rp of the centre, sphere bottom one dx above the top
    pj = ichelpers.lattice_ball(rp, dx)
    pj[:, 2] += rp + dx
    pos = np.concatenate([tgt, pj])
    nt, npp = len(tgt), len(pj)
    vel = np.zeros_like(pos)
    vel[nt:, 2] = -a.speed
    mat = np.r_[np.zeros(nt, dtype=np.int32), np.ones(npp, dtype=np.int32)]
    # shift into the positive octant of an open box with room above and below
    span = 2 * a.half_width + 0.2
    box = np.array([span, span, a.depth + 0.2])
    shift = np.array([0.5 * span, 0.5 * span, a.depth + 0.1])
    pos += shift
    N = len(pos)
    fields = ichelpers.solid_fields(pos, vel, mat, RHO0, dx, a.eta, npp, rp, a.lattice_mass)
    # Origin: the impact point (top face, axis), for the analysis
    ichelpers.write_ic(a.output, box, fields, header={"Origin": shift})
    print(f"{a.output}: {N} particles ({nt} target, {npp} projectile, r/dx = {rp / dx:.2f}), dx = {dx} m, "
          f"target {2 * a.half_width * 100:.1f} x {2 * a.half_width * 100:.1f} x {a.depth * 100:.1f} cm")


if __name__ == "__main__":
    main()
