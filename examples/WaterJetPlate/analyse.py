#!/usr/bin/env python3
"""The fluid-solid interface of the water jet on a plate over time, and
pictures.

Per snapshot:
- gap: the smallest distance between a water particle and a plate
  particle, in lattice spacings dx (1 at the start: the initial conditions
  put the phases one spacing apart);
- penetrated: the number of water particles below the plate's front face
  (a water particle whose z is below that of the nearest, in x and y,
  particle of the plate's initial top layer, by more than dx/2), and of
  water particles below the rear face;
- deflection: the displacement of the plate's rear face on the axis (the
  mean over the initial bottom-layer particles within 1.5 dx of it) and
  that of the plate's rim (the particles within 2 dx of the edge), and
  their difference (the bending of the plate; the free plate also moves
  as a whole);
- the water's largest pressure and the mass of water that has turned
  outwards (moving away from the axis faster than it moves down).

Draws interface.png: the gap and the penetration count against time, the
deflection against time, and slices through the axis at three times
(the water coloured by its density).

Usage: analyse.py [--dx 0.0005] [--out interface.png] RUN_DIR [RUN_DIR ...]
  (RUN_DIR holds output/jet_*.hdf5; with two or more, the gap and
  deflection curves of each are drawn and the slices are those of the
  first)"""
import argparse
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from scipy.spatial import cKDTree

sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from bolide import snapshot  # noqa: E402  (python/bolide, unless the package is installed)

FIELDS = ("Coordinates", "Velocities", "MaterialIDs", "ParticleIDs", "Pressures", "Masses", "Densities")


def read(path):
    """The fields of a snapshot in SI (bolide.snapshot), sorted by particle
    id, and its time "t"."""
    s = snapshot.load(path, FIELDS, si=True)
    d = {k: s[k] for k in FIELDS}
    d["t"] = snapshot.snapshot_time(s)
    o = np.argsort(d["ParticleIDs"])
    return {k: (v[o] if isinstance(v, np.ndarray) else v) for k, v in d.items()}


