"""SPH density of a particle set, for tests and checks of initial conditions.

The smoothing length of each particle solves sum_j W(r_ij, h) = (eta / h)^3
(the number-density form used by SWIFT and Bolide, eta = resolution_eta),
with the cubic spline in the Dehnen & Aly (2012) convention of src/kernel.h
(H = gamma h, gamma = sqrt(10/3)); then rho_i = sum_j m_j W(r_ij, h_i).
"""
import numpy as np
from scipy.spatial import cKDTree

GAMMA = np.sqrt(10.0 / 3.0)
NORM = 16.0 / np.pi


def w_cubic(q):
    """w(q) of the cubic spline, support q < 1 (src/kernel.h)."""
    a = np.clip(1.0 - q, 0.0, None)
    b = np.clip(0.5 - q, 0.0, None)
    return NORM * (a**3 - 4.0 * b**3)


def density(pos, mass, eta=1.2348, k=100):
    """SPH density and smoothing length of every particle (k nearest
    neighbours searched; k must exceed the neighbours inside the kernel)."""
    tree = cKDTree(pos)
    k = min(k, len(pos))
    dist, idx = tree.query(pos, k)
    lo = np.full(len(pos), 1e-300)
    hi = dist[:, -1] / GAMMA
    for _ in range(32):
        h = 0.5 * (lo + hi)
        H = GAMMA * h
        n = (w_cubic(dist / H[:, None])).sum(axis=1) / H**3
        big = n * h**3 > eta**3
        hi = np.where(big, h, hi)
        lo = np.where(big, lo, h)
    h = 0.5 * (lo + hi)
    H = GAMMA * h
    rho = (mass[idx] * w_cubic(dist / H[:, None])).sum(axis=1) / H**3
    return rho, h
