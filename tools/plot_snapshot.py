#!/usr/bin/env python3
"""Picture of a snapshot: x-y scatter of the particles in a slice in z,
coloured by a field, equal aspect (the README's collision picture).

--colour takes any dataset of /PartType0 (vector datasets are shown by their
magnitude) or one of the short names: density, pressure, internal_energy,
sound_speed, smoothing_length, material, velocity, damage, mass.  Materials
are coloured by category; the other fields on a linear scale, or a
logarithmic one with --log.

The slice keeps the particles with |z - ZC| < THICKNESS/2, ZC being the
centre of mass in z unless --zc is given.  The default thickness is four
times the median smoothing length (or a tenth of the z extent when the
snapshot has no smoothing lengths); --slice 0 keeps every particle and draws
them in order of increasing z, so the picture is a view from +z.
"""

import argparse
import os
import sys

import numpy as np

# an installed bolide first, else the source tree's (python/ beside tools/)
# or an install's (PREFIX/bin/SCRIPT: PREFIX/share/bolide/python)
_here = os.path.dirname(os.path.abspath(__file__))
sys.path += [os.path.join(_here, "..", "python"), os.path.join(_here, "..", "share", "bolide", "python")]
from bolide import common, snapshot  # noqa: E402

#: Short colour names -> dataset names (any dataset name is accepted too).
SHORT_NAMES = {
    "density": "Densities",
    "pressure": "Pressures",
    "internal_energy": "InternalEnergies",
    "sound_speed": "SoundSpeeds",
    "smoothing_length": "SmoothingLengths",
    "material": "MaterialIDs",
    "velocity": "Velocities",
    "damage": "Damage",
    "mass": "Masses",
}


def parse_args(argv):
    """Command line."""
    p = argparse.ArgumentParser(
        description="Draw an x-y slice of a snapshot, coloured by a field.")
    p.add_argument("snapshot", help="HDF5 snapshot")
    p.add_argument("--out", help="output PNG (default: SNAPSHOT-stem_COLOUR.png)")
    p.add_argument("--colour", "--color", default="material",
                   help="field: %s, or any /PartType0 dataset name (material)"
                   % ", ".join(SHORT_NAMES))
    p.add_argument("--slice", type=float, metavar="THICKNESS",
                   help="slice thickness in z (default: 4 median h; 0: no slice)")
    p.add_argument("--zc", type=float, help="centre of the slice in z (default: centre of mass)")
    p.add_argument("--log", action="store_true", help="logarithmic colour scale")
    p.add_argument("--vmin", type=float, help="lower end of the colour scale")
    p.add_argument("--vmax", type=float, help="upper end of the colour scale")
    p.add_argument("--size", type=float,
                   help="marker size in points^2 (default: 2e4 / particles drawn, within 0.3-20)")
    args = p.parse_args(argv)
    if args.slice is not None and args.slice < 0:
        p.error("--slice must be >= 0")
    if args.size is not None and not args.size > 0:
        p.error("--size must be positive")
    return args


def main(argv=None):
    """Draw the picture; returns the exit status."""
    args = parse_args(sys.argv[1:] if argv is None else argv)
    field = SHORT_NAMES.get(args.colour, args.colour)
    try:
        snap = snapshot.load(args.snapshot, ["Coordinates", "Masses", field],
                             optional=["SmoothingLengths"])
    except snapshot.SnapshotError as exc:
        common.die(str(exc))
    pos, mass = snap["Coordinates"], snap["Masses"]
    values = np.asarray(snap[field], dtype=float)
    if values.ndim == 2:
        values = np.sqrt(np.sum(values * values, axis=1))
    elif values.ndim != 1:
        common.die("%s: /PartType0/%s is neither a scalar nor a vector field"
                   % (args.snapshot, field))
    if pos.shape[0] == 0:
        common.die("%s: no particles" % args.snapshot)

    z = pos[:, 2]
    zc = args.zc if args.zc is not None else float(np.sum(mass * z) / np.sum(mass))
    thickness = args.slice
    if thickness is None:
        if "SmoothingLengths" in snap:
            thickness = 4.0 * float(np.median(snap["SmoothingLengths"]))
        else:
            thickness = 0.1 * float(np.ptp(z))
    if thickness > 0:
        keep = np.abs(z - zc) < 0.5 * thickness
        if not np.any(keep):
            common.die("%s: no particle in the slice |z - %g| < %g"
                       % (args.snapshot, zc, 0.5 * thickness))
        order = np.nonzero(keep)[0]
    else:
        order = np.argsort(z)
    x, y, c = pos[order, 0], pos[order, 1], values[order]
    if args.size is None:
        args.size = float(np.clip(2e4 / x.size, 0.3, 20.0))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.colors as mcolors
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.5, 6.5))
    if field == "MaterialIDs":
        ids = np.unique(c.astype(int))
        cmap = plt.get_cmap("tab10" if ids.size <= 10 else "tab20")
        for k, mat in enumerate(ids):
            m = c.astype(int) == mat
            ax.scatter(x[m], y[m], s=args.size, color=cmap(k % cmap.N), lw=0,
                       label="material %d" % mat, rasterized=True)
        ax.legend(loc="upper right", fontsize="small", markerscale=6)
    else:
        norm = None
        if args.log:
            positive = c[c > 0]
            if positive.size == 0:
                common.die("%s: --log with no positive value of %s" % (args.snapshot, field))
            norm = mcolors.LogNorm(vmin=args.vmin or positive.min(),
                                   vmax=args.vmax or positive.max())
            c = np.where(c > 0, c, positive.min())
            sc = ax.scatter(x, y, c=c, s=args.size, lw=0, norm=norm, cmap="viridis",
                            rasterized=True)
        else:
            sc = ax.scatter(x, y, c=c, s=args.size, lw=0, vmin=args.vmin, vmax=args.vmax,
                            cmap="viridis", rasterized=True)
        fig.colorbar(sc, ax=ax, label=args.colour, shrink=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    t = snap["header"].get("Time")
    what = ("|z - %.3g| < %.3g" % (zc, 0.5 * thickness)) if thickness > 0 else "all particles"
    ax.set_title("%s%s, %s, %d particles"
                 % (args.colour, "" if t is None else " at t = %.4g" % t, what, x.size))
    fig.tight_layout()
    out = args.out or common.default_output(args.snapshot, "_%s.png" % args.colour)
    common.write_figure(fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
