#!/usr/bin/env python3
"""Plot the colliding rubber rings with and without artificial stress and
print what they show: for each run and snapshot, the mean x velocity of the
left ring (positive while approaching, negative after a bounce) and the
number of pieces of each ring (friends-of-friends with linking length
1.5 dx within each ring: 1 + 1 for two intact rings, more after fracture),
and the fraction of particles whose nearest neighbour is closer than
0.5 dx (pairing, the mark of the tensile instability).

Usage: plot_rings.py [--dx 0.0025] [--out rings.png] DIR_WITH_AS DIR_WITHOUT"""
import argparse
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from bolide import snapshot  # noqa: E402  (python/bolide, unless the package is installed)


def fragments(pos, link):
    """Number of friends-of-friends groups of at least 10 particles and the mass fraction in them."""
    pairs = cKDTree(pos).query_pairs(link, output_type="ndarray")
    from scipy.sparse import coo_matrix

    n = len(pos)
    g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    ncomp, lab = connected_components(g, directed=False)
    sizes = np.bincount(lab)
    big = sizes[sizes >= 10]
    return len(big), sizes.max() / n


def read(path):
    """Time, positions, velocities and deviatoric stress (None without it),
    in SI (bolide.snapshot), the particles in the order of their ids."""
    s = snapshot.load(path, ["ParticleIDs", "Coordinates", "Velocities"], optional=["DeviatoricStress"],
                      si=True)
    o = np.argsort(s["ParticleIDs"])
    S = s["DeviatoricStress"][o] if "DeviatoricStress" in s else None
    return snapshot.snapshot_time(s), s["Coordinates"][o], s["Velocities"][o], S


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs=2)
    ap.add_argument("--dx", type=float, default=0.0025)
    ap.add_argument("--out", default="rings.png")
    a = ap.parse_args()
    runs = []
    for d in a.dirs:
        snaps = sorted(glob.glob(os.path.join(d, "rings_*.hdf5")))
        runs.append([read(s) for s in snaps])
    ncol = max(len(r) for r in runs)
    fig, axes = plt.subplots(2, ncol, figsize=(2.2 * ncol, 4.6), squeeze=False)
    for row, (d, run) in enumerate(zip(a.dirs, runs)):
        n1 = len(run[0][1]) // 2
        print(f"{d}:")
        print("      t[ms]   <vx> left ring [m/s]   pieces L+R   paired fraction   max sqrt(3 J2) [MPa]")
        for k, (t, x, v, S) in enumerate(run):
            nl, _ = fragments(x[:n1], 1.5 * a.dx)
            nr, _ = fragments(x[n1:], 1.5 * a.dx)
            dnn = cKDTree(x).query(x, k=2)[0][:, 1]
            paired = np.mean(dnn < 0.5 * a.dx)
            seq = 0.0
            if S is not None:
                J2 = 0.5 * (S[:, 0] ** 2 + S[:, 3] ** 2 + S[:, 5] ** 2) + S[:, 1] ** 2 + S[:, 2] ** 2 + S[:, 4] ** 2
                seq = np.sqrt(3 * J2).max() / 1e6
            print(f"  {t * 1e3:9.3f}   {v[:n1, 0].mean():20.2f}   {nl:5d}+{nr:<5d}   {paired:15.3f}   {seq:12.2f}")
            ax = axes[row, k]
            ax.scatter(x[:, 0], x[:, 1], s=0.3, c=np.r_[np.zeros(n1), np.ones(len(x) - n1)], cmap="coolwarm")
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            ax.set_title(f"t = {t * 1e3:.2f} ms", fontsize=8)
        axes[row, 0].set_ylabel(os.path.basename(os.path.normpath(d)))
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    print(f"plot: {a.out}")


if __name__ == "__main__":
    main()
