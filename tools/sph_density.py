"""SPH density of a particle set, for tests and checks of initial conditions.

The smoothing length of each particle solves sum_j W(r_ij, h) = (eta / h)^3
(the number-density form used by SWIFT and Bolide, eta = resolution_eta),
with the cubic spline (default) or the Wendland C2 kernel in the Dehnen &
Aly (2012) convention of tasks/hydro/kernel.h (H = gamma h; cubic spline gamma =
sqrt(10/3), Wendland C2 sqrt(15/4)); then rho_i = sum_j m_j W(r_ij, h_i).
Written independently of the C code: the formulas are those of Dehnen & Aly
(2012), Table 1.  `kernel_of(path)` reads the kernel a Bolide file was made
with (Header/Kernel) and `eta_default(bolide)` the default resolution_eta of
a Bolide build (its --param-reference), so that a test measures the density
Bolide computes.
"""
import os
import subprocess
import sys

import numpy as np
from numpy.polynomial import Polynomial
from scipy.spatial import cKDTree

# an installed bolide first, else the source tree's (python/ beside tools/)
sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from bolide import snapshot  # noqa: E402

GAMMA = np.sqrt(10.0 / 3.0)
NORM = 16.0 / np.pi
N_BRACKET = 64.0

# Wendland C2 (Wendland 1995; Dehnen & Aly 2012, Table 1): w = C (1-q)^4 (1+4q)
WC2_GAMMA = np.sqrt(15.0 / 4.0)
WC2_NORM = 21.0 / (2.0 * np.pi)
_WC2_P = Polynomial([1.0, -1.0]) ** 4 * Polynomial([1.0, 4.0])
_WC2_F1 = (_WC2_P * Polynomial([0.0, 1.0])).integ()  # int_0^q w(t) t dt / C


def w_cubic(q):
    """w(q) of the cubic spline, support q < 1 (tasks/hydro/kernel.h)."""
    a = np.clip(1.0 - q, 0.0, None)
    b = np.clip(0.5 - q, 0.0, None)
    return NORM * (a**3 - 4.0 * b**3)


def w_wendland_c2(q):
    """w(q) of the Wendland C2 kernel, support q < 1 (tasks/hydro/kernel.h)."""
    q = np.clip(q, 0.0, 1.0)
    return WC2_NORM * _WC2_P(q)


def _f1_wendland_c2(q):
    """F(q) = int_0^q w(t) t dt of the Wendland C2 kernel (support 1)."""
    return WC2_NORM * _WC2_F1(np.clip(q, 0.0, 1.0))


def kernel_of(path):
    """Name of the kernel recorded in the Header of a Bolide HDF5 file
    ("cubic-spline" when there is none)."""
    k = snapshot.load(path, [])["header"].get("Kernel", b"cubic-spline")
    return k.decode() if isinstance(k, bytes) else str(k)


def eta_default(bolide):
    """Default SPH:resolution_eta of a Bolide executable (from the parameter
    reference it writes)."""
    out = subprocess.run([bolide, "--param-reference"], capture_output=True, text=True,
                         check=True).stdout
    section = None
    for line in out.splitlines():
        if line and not line[0].isspace() and line.rstrip().endswith(":"):
            section = line.strip()[:-1]
        elif section == "SPH" and line.strip().startswith("resolution_eta:"):
            return float(line.split(":", 1)[1].split("#")[0])
    raise ValueError("no SPH:resolution_eta in %s --param-reference" % bolide)


def neighbours(eta, kernel="cubic-spline"):
    """Neighbours inside the kernel support, (4 pi / 3) (gamma eta)^3."""
    return 4.0 * np.pi / 3.0 * (_kernel(kernel)[0] * eta) ** 3


def _kernel(name):
    """(gamma, w, F) of a kernel by name."""
    if name == "cubic-spline":
        return GAMMA, w_cubic, _f1
    if name == "wendland-C2":
        return WC2_GAMMA, w_wendland_c2, _f1_wendland_c2
    raise ValueError("sph_density: kernel %s not implemented" % name)


def density(pos, mass, eta=1.2348, k=100, kernel="cubic-spline"):
    """SPH density and smoothing length of every particle (k nearest
    neighbours searched; k must exceed the neighbours inside the kernel)."""
    GAMMA, w_cubic, _ = _kernel(kernel)  # noqa: N806 (the names of the cubic default)
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


def profile_density(r0, h, r_prof, rho_prof, nq=96, kernel="cubic-spline"):
    """The SPH density a continuum with the spherical profile rho(r) (zero
    beyond r_prof[-1]) gives at radius r0 with smoothing length h:
    int rho(r') W(|x0 - x'|, h) d^3x'.  The angles are integrated in closed
    form, int W dOmega r'^2 = 2 pi r' / (r0 H) [F((r0 + r') / H) - F(|r0 - r'| / H)],
    the radius by Gauss-Legendre over [r0 - H, r0 + H] cut at 0 and the
    surface.  theory/planets.md, "SPH density of a profile"."""
    GAMMA, _, _f1 = _kernel(kernel)  # noqa: N806
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
