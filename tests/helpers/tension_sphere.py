"""Initial conditions of the solid-fracture tests (test_damage_run.sh,
test_restart_damage.sh, test_mpi.sh): a sphere of radius 3 cm cut from an
n^3 cubic lattice, density 2700 kg/m^3, u = 1 J/kg, material 0, expanding
radially at 50 m/s at its surface (tension: the Weibull flaws activate and
the sphere fractures), centred in an open 0.2 m box.

Usage: tension_sphere.py OUT.hdf5 N [--reverse-ids]
  --reverse-ids  the particle ids in the reverse of the file order
Prints the number of particles."""
import sys

import h5py
import numpy as np


def write(name, n, reverse_ids=False, R=0.03, rho=2700.0):
    dx = 2 * R / n
    g = (np.arange(n) + 0.5) * dx - R
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    keep = x**2 + y**2 + z**2 < R * R
    pos = np.stack([x[keep], y[keep], z[keep]], axis=1)
    N = len(pos)
    ids = np.arange(1, N + 1)
    with h5py.File(name, "w") as f:
        h = f.create_group("Header")
        h.attrs["BoxSize"] = [0.2, 0.2, 0.2]
        h.attrs["NumPart_Total"] = [N, 0, 0, 0, 0, 0]
        p = f.create_group("PartType0")
        p["Coordinates"] = pos + 0.1
        p["Velocities"] = pos / R * 50.0
        p["Masses"] = np.full(N, rho * dx**3)
        p["SmoothingLengths"] = np.full(N, 1.2348 * dx)
        p["InternalEnergies"] = np.full(N, 1.0)
        p["Densities"] = np.full(N, rho)
        p["ParticleIDs"] = ids[::-1].copy() if reverse_ids else ids
        p["MaterialIDs"] = np.zeros(N, dtype=np.int32)
    return N


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    print(write(sys.argv[1], int(sys.argv[2]), "--reverse-ids" in sys.argv[3:]))
