#!/usr/bin/env python3
"""Initial conditions of issue 7's solid reference problem (theory/validation.md,
"Benchmarks", the solid-body impact on the GPU): a basalt sphere of radius 50 km on a simple cubic
lattice hit by a basalt sphere of radius 6.25 km (the same spacing) at
5 km/s and 45 degrees, the bodies one spacing apart along the velocity, in
the centre-of-mass frame.  Basalt: material id 103 (the library's SWIFT id),
rho0 2700 kg/m^3, u = 0.  h = ETA x spacing.  SI units.

Usage: basalt_ic.py N OUT.hdf5 [ETA]   (N: total particles, about)
"""
import sys

import h5py
import numpy as np

RHO0, MAT = 2700.0, 103
R_T, R_I = 5.0e4, 6.25e3
V, ANGLE = 5.0e3, 45.0


def ball(radius, dx):
    k = int(np.ceil(radius / dx)) + 1
    g = np.arange(-k, k + 1) * dx
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    p = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    return p[np.einsum("ij,ij->i", p, p) <= radius * radius]


def main():
    n = float(sys.argv[1])
    out = sys.argv[2]
    eta = float(sys.argv[3]) if len(sys.argv) > 3 else 1.534
    dx = (4.0 / 3.0 * np.pi * (R_T ** 3 + R_I ** 3) / n) ** (1.0 / 3.0)
    pt, pi = ball(R_T, dx), ball(R_I, dx)
    m = RHO0 * dx ** 3
    s = np.sin(np.radians(ANGLE)) * (R_T + R_I)
    c = np.array([np.sqrt((R_T + R_I) ** 2 - s * s) + dx, s, 0.0])
    vi = np.array([-V, 0.0, 0.0])
    nt, ni = len(pt), len(pi)
    com = ni * c / (nt + ni)
    vcom = ni * vi / (nt + ni)
    pos = np.concatenate([pt - com, pi + c - com])
    box = 4.0 * np.abs(pos).max()
    pos += 0.5 * box
    vel = np.concatenate([np.tile(-vcom, (nt, 1)), np.tile(vi - vcom, (ni, 1))])
    N = nt + ni
    with h5py.File(out, "w") as f:
        h = f.create_group("Header")
        h.attrs["BoxSize"] = np.full(3, box)
        h.attrs["NumPart_Total"] = np.array([N, 0, 0, 0, 0, 0], dtype=np.int64)
        h.attrs["NumPart_Total_HighWord"] = np.zeros(6, dtype=np.int64)
        h.attrs["NumPart_ThisFile"] = np.array([N, 0, 0, 0, 0, 0], dtype=np.int64)
        h.attrs["MassTable"] = np.zeros(6)
        h.attrs["Time"] = 0.0
        h.attrs["NumFilesPerSnapshot"] = 1
        h.attrs["Dimension"] = 3
        u = f.create_group("Units")
        u.attrs["Unit mass in cgs (U_M)"] = 1e3
        u.attrs["Unit length in cgs (U_L)"] = 1e2
        u.attrs["Unit time in cgs (U_t)"] = 1.0
        u.attrs["Unit current in cgs (U_I)"] = 1.0
        u.attrs["Unit temperature in cgs (U_T)"] = 1.0
        p = f.create_group("PartType0")
        p["Coordinates"] = pos
        p["Velocities"] = vel
        p["Masses"] = np.full(N, m)
        p["SmoothingLength"] = np.full(N, eta * dx)
        p["InternalEnergy"] = np.zeros(N)
        p["Density"] = np.full(N, RHO0)
        p["ParticleIDs"] = np.arange(1, N + 1, dtype=np.int64)
        p["MaterialIDs"] = np.full(N, MAT, dtype=np.int32)
    print("basalt_ic: %d + %d particles, spacing %.4g m, box %.4g m -> %s" % (nt, ni, dx, box, out))


if __name__ == "__main__":
    main()
