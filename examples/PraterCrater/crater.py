#!/usr/bin/env python3
"""Crater depth and diameter of the Prater crater run, and a picture.

The impact point is taken from the first snapshot (axis: the projectile's
centre in x, y; surface: the top of the target, one half lattice spacing
above its top layer).  In each later snapshot, condensed material (density
above --rho-frac of rho0, projectile and target alike) is binned in radius
r from the axis (bins of one lattice spacing); the crater floor of a bin is
the highest such particle at or below the original surface (z <= 0, so the
lip and the ejecta above the surface do not count).  The crater diameter is
twice the radius where the floor first comes back up to the original
surface (within half a spacing), i.e. the diameter at the level of the
original surface; the crater depth is the median floor depth of the bins
within a quarter of that diameter of the axis (robust against the single
column of particles that a cubic lattice leaves on the symmetry axis).

Usage: crater.py [--dx 0.002] [--out crater.png] OUTPUT_DIR"""
import argparse
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from bolide import snapshot  # noqa: E402  (python/bolide, unless the package is installed)

RHO0 = 2700.0


def read(path):
    """Time, positions, densities, material ids and plastic strains, in SI
    (bolide.snapshot)."""
    s = snapshot.load(path, ["Coordinates", "Densities", "MaterialIDs", "PlasticStrains"], si=True)
    return snapshot.snapshot_time(s), s["Coordinates"], s["Densities"], s["MaterialIDs"], s["PlasticStrains"]


def profile(x, rho, mat, origin, dx, rho_frac):
    """Floor z(r) (m, negative below the original surface) per radial bin,
    from condensed target material (id 0)."""
    d = x - origin
    r = np.hypot(d[:, 0], d[:, 1])
    z = d[:, 2]
    keep = (rho > rho_frac * RHO0) & (z <= 0.5 * dx) & (mat == 0)
    nb = int(np.ceil(r[keep].max() / dx)) + 1 if keep.any() else 1
    k = (r[keep] / dx).astype(int)
    floor = np.full(nb, np.nan)
    np.fmax.at(floor, k, z[keep])
    rc = (np.arange(nb) + 0.5) * dx
    return rc, floor


def measure(rc, floor, dx):
    """Diameter at the level of the original surface; depth: the median
    floor depth of the bins within a quarter of that diameter of the axis
    (at least two bins), so that one column of particles left on the
    symmetry axis of the lattice does not set it."""
    up = np.where(floor >= -0.5 * dx)[0]
    if not len(up):
        return np.nan, np.nan
    k = up[0]
    if k == 0 or not np.isfinite(floor[k - 1]):
        radius = rc[k]
    else:  # where the floor crosses -dx/2, linear between the bin centres
        f0, f1 = floor[k - 1], floor[k]
        radius = rc[k - 1] + (rc[k] - rc[k - 1]) * (-0.5 * dx - f0) / (f1 - f0)
    inner = (rc < max(0.5 * radius, 2.0 * dx)) & np.isfinite(floor)
    depth = float(np.median(-floor[inner]))
    return depth, 2.0 * radius


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dir")
    ap.add_argument("--dx", type=float, default=0.002)
    ap.add_argument("--rho-frac", type=float, default=0.5, help="condensed: rho > RHO_FRAC rho0")
    ap.add_argument("--out", default="crater.png")
    a = ap.parse_args()
    snaps = sorted(glob.glob(os.path.join(a.dir, "crater_*.hdf5")))
    if len(snaps) < 2:
        raise SystemExit(f"crater.py: error: {a.dir}: fewer than two snapshots crater_*.hdf5")
    t0, x0, _, mat0, _ = read(snaps[0])
    origin = np.array([x0[mat0 == 1, 0].mean(), x0[mat0 == 1, 1].mean(), x0[mat0 == 0, 2].max() + 0.5 * a.dx])
    print("   t [us]   depth [cm]   diameter [cm]")
    hist = []
    for s in snaps[1:]:
        t, x, rho, mat, eps = read(s)
        rc, fl = profile(x, rho, mat, origin, a.dx, a.rho_frac)
        depth, diam = measure(rc, fl, a.dx)
        hist.append((t, depth, diam))
        print(f"  {t * 1e6:7.1f}   {depth * 100:10.2f}   {diam * 100:13.2f}")
    t, x, rho, mat, eps = read(snaps[-1])
    rc, fl = profile(x, rho, mat, origin, a.dx, a.rho_frac)
    depth, diam = measure(rc, fl, a.dx)
    print(f"final (t = {t * 1e6:.1f} us): crater depth {depth * 100:.2f} cm, diameter {diam * 100:.2f} cm "
          f"(dx = {a.dx * 1e3:.2f} mm; depth/diameter {depth / diam:.2f})")

    fig, ax = plt.subplots(1, 2, figsize=(11, 4.5), gridspec_kw={"width_ratios": [2, 1]})
    d = x - origin
    sl = np.abs(d[:, 1]) < 0.6 * a.dx
    cond = rho > a.rho_frac * RHO0
    m = sl & cond
    sc = ax[0].scatter(d[m, 0] * 100, d[m, 2] * 100, c=np.log10(eps[m] + 1e-4), s=6, cmap="viridis", vmin=-3, vmax=1)
    pj = m & (mat == 1)
    ax[0].scatter(d[pj, 0] * 100, d[pj, 2] * 100, s=6, c="red", label="projectile material")
    ax[0].scatter(d[sl & ~cond, 0] * 100, d[sl & ~cond, 2] * 100, s=2, c="0.7", label=f"rho < {a.rho_frac} rho0")
    ok = np.isfinite(fl)
    ax[0].plot(rc[ok] * 100, fl[ok] * 100, "k-", lw=1.5, label="crater floor (this run)")
    ax[0].plot(-rc[ok] * 100, fl[ok] * 100, "k-", lw=1.5)
    ax[0].axhline(0, color="0.5", lw=0.5)
    ax[0].set_xlim(-5, 5)
    ax[0].set_ylim(-5, 3)
    ax[0].set_aspect("equal")
    ax[0].set_xlabel("x [cm]")
    ax[0].set_ylabel("z [cm] (0: original surface)")
    ax[0].set_title(f"slice |y| < {0.6 * a.dx * 1e3:.1f} mm, t = {t * 1e6:.0f} us; colour log10 plastic strain")
    ax[0].legend(fontsize=7, loc="upper right")
    fig.colorbar(sc, ax=ax[0], shrink=0.8)
    h = np.array(hist)
    ax[1].plot(h[:, 0] * 1e6, h[:, 1] * 100, "o-", label="depth")
    ax[1].plot(h[:, 0] * 1e6, h[:, 2] * 100, "s-", label="diameter")
    ax[1].set_xlabel("t [us]")
    ax[1].set_ylabel("cm")
    ax[1].set_title("crater growth")
    ax[1].legend()
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(f"plot: {a.out}")


if __name__ == "__main__":
    main()
