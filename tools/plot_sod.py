#!/usr/bin/env python3
"""Compare a Sod shock-tube snapshot with the exact Riemann solution.

Plots density, x-velocity, pressure and specific internal energy against x
(particles as points, their binned means, the exact solution as a line),
writes a PNG and prints the L1 errors (bolide.l1: plain mean over the
particles of |f_i - f_exact(x_i)|, in the snapshot's units) as lines
"L1 density X", "L1 velocity X", "L1 pressure X", then the star state as
lines "star QUANTITY MEASURED EXACT" for left_density, right_density,
left_pressure, right_pressure and velocity: means over the particles in the
middle half of the left star region (between the tail of the rarefaction and
the contact) and of the right one (between the contact and the shock), of
both interfaces of a periodic tube (velocity: of both regions, in the
direction of the flow away from the dense gas).  The middle halves stay
clear of the smoothed waves once the regions are several smoothing lengths
wide; the pressure difference across the contact is
right_pressure / left_pressure - 1.

Default set-up (that of SWIFT's examples/HydroTests/SodShock_3D and of
`bolide-ic sod`): a box periodic in x of length Lx (the snapshot's BoxSize),
the left state (rho 1, v 0, P 1) in 0 <= x < Lx/2, the right state
(rho 0.125, v 0, P 0.1) in Lx/2 <= x < Lx, gamma 5/3.  There are therefore
two interfaces: the usual Sod problem at x = Lx/2 and its mirror image at
x = 0 (= Lx).  Each particle is compared with the solution of the nearer one;
this is exact until the waves of the two meet (for Lx = 2 and gamma 5/3,
until t = 0.271, when the two shocks meet; a warning is printed after
that).  --x0 A B moves the
interfaces (left state in A <= x < B); --x0 A alone means one interface at
A in a non-periodic tube (left state at x < A).
"""

import argparse
import os
import sys

import numpy as np

# an installed bolide first, else the source tree's (python/ beside tools/)
# or an install's (PREFIX/bin/SCRIPT: PREFIX/share/bolide/python)
_here = os.path.dirname(os.path.abspath(__file__))
sys.path += [os.path.join(_here, "..", "python"), os.path.join(_here, "..", "share", "bolide", "python")]
from bolide import common, l1, riemann, snapshot  # noqa: E402


def parse_args(argv):
    """Command line."""
    p = argparse.ArgumentParser(
        description="Plot a Sod shock-tube snapshot against the exact Riemann solution "
        "and print the L1 errors of density, velocity and pressure.",
        epilog="Default: periodic box of length BoxSize[0] with the left state in "
        "0 <= x < BoxSize[0]/2 (SWIFT's SodShock_3D layout).")
    p.add_argument("snapshot", help="HDF5 snapshot")
    p.add_argument("--out", help="output PNG (default: SNAPSHOT-stem_sod.png)")
    p.add_argument("--gamma", type=float, default=5.0 / 3.0, help="adiabatic index (5/3)")
    p.add_argument("--x0", type=float, nargs="+", metavar="X",
                   help="interfaces: A B (left state in A <= x < B, periodic in x; "
                   "default 0 and BoxSize[0]/2) or A (single interface, left state at x < A)")
    p.add_argument("--left", type=float, nargs=3, default=(1.0, 0.0, 1.0),
                   metavar=("RHO", "V", "P"), help="left state (1 0 1)")
    p.add_argument("--right", type=float, nargs=3, default=(0.125, 0.0, 0.1),
                   metavar=("RHO", "V", "P"), help="right state (0.125 0 0.1)")
    p.add_argument("--time", type=float, help="time of the snapshot (default: header Time)")
    p.add_argument("--xrange", type=float, nargs=2, metavar=("XMIN", "XMAX"),
                   help="region of the L1 errors and of the plot (default: whole tube)")
    p.add_argument("--nbins", type=int, default=100, help="bins along x for the means (100)")
    p.add_argument("--no-plot", action="store_true", help="print the numbers only (no PNG)")
    args = p.parse_args(argv)
    if args.x0 is not None and len(args.x0) > 2:
        p.error("--x0 takes one or two positions")
    if args.nbins < 1:
        p.error("--nbins must be positive")
    if not args.gamma > 1.0:
        p.error("--gamma must exceed 1")
    return args


def exact_at(x, t, args, box_length):
    """rho, v, P of the exact solution at positions x (see module doc)."""
    if args.x0 is not None and len(args.x0) == 1:
        return riemann.shock_tube(x, t, args.left, args.right, args.gamma, args.x0[0])
    x_left, x_right = (0.0, 0.5 * box_length) if args.x0 is None else args.x0
    return riemann.shock_tube(x, t, args.left, args.right, args.gamma, x_left, x_right,
                              box_length)


