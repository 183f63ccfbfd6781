#!/usr/bin/env python3
"""Hole diameter and debris-cloud length/width of the sphere-on-plate run,
and a picture.

Geometry from the first snapshot: the axis is the projectile's centre in
x, y; z = 0 is the plate's front face, the rear face is at z = -0.4 cm.
- Hole: plate material (id 0) still in the plate (within one plate
  thickness of its mid-plane) and condensed (density above --rho-frac rho0)
  is sorted into 32 azimuthal sectors; the hole radius of a sector is the
  smallest radius of such material in it, the hole diameter twice the
  median over the sectors (the clear opening).
- Fractured rim (Johnson-Cook fracture, ShearDamage = 1): per sector the
  95th percentile radius of fractured condensed plate material still in
  the plate, twice the median over the sectors.  Fractured material carries
  no tension and no shear: the ring between the clear hole and this
  diameter is rubble, no longer attached to the plate, so this is the hole
  of the plate that would be recovered if the rubble fell out.
- Perforation (the opening in which no plate material remains connected
  to the plate; issue 17 item 6): the intact plate particles (ShearDamage
  < 1) are linked friends-of-friends at --link lattice spacings (default
  1.5: the nearest and the face-diagonal neighbours of the initial
  lattice, with room for stretching); fractured particles (D = 1: no
  tension, no shear) link to nothing, so material they alone hold counts
  as separated.  The plate is the largest of the resulting components;
  the perforation diameter is twice the median over the 32 sectors of the
  smallest radius of condensed plate-component material in the plate.
- Debris cloud: every particle behind the rear face by more than one
  lattice spacing (projectile and plate fragments).  Length L: from the rear
  face to the front of the cloud (the 99.5th percentile of the distance
  behind the rear face, so that a few stray particles do not set it);
  width W: twice the 99.5th percentile of the distance from the axis.
  This is meant to follow an L/W read off a flash X-ray image (rear face of
  the bumper to the cloud's front, largest width); how Hiermaier et al.
  (1997) measured it and at what time was not checked against the paper.

Usage: analyse.py [--dx 0.0008] [--out plate.png] OUTPUT_DIR"""
import argparse
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from bolide import snapshot  # noqa: E402  (python/bolide, unless the package is installed)

RHO0 = 2710.0
THICK = 0.004


def read(path):
    """Time, positions, densities, material ids and shear damage (0 without
    it), in SI whatever the run's units (bolide.snapshot)."""
    s = snapshot.load(path, ["Coordinates", "Densities", "MaterialIDs"], optional=["ShearDamage"], si=True)
    dmg = s.get("ShearDamage", np.zeros(len(s["Densities"])))
    return snapshot.snapshot_time(s), s["Coordinates"], s["Densities"], s["MaterialIDs"], dmg


def in_plate(d, rho, mat, rho_frac):
    """Condensed plate material still in the plate: sector index and radius."""
    zmid = -0.5 * THICK
    inplate = (mat == 0) & (np.abs(d[:, 2] - zmid) < THICK) & (rho > rho_frac * RHO0)
    r = np.hypot(d[:, 0], d[:, 1])
    phi = np.arctan2(d[:, 1], d[:, 0])
    k = ((phi + np.pi) / (2 * np.pi) * 32).astype(int) % 32
    return inplate, k, r


def hole_diameter(d, rho, mat, rho_frac):
    """Clear hole: twice the median over 32 sectors of the smallest radius of
    condensed plate material in the plate."""
    inplate, k, r = in_plate(d, rho, mat, rho_frac)
    rmin = np.full(32, np.inf)
    np.minimum.at(rmin, k[inplate], r[inplate])
    return 2.0 * np.median(rmin)


def rim_diameter(d, rho, mat, dmg, rho_frac):
    """Outer diameter of the fractured rim: twice the median over 32 sectors
    of the 95th percentile radius of fractured (D = 1) condensed plate
    material in the plate (nan without fracture)."""
    inplate, k, r = in_plate(d, rho, mat, rho_frac)
    frac = inplate & (dmg >= 1.0)
    if frac.sum() < 32:
        return np.nan
    rr = [np.percentile(r[frac & (k == j)], 95) if (frac & (k == j)).any() else 0.0 for j in range(32)]
    return 2.0 * np.median(rr)


