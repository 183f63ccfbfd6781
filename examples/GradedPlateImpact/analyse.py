#!/usr/bin/env python3
"""Deformation of the plate and of the sphere in the graded plate impact,
uniform against graded particles, and a picture.

Geometry from the first snapshot of each run: the axis is the sphere's
centre in x, y; z = 0 is the plate's front face (the top layer of plate
particles is at z = -dx/2).  The measures are Lagrangian, on the particles
of the initial surfaces, so that they do not depend on the particle size
(the fine region of the graded plate starts as the uniform lattice):

- crater depth: how far the front face has moved down on the axis (the
  largest downward displacement of the initial top-layer plate particles
  within 1.5 dx of the axis);
- dent diameter: twice the radius (initial radius of the top-layer
  particles, averaged in rings of dx, interpolated) inside which the front
  face has moved down by more than a tenth of the crater depth: the dish
  of the plate, not only the crater;
- rear bulge: how far the rear face has moved down on the axis (the mean
  displacement of the initial bottom-layer particles within 1.5 dx of the
  axis);
- rear displacement at r = 2.5 cm (in the coarse part of the graded plate);
- thinning: crater depth minus rear bulge, the plate's loss of thickness
  on the axis;
- sphere: the aluminium spreads over the plate and part of it jets
  sideways, so its size is taken from quantiles of its particles (equal
  masses): the median diameter (twice the median distance from the axis),
  the height (90th minus 10th percentile of z) and the mean axial
  velocity;
- plastic zone: the plate mass with plastic strain above 1%, and the
  plastic strain at the crater floor (the largest over the top-layer
  particles within 1.5 dx of the axis).

Usage: analyse.py [--dx 0.001] [--out deformation.png] RUN_DIR [RUN_DIR ...]
  (each RUN_DIR holds output/plate_*.hdf5 and log.txt of one run; the
  first is the reference the others are compared with)."""
import argparse
import glob
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from bolide import snapshot  # noqa: E402  (python/bolide, unless the package is installed)

R_FAR = 0.025
FIELDS = ("Coordinates", "Velocities", "Masses", "MaterialIDs", "ParticleIDs", "PlasticStrains")


def read(path):
    """The fields of a snapshot in SI (bolide.snapshot), sorted by particle
    id, and its time "t"."""
    s = snapshot.load(path, FIELDS, si=True)
    d = {k: s[k] for k in FIELDS}
    d["t"] = snapshot.snapshot_time(s)
    o = np.argsort(d["ParticleIDs"])
    return {k: (v[o] if isinstance(v, np.ndarray) else v) for k, v in d.items()}