def analyse(d, dx):
    snaps = sorted(glob.glob(os.path.join(d, "output", "jet_*.hdf5")))
    if len(snaps) < 2:
        raise SystemExit(f"analyse.py: error: {d}: fewer than two snapshots output/jet_*.hdf5")
    s0 = read(snaps[0])
    x0, mat = s0["Coordinates"], s0["MaterialIDs"]
    pl, wa = mat == 0, mat == 1
    origin = np.array([x0[wa, 0].mean(), x0[wa, 1].mean(), x0[pl, 2].max() + 0.5 * dx])
    x0 = x0 - origin
    r0 = np.hypot(x0[:, 0], x0[:, 1])
    top = pl & (x0[:, 2] > -dx)
    zb = x0[pl, 2].min()
    bottom = pl & (x0[:, 2] < zb + 0.5 * dx)
    half = np.abs(x0[pl, :2]).max() + 0.5 * dx
    rim = pl & (np.abs(x0[:, :2]).max(axis=1) > half - 2 * dx)
    axis = bottom & (r0 < 1.5 * dx)
    rows = []
    for path in snaps:
        s = read(path)
        x = s["Coordinates"] - origin
        dz = x[:, 2] - x0[:, 2]
        gap, _ = cKDTree(x[pl]).query(x[wa])
        # water below the front face: compare with the nearest top-layer particle in x, y
        _, k = cKDTree(x[top, :2]).query(x[wa, :2])
        ztop = x[top, 2][k] + 0.5 * dx
        below_front = int(np.sum(x[wa, 2] < ztop - 0.5 * dx))
        _, k = cKDTree(x[bottom, :2]).query(x[wa, :2])
        below_rear = int(np.sum(x[wa, 2] < x[bottom, 2][k] - 0.5 * dx))
        v = s["Velocities"][wa]
        rw = np.hypot(x[wa, 0], x[wa, 1])
        vr = (x[wa, 0] * v[:, 0] + x[wa, 1] * v[:, 1]) / np.maximum(rw, 1e-30)
        turned = s["Masses"][wa][vr > -v[:, 2]].sum() / s["Masses"][wa].sum()
        rows.append(dict(t=s["t"], gap=gap.min() / dx, below_front=below_front, below_rear=below_rear,
                         centre=-dz[axis].mean(), rim=-dz[rim].mean(), pmax=s["Pressures"][wa].max(),
                         turned=turned))
    return snaps, origin, rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--dx", type=float, default=0.0005)
    ap.add_argument("--out", default="interface.png")
    a = ap.parse_args()
    runs = []
    for d in a.dirs:
        snaps, origin, rows = analyse(d, a.dx)
        runs.append((d, snaps, origin, rows))
        print(f"{d}:")
        print("   t [us]   gap [dx]   water below front / rear face   centre [um]   rim [um]   deflection [um]"
              "   water P_max [GPa]   turned out")
        for m in rows:
            print(f"  {m['t'] * 1e6:7.2f}   {m['gap']:8.3f}   {m['below_front']:14d} / {m['below_rear']:<14d}"
                  f"   {m['centre'] * 1e6:11.1f}   {m['rim'] * 1e6:8.1f}   {(m['centre'] - m['rim']) * 1e6:15.1f}"
                  f"   {m['pmax'] / 1e9:17.3f}   {100 * m['turned']:9.1f}%")
        g = np.array([m["gap"] for m in rows])
        last = rows[-1]
        print(f"summary {d}: smallest fluid-solid distance {g.min():.3f} dx (at t = "
              f"{rows[int(g.argmin())]['t'] * 1e6:.1f} us; {g[1:].min():.3f} to {g[1:].max():.3f} dx after the "
              f"start), water particles below the front face at most {max(m['below_front'] for m in rows)}, below "
              f"the rear face at most {max(m['below_rear'] for m in rows)}; plate deflection at "
              f"t = {last['t'] * 1e6:.0f} us {(last['centre'] - last['rim']) * 1e6:.0f} um (centre "
              f"{last['centre'] * 1e6:.0f} um, rim {last['rim'] * 1e6:.0f} um)")

    fig = plt.figure(figsize=(13, 8))
    g1 = fig.add_subplot(2, 3, 1)
    g2 = fig.add_subplot(2, 3, 2)
    g3 = fig.add_subplot(2, 3, 3)
    for (d, _, _, rows), ls in zip(runs, ("-", "--", ":")):
        lab = os.path.basename(os.path.normpath(d))
        t = np.array([m["t"] for m in rows]) * 1e6
        g1.plot(t, [m["gap"] for m in rows], "C0" + ls + "o", ms=3, label=f"smallest distance, {lab}")
        g2.plot(t, [m["below_front"] for m in rows], "C3" + ls + "o", ms=3, label=f"below the front face, {lab}")
        g3.plot(t, [(m["centre"] - m["rim"]) * 1e6 for m in rows], "C2" + ls, label=f"centre - rim, {lab}")
        g3.plot(t, [m["centre"] * 1e6 for m in rows], "C1" + ls, label=f"centre, {lab}")
    g1.axhline(1.0, color="k", lw=0.5)
    g1.set_ylim(0, None)
    g1.set_xlabel("t [us]")
    g1.set_ylabel("fluid-solid distance [dx]")
    g1.set_title("gap between water and plate")
    g1.legend(fontsize=7)
    top = max(max(m["below_front"] for m in rows) for _, _, _, rows in runs)
    g2.set_ylim(-0.5, max(5, 1.1 * top))
    g2.set_xlabel("t [us]")
    g2.set_ylabel("water particles")
    g2.set_title("penetration: water below the plate's front face")
    g2.legend(fontsize=7)
    g3.set_xlabel("t [us]")
    g3.set_ylabel("rear-face displacement [um]")
    g3.set_title("plate deflection")
    g3.legend(fontsize=7)
    d, snaps, origin, _ = runs[0]
    picks = [snaps[len(snaps) // 4], snaps[len(snaps) // 2], snaps[-1]]
    for i, path in enumerate(picks):
        ax = fig.add_subplot(2, 3, 4 + i)
        s = read(path)
        x = s["Coordinates"] - origin
        sl = np.abs(x[:, 1]) < 1.2 * a.dx  # particles leave their lattice planes: a slab of 2.4 dx
        k = sl & (s["MaterialIDs"] == 0)
        ax.scatter(x[k, 0] * 1e3, x[k, 2] * 1e3, s=3, c="tab:grey", label="Al 6061-T6")
        k = sl & (s["MaterialIDs"] == 1)
        sc = ax.scatter(x[k, 0] * 1e3, x[k, 2] * 1e3, s=4, c=s["Densities"][k], cmap="viridis", vmin=0, vmax=1500,
                        label="water")
        ax.set_aspect("equal")
        ax.set_xlim(-12, 12)
        ax.set_ylim(-4, 7)
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("z [mm]")
        ax.set_title(f"slice |y| < {1.2 * a.dx * 1e3:.1f} mm, t = {s['t'] * 1e6:.0f} us", fontsize=9)
        if i == 2:
            fig.colorbar(sc, ax=ax, label="water density [kg/m^3]", shrink=0.6)
        if i == 0:
            ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(f"plot: {a.out}")


if __name__ == "__main__":
    main()