def plate_component(d, mat, dmg, link):
    """Mask of the plate: the largest friends-of-friends component (linking
    length `link`, metres) of the intact (ShearDamage < 1) plate particles.
    Fractured particles link to nothing."""
    intact = np.flatnonzero((mat == 0) & (dmg < 1.0))
    pairs = cKDTree(d[intact]).query_pairs(link, output_type="ndarray")
    n = len(intact)
    g = coo_matrix((np.ones(len(pairs), dtype=np.int8), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, lab = connected_components(g, directed=False)
    keep = np.zeros(len(d), dtype=bool)
    keep[intact[lab == np.bincount(lab).argmax()]] = True
    return keep


def perforation_diameter(d, rho, mat, dmg, rho_frac, link):
    """Opening with no plate material connected to the plate: twice the
    median over 32 sectors of the smallest radius of condensed material of
    the plate component (plate_component) in the plate."""
    inplate, k, r = in_plate(d, rho, mat, rho_frac)
    sel = inplate & plate_component(d, mat, dmg, link)
    rmin = np.full(32, np.inf)
    np.minimum.at(rmin, k[sel], r[sel])
    return 2.0 * np.median(rmin)


def cloud(d, dx):
    behind = -THICK - d[:, 2]
    deb = behind > dx
    if deb.sum() < 10:
        return np.nan, np.nan, deb
    L = np.percentile(behind[deb], 99.5)
    W = 2.0 * np.percentile(np.hypot(d[deb, 0], d[deb, 1]), 99.5)
    return L, W, deb


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dir")
    ap.add_argument("--dx", type=float, default=0.0008)
    ap.add_argument("--rho-frac", type=float, default=0.5)
    ap.add_argument("--link", type=float, default=1.5,
                    help="friends-of-friends linking length of the perforation, in lattice spacings")
    ap.add_argument("--out", default="plate.png")
    a = ap.parse_args()
    snaps = sorted(glob.glob(os.path.join(a.dir, "plate_*.hdf5")))
    if len(snaps) < 2:
        raise SystemExit(f"analyse.py: error: {a.dir}: fewer than two snapshots plate_*.hdf5")
    t0, x0, _, mat0, _ = read(snaps[0])
    origin = np.array([x0[mat0 == 1, 0].mean(), x0[mat0 == 1, 1].mean(), x0[mat0 == 0, 2].max() + 0.5 * a.dx])
    print("   t [us]   hole [cm]   fractured rim [cm]   perforation [cm]   cloud L [cm]   cloud W [cm]    L/W")
    rows = []
    for s in snaps[1:]:
        t, x, rho, mat, dmg = read(s)
        d = x - origin
        D = hole_diameter(d, rho, mat, a.rho_frac)
        Di = rim_diameter(d, rho, mat, dmg, a.rho_frac)
        Dp = perforation_diameter(d, rho, mat, dmg, a.rho_frac, a.link * a.dx)
        L, W, _ = cloud(d, a.dx)
        rows.append((t, D, Di, Dp, L, W))
        print(f"  {t * 1e6:7.2f}   {D * 100:9.2f}   {Di * 100:18.2f}   {Dp * 100:16.2f}   {L * 100:12.2f}"
              f"   {W * 100:12.2f}   {L / W:5.2f}")
    t, D, Di, Dp, L, W = rows[-1]
    print(f"final (t = {t * 1e6:.1f} us, dx = {a.dx * 1e3:.2f} mm): hole diameter {D * 100:.2f} cm "
          f"(experiment 3.45 cm: {100 * (D / 0.0345 - 1):+.0f}%), fractured rim {Di * 100:.2f} cm "
          f"({100 * (Di / 0.0345 - 1):+.0f}%), perforation {Dp * 100:.2f} cm ({100 * (Dp / 0.0345 - 1):+.0f}%), "
          f"debris cloud L/W {L / W:.2f} (experiment 1.39: {100 * (L / W / 1.39 - 1):+.0f}%)")

    t, x, rho, mat, dmg = read(snaps[-1])
    d = x - origin
    fig, ax = plt.subplots(1, 2, figsize=(12, 5))
    sl = np.abs(d[:, 1]) < 0.6 * a.dx
    for m, c, lab in ((0, "tab:blue", "plate"), (1, "tab:red", "projectile")):
        k = sl & (mat == m)
        ax[0].scatter(d[k, 0] * 100, d[k, 2] * 100, s=2, c=c, label=lab)
    _, _, deb = cloud(d, a.dx)
    ax[0].add_patch(plt.Rectangle((-W / 2 * 100, (-THICK - L) * 100), W * 100, L * 100, fill=False, ls="--",
                                  color="k", label=f"L/W = {L / W:.2f}"))
    ax[0].axvline(-D / 2 * 100, color="g", lw=0.8)
    ax[0].axvline(D / 2 * 100, color="g", lw=0.8, label=f"hole {D * 100:.2f} cm")
    ax[0].set_aspect("equal")
    ax[0].set_xlabel("x [cm]")
    ax[0].set_ylabel("z [cm] (0: front face of the plate)")
    ax[0].set_title(f"slice |y| < {0.6 * a.dx * 1e3:.2f} mm, t = {t * 1e6:.1f} us")
    ax[0].legend(fontsize=7, loc="lower right")
    pl = (mat == 0) & (np.abs(d[:, 2] + 0.5 * THICK) < THICK)
    ax[1].scatter(d[pl, 0] * 100, d[pl, 1] * 100, s=0.5, c="tab:blue")
    th = np.linspace(0, 2 * np.pi, 200)
    ax[1].plot(1.725 * np.cos(th), 1.725 * np.sin(th), "k--", lw=1, label="experiment, 3.45 cm")
    ax[1].plot(D / 2 * 100 * np.cos(th), D / 2 * 100 * np.sin(th), "g-", lw=1, label=f"this run, {D * 100:.2f} cm")
    if Di > D:
        ax[1].plot(Di / 2 * 100 * np.cos(th), Di / 2 * 100 * np.sin(th), "m-", lw=1,
                   label=f"fractured rim, {Di * 100:.2f} cm")
    ax[1].plot(Dp / 2 * 100 * np.cos(th), Dp / 2 * 100 * np.sin(th), "c-", lw=1,
               label=f"perforation, {Dp * 100:.2f} cm")
    frac = pl & (dmg >= 1.0)
    ax[1].scatter(d[frac, 0] * 100, d[frac, 1] * 100, s=0.5, c="tab:orange", label="fractured (D = 1)")
    ax[1].set_aspect("equal")
    ax[1].set_xlim(-4, 4)
    ax[1].set_ylim(-4, 4)
    ax[1].set_xlabel("x [cm]")
    ax[1].set_ylabel("y [cm]")
    ax[1].set_title("plate seen along the axis (plate material only)")
    ax[1].legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(f"plot: {a.out}")


if __name__ == "__main__":
    main()