class Run:
    """The snapshots of one run and its reference surfaces."""

    def __init__(self, d, dx):
        self.dir = d
        self.snaps = sorted(glob.glob(os.path.join(d, "output", "plate_*.hdf5")))
        if len(self.snaps) < 2:
            raise SystemExit(f"analyse.py: error: {d}: fewer than two snapshots output/plate_*.hdf5")
        s0 = read(self.snaps[0])
        x, mat = s0["Coordinates"], s0["MaterialIDs"]
        pl = mat == 0
        ztop = x[pl, 2].max()
        self.origin = np.array([x[mat == 1, 0].mean(), x[mat == 1, 1].mean(), ztop + 0.5 * dx])
        x0 = x - self.origin
        self.x0 = x0
        self.r0 = np.hypot(x0[:, 0], x0[:, 1])
        self.n = len(x)
        # the top layer: fine particles at -dx/2, coarse ones (graded) at -dx
        self.top = pl & (x0[:, 2] > -1.25 * dx)
        zb = x0[pl, 2].min()  # the fine bottom layer, dx/2 above the rear face
        self.bottom = pl & (x0[:, 2] < zb + 0.75 * dx)
        self.plate = pl
        self.dx = dx
        self.wall = wall_time(d)
        self.cpu = cpu_time(d)

    def measure(self, s):
        dx = self.dx
        x = s["Coordinates"] - self.origin
        dz = x[:, 2] - self.x0[:, 2]
        ax_top = self.top & (self.r0 < 1.5 * dx)
        depth = -dz[ax_top].min()
        # front-face profile in bins of the initial radius
        edges = np.arange(0, 0.03 + dx, dx)
        k = np.digitize(self.r0[self.top], edges) - 1
        prof = np.array([np.mean(dz[self.top][k == j]) if (k == j).any() else 0.0 for j in range(len(edges) - 1)])
        rb = edges[:-1] + 0.5 * dx
        j = np.flatnonzero(prof > -0.1 * depth)
        j = j[0] if len(j) else len(prof) - 1
        # the radius where the profile crosses -depth/10, interpolated in the bin before
        rc = np.interp(-0.1 * depth, [prof[j - 1], prof[j]], [rb[j - 1], rb[j]]) if j > 0 else rb[0]
        ax_bot = self.bottom & (self.r0 < 1.5 * dx)
        bulge = -dz[ax_bot].mean()
        far = self.bottom & (np.abs(self.r0 - R_FAR) < 2 * dx)
        dfar = -dz[far].mean()
        al = s["MaterialIDs"] == 1
        ra = np.hypot(x[al, 0], x[al, 1])
        sph_d = 2 * np.percentile(ra, 50)
        sph_h = np.percentile(x[al, 2], 90) - np.percentile(x[al, 2], 10)
        vz = np.average(s["Velocities"][al, 2], weights=s["Masses"][al])
        eps = s["PlasticStrains"]
        mpl = s["Masses"][self.plate & (eps > 0.01)].sum()
        eps_floor = eps[ax_top].max()
        return dict(t=s["t"], depth=depth, diam=2 * rc, bulge=bulge, thin=depth - bulge, far=dfar, sph_d=sph_d, sph_h=sph_h, vz=vz,
                    mpl=mpl, eps=eps_floor, prof=(edges[:-1] + 0.5 * dx, prof))


def wall_time(d):
    """Wall time of the run from bolide's closing line in log.txt (nan if absent)."""
    try:
        with open(os.path.join(d, "log.txt")) as f:
            for line in f:
                m = re.search(r"done: \d+ steps to t = \S+ in ([0-9.]+) s", line)
                if m:
                    return float(m.group(1))
    except OSError:
        pass
    return np.nan


def cpu_time(d):
    """User plus system seconds of the run from time.txt ("wall user sys",
    written by run.sh; nan if absent)."""
    try:
        with open(os.path.join(d, "time.txt")) as f:
            w = f.read().split()
        return float(w[1]) + float(w[2])
    except (OSError, IndexError, ValueError):
        return np.nan


