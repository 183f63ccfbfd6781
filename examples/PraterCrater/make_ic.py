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

import h5py
import numpy as np

RHO0 = 2700.0
R_P = 3.175e-3  # 6.35 mm diameter (README.md: the projectile size)


def lattice(n_lo, n_hi, dx):
    g = [np.arange(a, b + 1) * dx for a, b in zip(n_lo, n_hi)]
    x, y, z = np.meshgrid(*g, indexing="ij")
    return np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)


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
    tgt = lattice((-nw, -nw, -nd), (nw, nw, -1), dx) + [0, 0, 0.5 * dx]
    # projectile: lattice points within rp of the centre, sphere bottom one dx above the top
    npj = int(np.ceil(rp / dx)) + 1
    pj = lattice((-npj, -npj, -npj), (npj, npj, npj), dx)
    pj = pj[np.linalg.norm(pj, axis=1) < rp]
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
    mass = np.full(N, RHO0 * dx**3)
    if not a.lattice_mass:
        # the lattice sphere is not the sphere: give the projectile the mass of
        # the true sphere (its particles' volumes m / rho0 then sum to 4/3 pi R^3)
        mass[-npp:] = RHO0 * 4.0 / 3.0 * np.pi * rp**3 / npp
    with h5py.File(a.output + ".tmp", "w") as f:
        h = f.create_group("Header")
        h.attrs["BoxSize"] = box
        h.attrs["NumPart_Total"] = [N, 0, 0, 0, 0, 0]
        h.attrs["Dimension"] = 3
        h.attrs["Origin"] = shift  # the impact point (top face, axis), for the analysis
        p = f.create_group("PartType0")
        p["Coordinates"] = pos
        p["Velocities"] = vel
        p["Masses"] = mass
        p["SmoothingLengths"] = np.full(N, a.eta * dx)
        p["InternalEnergies"] = np.zeros(N)
        p["Densities"] = np.full(N, RHO0)
        p["ParticleIDs"] = np.arange(1, N + 1)
        p["MaterialIDs"] = mat
    os.replace(a.output + ".tmp", a.output)
    print(f"{a.output}: {N} particles ({nt} target, {npp} projectile, r/dx = {rp / dx:.2f}), dx = {dx} m, "
          f"target {2 * a.half_width * 100:.1f} x {2 * a.half_width * 100:.1f} x {a.depth * 100:.1f} cm")


if __name__ == "__main__":
    main()
