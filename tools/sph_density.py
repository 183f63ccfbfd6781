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
N_BRACKET = 64.0


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
    if k == len(pos):
        # every point is a neighbour: the kernel may have to reach beyond
        # the farthest one (a few points, e.g. an isolated shell of N < 26);
        # h^3 sum_j W -> N w(0) / gamma^3 > eta^3 as h grows, so a large
        # enough bracket holds the solution
        hi = np.maximum(hi, (N_BRACKET * eta / GAMMA) * (dist[:, -1] + 1e-300))
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


def _f1(q):
    """F(q) = int_0^q w(t) t dt of the cubic spline (support 1)."""
    q = np.clip(q, 0.0, 1.0)
    qb = np.clip(q, 0.0, 0.5)
    a = 1.0 / 20.0 - (1.0 - q) ** 4 * (1.0 + 4.0 * q) / 20.0
    b = 0.5**5 / 20.0 - (0.5 - qb) ** 4 * (0.5 + 4.0 * qb) / 20.0
    return NORM * (a - 4.0 * b)


def profile_density(r0, h, r_prof, rho_prof, nq=96):
    """The SPH density a continuum with the spherical profile rho(r) (zero
    beyond r_prof[-1]) gives at radius r0 with smoothing length h:
    int rho(r') W(|x0 - x'|, h) d^3x'.  The angles are integrated in closed
    form, int W dOmega r'^2 = 2 pi r' / (r0 H) [F((r0 + r') / H) - F(|r0 - r'| / H)],
    the radius by Gauss-Legendre over [r0 - H, r0 + H] cut at 0 and the
    surface.  theory/planets.md, "SPH density of a profile"."""
    r0 = np.asarray(r0, float)
    H = GAMMA * np.asarray(h, float)
    lo = np.maximum(r0 - H, 0.0)
    hi = np.minimum(r0 + H, r_prof[-1])
    g, wg = np.polynomial.legendre.leggauss(nq)
    rp = 0.5 * (hi - lo)[:, None] * (g[None, :] + 1.0) + lo[:, None]
    wq = 0.5 * (hi - lo)[:, None] * wg[None, :]
    rho = np.interp(rp, r_prof, rho_prof)
    ang = _f1((r0[:, None] + rp) / H[:, None]) - _f1(np.abs(r0[:, None] - rp) / H[:, None])
    return 2.0 * np.pi / (r0 * H) * (rho * rp * ang * wq).sum(axis=1)