COLS = (("depth", "crater depth [mm]", 1e3), ("diam", "dent diameter [mm]", 1e3), ("bulge", "rear bulge [mm]", 1e3),
        ("thin", "thinning [mm]", 1e3),
        ("far", "rear at 2.5 cm [um]", 1e6), ("sph_d", "Al median diam. [mm]", 1e3),
        ("sph_h", "Al height 10-90% [mm]", 1e3), ("vz", "sphere v_z [m/s]", 1.0),
        ("mpl", "plastic mass [g]", 1e3), ("eps", "eps_p floor", 1.0))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--dx", type=float, default=0.001)
    ap.add_argument("--out", default="deformation.png")
    a = ap.parse_args()
    runs = [Run(d, a.dx) for d in a.dirs]
    finals = []
    for run in runs:
        print(f"{run.dir}: {run.n} particles, wall time {run.wall:.1f} s, CPU time {run.cpu:.1f} s")
        print("   t [us]  " + "  ".join(f"{c[1]:>20s}" for c in COLS))
        rows = []
        for path in run.snaps[1:]:
            m = run.measure(read(path))
            rows.append(m)
            print(f"  {m['t'] * 1e6:7.2f}  " + "  ".join(f"{m[c[0]] * c[2]:20.3f}" for c in COLS))
        run.rows = rows
        finals.append(rows[-1])
    ref = runs[0]
    print(f"\nat t = {finals[0]['t'] * 1e6:.1f} us, against {ref.dir}:")
    print(f"  {'':24s}" + "".join(f"{os.path.basename(os.path.normpath(r.dir)):>14s}" for r in runs) + "    difference")
    print(f"  {'particles':24s}" + "".join(f"{r.n:14d}" for r in runs) +
          "".join(f"    {r.n / ref.n:.3f} x" for r in runs[1:]))
    for key, name, sc in COLS:
        vals = [f[key] * sc for f in finals]
        diff = "".join(f"    {100 * (v / vals[0] - 1):+.1f}%" if vals[0] else "" for v in vals[1:])
        print(f"  {name:24s}" + "".join(f"{v:14.3f}" for v in vals) + diff)
    print(f"  {'wall time [s]':24s}" + "".join(f"{r.wall:14.1f}" for r in runs) +
          "".join(f"    speed-up {ref.wall / r.wall:.2f} x (paper: 3.8 x)" for r in runs[1:]))
    print(f"  {'CPU time [s]':24s}" + "".join(f"{r.cpu:14.1f}" for r in runs) +
          "".join(f"    ratio {ref.cpu / r.cpu:.2f} x" for r in runs[1:]))

    fig, ax = plt.subplots(2, 2, figsize=(12, 8))
    styles = ("-", "--", ":", "-.")
    for run, ls in zip(runs, styles):
        lab = f"{os.path.basename(os.path.normpath(run.dir))} ({run.n} particles)"
        t = np.array([m["t"] for m in run.rows]) * 1e6
        ax[0, 0].plot(t, [m["depth"] * 1e3 for m in run.rows], "C0" + ls, label="crater depth, " + lab)
        ax[0, 0].plot(t, [m["bulge"] * 1e3 for m in run.rows], "C1" + ls, label="rear bulge, " + lab)
        ax[0, 1].plot(t, [m["sph_d"] * 1e3 for m in run.rows], "C2" + ls, label="Al median diameter, " + lab)
        ax[0, 1].plot(t, [m["sph_h"] * 1e3 for m in run.rows], "C3" + ls, label="Al height, " + lab)
        r, prof = run.rows[-1]["prof"]
        ax[1, 0].plot(r * 1e3, prof * 1e3, "C0" + ls, label=lab)
    ax[0, 0].set_xlabel("t [us]")
    ax[0, 0].set_ylabel("displacement on the axis [mm]")
    ax[0, 0].legend(fontsize=7)
    ax[0, 1].set_xlabel("t [us]")
    ax[0, 1].set_ylabel("aluminium sphere [mm]")
    ax[0, 1].legend(fontsize=7)
    ax[1, 0].set_xlabel("initial radius of the front-face particles [mm]")
    ax[1, 0].set_ylabel(f"axial displacement at t = {finals[0]['t'] * 1e6:.0f} us [mm]")
    ax[1, 0].set_title("crater profile (front face)")
    ax[1, 0].legend(fontsize=7)
    # slice of the last run's final state, coloured by plastic strain
    run = runs[-1]
    s = read(run.snaps[-1])
    x = s["Coordinates"] - run.origin
    sl = np.abs(x[:, 1]) < 1.05 * a.dx  # fine layers at +-dx/2, coarse at +-dx
    pl = sl & (s["MaterialIDs"] == 0)
    sc = ax[1, 1].scatter(x[pl, 0] * 1e3, x[pl, 2] * 1e3, s=4, c=np.minimum(s["PlasticStrains"][pl], 0.3),
                          cmap="viridis")
    al = sl & (s["MaterialIDs"] == 1)
    ax[1, 1].scatter(x[al, 0] * 1e3, x[al, 2] * 1e3, s=4, c="tab:red", label="aluminium")
    fig.colorbar(sc, ax=ax[1, 1], label="plastic strain of the steel (cut at 0.3)")
    ax[1, 1].set_xlim(-30, 30)
    ax[1, 1].set_ylim(-12, 8)
    ax[1, 1].set_xlabel("x [mm]")
    ax[1, 1].set_ylabel("z [mm]")
    ax[1, 1].set_title(f"{os.path.basename(os.path.normpath(run.dir))}: slice |y| < {1.05 * a.dx * 1e3:.2f} mm, "
                       f"t = {s['t'] * 1e6:.0f} us")
    ax[1, 1].legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print(f"plot: {a.out}")


if __name__ == "__main__":
    main()
