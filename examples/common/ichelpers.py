"""Helpers shared by the initial-condition scripts of examples/ (make_ic.py
in each folder): lattices, the mass of a lattice sphere, and the HDF5 file
in the layout Bolide reads (theory/architecture.md, "Parameters and files").

A make_ic.py imports this module with

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
    import ichelpers

so that it runs from any working directory, from the source tree or from a
copy of examples/.  SI units unless a script says otherwise."""
import os

import h5py
import numpy as np


def lattice(n_lo, n_hi, dx):
    """Points of the simple cubic lattice of spacing dx with integer indices
    n_lo[k] .. n_hi[k] (both included) along each axis, as an (N, 3) array,
    x slowest."""
    g = [np.arange(a, b + 1) * dx for a, b in zip(n_lo, n_hi)]
    x, y, z = np.meshgrid(*g, indexing="ij")
    return np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)


def lattice_ball(radius, dx, offset=0.0):
    """Points of the cubic lattice of spacing dx, moved by `offset` along
    each axis (0.5 dx: a lattice centred between the planes), strictly
    inside a sphere of `radius` about the origin."""
    n = int(np.ceil(radius / dx)) + 1
    pts = lattice((-n, -n, -n), (n, n, n), dx)
    if offset:
        pts = pts + offset
    return pts[np.linalg.norm(pts, axis=1) < radius]


def centred_grid(n_across, radius):
    """The n_across^3 cell-centred points of the cube [-radius, radius]^3 as
    three meshgrid arrays (x, y, z), and the spacing 2 radius / n_across."""
    dx = 2.0 * radius / n_across
    g = (np.arange(n_across) + 0.5) * dx - radius
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    return x, y, z, dx


def sphere_particle_mass(rho0, radius, n):
    """Mass of each of n particles that together carry the mass of the true
    sphere, rho0 4/3 pi radius^3 (a lattice sphere of a coarse run holds up
    to 20% more lattice cells than the sphere's volume)."""
    return rho0 * 4.0 / 3.0 * np.pi * radius**3 / n


def solid_fields(pos, vel, mat, rho0, dx, eta, n_projectile, r_projectile, lattice_mass):
    """The fields of a cold solid target and projectile cut from one lattice
    of spacing dx at density rho0 (the projectile: the last n_projectile
    particles): h = eta dx, u = 0, ids from 1.  Each particle carries
    rho0 dx^3; unless lattice_mass, the projectile's particles carry the mass
    of the true sphere of radius r_projectile instead (the lattice sphere is
    not the sphere: their volumes m / rho0 then sum to 4/3 pi r^3)."""
    n = len(pos)
    mass = np.full(n, rho0 * dx**3)
    if not lattice_mass:
        mass[-n_projectile:] = sphere_particle_mass(rho0, r_projectile, n_projectile)
    return {
        "Coordinates": pos,
        "Velocities": vel,
        "Masses": mass,
        "SmoothingLengths": np.full(n, eta * dx),
        "InternalEnergies": np.zeros(n),
        "Densities": np.full(n, rho0),
        "ParticleIDs": np.arange(1, n + 1),
        "MaterialIDs": mat,
    }


def write_ic(path, box, fields, header=None):
    """Write initial conditions: /Header (BoxSize, NumPart_Total,
    Dimension = 3, plus the attributes of `header`) and /PartType0 with one
    dataset per entry of `fields` (Coordinates, Velocities, Masses,
    SmoothingLengths, InternalEnergies, ParticleIDs, MaterialIDs, and
    optionally Densities).  The file is written under path.tmp and renamed,
    so that an interrupted run never leaves a truncated file under `path`.
    Returns the number of particles."""
    n = len(fields["Coordinates"])
    with h5py.File(path + ".tmp", "w") as f:
        h = f.create_group("Header")
        h.attrs["BoxSize"] = box
        h.attrs["NumPart_Total"] = [n, 0, 0, 0, 0, 0]
        h.attrs["Dimension"] = 3
        for k, v in (header or {}).items():
            h.attrs[k] = v
        p = f.create_group("PartType0")
        for k, v in fields.items():
            p[k] = v
    os.replace(path + ".tmp", path)
    return n