def star_state(x, t, rho, v, p, args, box_length):
    """Measured and exact star state (see the module doc): a list of
    (name, measured, exact); empty when a region holds no particle."""
    sol = riemann.RiemannSolution(args.left, args.right, args.gamma)
    speeds = sol.wave_speeds()
    if args.x0 is not None and len(args.x0) == 1:
        ifaces = [(args.x0[0], 1.0)]
    else:
        x_left, x_right = (0.0, 0.5 * box_length) if args.x0 is None else args.x0
        ifaces = [(x_right, 1.0), (x_left, -1.0)]  # the mirrored problem at x_left
    sel_l, sel_r, sign = [], [], []
    for x0, s in ifaces:
        d = x - x0
        if box_length is not None:
            d = np.mod(d + 0.5 * box_length, box_length) - 0.5 * box_length
        xi = s * d / t  # self-similar coordinate of the forward problem
        a, c, b = speeds["left_tail"], speeds["contact"], speeds["right_head"]
        sel_l.append((xi > a + 0.25 * (c - a)) & (xi < c - 0.25 * (c - a)))
        sel_r.append((xi > c + 0.25 * (b - c)) & (xi < b - 0.25 * (b - c)))
        sign.append(np.full(x.shape, s))
    ml, mr = np.any(sel_l, axis=0), np.any(sel_r, axis=0)
    if not (np.any(ml) and np.any(mr)):
        return []
    s = np.choose(np.argmax(sel_l + sel_r, axis=0) % len(ifaces), sign)
    flow = s * v
    return [("left_density", np.mean(rho[ml]), sol.rho_star_left),
            ("right_density", np.mean(rho[mr]), sol.rho_star_right),
            ("left_pressure", np.mean(p[ml]), sol.p_star),
            ("right_pressure", np.mean(p[mr]), sol.p_star),
            ("velocity", np.mean(flow[ml | mr]), sol.u_star)]


def main(argv=None):
    """Run the comparison; returns the exit status."""
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        snap = snapshot.load(args.snapshot, ["Coordinates", "Velocities", "Densities",
                                             "Pressures", "InternalEnergies"])
        t = snapshot.snapshot_time(snap, args.time)
    except snapshot.SnapshotError as exc:
        common.die(str(exc))
    if not t > 0:
        common.die("%s: time %g: the exact solution needs t > 0" % (args.snapshot, t))
    x = snap["Coordinates"][:, 0]
    periodic = args.x0 is None or len(args.x0) == 2
    box_length = None
    if periodic:
        box = snap["header"].get("BoxSize")
        if box is None:
            common.die("%s: /Header has no BoxSize (needed for the periodic tube)"
                       % args.snapshot)
        box_length = float(box[0])
        x = np.mod(x, box_length)
        x_left, x_right = (0.0, 0.5 * box_length) if args.x0 is None else args.x0
        try:
            t_max = riemann.tube_valid_until(args.left, args.right, args.gamma, x_left,
                                             x_right, box_length)
        except ValueError as exc:
            common.die(str(exc))
        if t > t_max:
            common.warn("at t = %g the waves of the two interfaces have met (after t = %g): "
                        "the exact solution is no longer exact" % (t, t_max))
    try:
        rho_e, v_e, p_e = exact_at(x, t, args, box_length)
    except ValueError as exc:
        common.die(str(exc))

    fields = [
        ("density", snap["Densities"], rho_e),
        ("velocity", snap["Velocities"][:, 0], v_e),
        ("pressure", snap["Pressures"], p_e),
        ("internal_energy", snap["InternalEnergies"], p_e / ((args.gamma - 1.0) * rho_e)),
    ]
    if args.xrange is not None:
        lo, hi = args.xrange
        region = (x >= lo) & (x <= hi)
    else:
        lo, hi = (0.0, box_length) if periodic else (x.min(), x.max())
        region = np.ones_like(x, dtype=bool)
    if not np.any(region):
        common.die("%s: no particle in --xrange %g %g" % (args.snapshot, lo, hi))
    for name, values, exact in fields[:3]:
        try:
            print("L1 %s %.6g" % (name, l1.l1_error(values, exact, mask=region)))
        except ValueError as exc:
            common.die("%s: %s" % (args.snapshot, exc))

    sel = region if args.xrange is not None else np.ones_like(x, dtype=bool)
    for name, measured, exact in star_state(x[sel], t, np.asarray(snap["Densities"])[sel],
                                            np.asarray(snap["Velocities"])[sel, 0],
                                            np.asarray(snap["Pressures"])[sel], args,
                                            box_length):
        print("star %s %.6g %.6g" % (name, measured, exact))
    if args.no_plot:
        return 0

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    xs = np.linspace(lo, hi, 4001)
    rho_l, v_l, p_l = exact_at(xs, t, args, box_length)
    lines = [rho_l, v_l, p_l, p_l / ((args.gamma - 1.0) * rho_l)]
    labels = ["density", "velocity $v_x$", "pressure", "specific internal energy"]
    edges = np.linspace(lo, hi, args.nbins + 1)
    centres = 0.5 * (edges[1:] + edges[:-1])
    which = np.clip(np.digitize(x[region], edges) - 1, 0, args.nbins - 1)
    count = np.bincount(which, minlength=args.nbins)
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
    for ax, (name, values, _), line, label in zip(axes.flat, fields, lines, labels):
        vals = np.asarray(values, dtype=float)[region]
        ax.plot(x[region], vals, ",", color="0.6", rasterized=True, label="particles")
        with np.errstate(invalid="ignore", divide="ignore"):
            mean = np.bincount(which, weights=vals, minlength=args.nbins) / count
        ax.plot(centres, mean, "o", ms=3, color="C0", label="binned mean")
        ax.plot(xs, line, "-", color="C3", lw=1.2, label="exact")
        ax.set_ylabel(label)
    for ax in axes[1]:
        ax.set_xlabel("x")
    axes[0, 0].legend(loc="best", fontsize="small")
    fig.suptitle("Sod shock tube, t = %.4g, gamma = %.4g, N = %d"
                 % (t, args.gamma, x.size))
    fig.tight_layout()
    out = args.out or common.default_output(args.snapshot, "_sod.png")
    common.write_figure(fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
