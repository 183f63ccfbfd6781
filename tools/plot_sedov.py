#!/usr/bin/env python3
"""Compare a Sedov-Taylor blast-wave snapshot with the similarity solution.

Plots the radial profiles of density, radial velocity and pressure
(particles as points, binned means, the solution of bolide.sedov as a
line), writes a PNG and prints

    shock_radius measured X analytic Y rel_error Z
    bin_width W
    L1 density X      (likewise velocity (radial) and pressure; inside --rmax,
                       plain mean over particles, see python/bolide/l1.py)

The measured shock radius is where the binned mean density, going outwards
from its peak, falls through half-way between the peak and the ambient
density rho0 (linear interpolation between bin centres): the middle of the
jump, which for a shock smeared over a few smoothing lengths is less biased
than the radius of the peak bin itself (the peak sits a bin or more inside
the front).  Its resolution is a fraction of the bin width (printed as
"bin_width"); choose --nbins so that a bin holds many particles.

With --initial (the initial conditions or the t = 0 snapshot) the script
also prints

    shock_radius_moment measured X analytic Y rel_error Z

from the radial mass transport: sum_i m_i (r_i(t) - r_i(0)) equals
int (rho - rho0) r dV = 4 pi rho0 R^4 I(gamma) in the similarity solution
(I from SedovSolution.moment_coefficient), so R = (sum / (4 pi rho0 I))^(1/4).
Smoothing the shock over a few h moves mass symmetrically about the front
and leaves this moment unchanged to second order in h / R, whereas any
feature of the smeared profile (peak, half-height) shifts by O(h): this is
the estimator the validation test asserts.  Radii are
taken from --centre (default: the box centre, BoxSize/2) with the periodic
minimum image when the header has a BoxSize.
"""

import argparse
import os
import sys

import numpy as np

# an installed bolide first, else the source tree's (python/ beside tools/)
# or an install's (PREFIX/bin/SCRIPT: PREFIX/share/bolide/python)
_here = os.path.dirname(os.path.abspath(__file__))
sys.path += [os.path.join(_here, "..", "python"), os.path.join(_here, "..", "share", "bolide", "python")]
from bolide import common, l1, sedov, snapshot  # noqa: E402


def parse_args(argv):
    """Command line."""
    p = argparse.ArgumentParser(
        description="Plot a Sedov blast-wave snapshot against the similarity solution "
        "and print the measured and analytic shock radii.")
    p.add_argument("snapshot", help="HDF5 snapshot")
    p.add_argument("--out", help="output PNG (default: SNAPSHOT-stem_sedov.png)")
    p.add_argument("--E", type=float, default=1.0, help="explosion energy (1)")
    p.add_argument("--rho0", type=float, default=1.0, help="ambient density (1)")
    p.add_argument("--gamma", type=float, default=5.0 / 3.0, help="adiabatic index (5/3)")
    p.add_argument("--centre", type=float, nargs=3, metavar=("X", "Y", "Z"),
                   help="explosion centre (default: BoxSize/2)")
    p.add_argument("--time", type=float, help="time since the explosion (default: header Time)")
    p.add_argument("--nbins", type=int, default=60, help="radial bins out to --rmax (60)")
    p.add_argument("--rmax", type=float, help="outer radius of the bins (default: 1.5 R analytic)")
    p.add_argument("--initial", help="initial conditions (or t = 0 snapshot) of the same particles: "
                   "also print the moment estimate of the shock radius")
    args = p.parse_args(argv)
    for name in ("E", "rho0"):
        if not getattr(args, name) > 0:
            p.error("--%s must be positive" % name)
    if not args.gamma > 1.0:
        p.error("--gamma must exceed 1")
    if args.nbins < 3:
        p.error("--nbins must be at least 3")
    return args


def measured_shock_radius(r, rho, rho0, rmax, nbins):
    """Radius where the binned mean density, outwards from its peak, falls
    through (peak + rho0)/2 (see module doc); the peak bin's centre when it
    never does.  Returns (radius, bin width)."""
    edges = np.linspace(0.0, rmax, nbins + 1)
    width = edges[1] - edges[0]
    centres = 0.5 * (edges[1:] + edges[:-1])
    inside = r < rmax
    which = np.clip((r[inside] / width).astype(int), 0, nbins - 1)
    count = np.bincount(which, minlength=nbins)
    if not np.any(count > 0):
        raise ValueError("no particle within r < %g of the centre" % rmax)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.bincount(which, weights=rho[inside], minlength=nbins) / count
    filled = count > 0
    centres, mean = centres[filled], mean[filled]
    k = int(np.argmax(mean))
    level = 0.5 * (mean[k] + rho0)
    below = np.nonzero(mean[k:] < level)[0]
    if below.size == 0:
        return centres[k], width
    j = k + below[0]
    f = (mean[j - 1] - level) / (mean[j - 1] - mean[j])
    return centres[j - 1] + f * (centres[j] - centres[j - 1]), width


def moment_shock_radius(snap, initial, centre, box, rho0, sol):
    """Shock radius from sum_i m_i (r_i(t) - r_i(0)) (see module doc); the
    particles are matched by ParticleIDs."""
    ini = snapshot.load(initial, ["Coordinates", "ParticleIDs", "Masses"])
    cur = snapshot.load(snap["path"], ["ParticleIDs", "Masses"])

    def radii(coords):
        d = coords - centre
        if box is not None:
            d -= box * np.round(d / box)
        return np.sqrt(np.sum(d * d, axis=1))

    order0 = np.argsort(ini["ParticleIDs"])
    order1 = np.argsort(cur["ParticleIDs"])
    if not np.array_equal(ini["ParticleIDs"][order0], cur["ParticleIDs"][order1]):
        raise ValueError("%s and %s do not hold the same particles" % (initial, snap["path"]))
    r0 = radii(ini["Coordinates"])[order0]
    r1 = radii(snap["Coordinates"])[order1]
    moment = float(np.sum(cur["Masses"][order1] * (r1 - r0)))
    coeff = sol.moment_coefficient()
    if not moment / coeff > 0:
        raise ValueError("no outward mass transport: is this a blast wave?")
    return (moment / (4.0 * np.pi * rho0 * coeff)) ** 0.25


def main(argv=None):
    """Run the comparison; returns the exit status."""
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        snap = snapshot.load(args.snapshot, ["Coordinates", "Velocities", "Densities",
                                             "Pressures"])
        t = snapshot.snapshot_time(snap, args.time)
    except snapshot.SnapshotError as exc:
        common.die(str(exc))
    if not t > 0:
        common.die("%s: time %g: the similarity solution needs t > 0" % (args.snapshot, t))
    box = snap["header"].get("BoxSize")
    if args.centre is not None:
        centre = np.array(args.centre)
    elif box is not None:
        centre = 0.5 * box
    else:
        common.die("%s: /Header has no BoxSize: give --centre" % args.snapshot)
    d = snap["Coordinates"] - centre
    if box is not None:
        d -= box * np.round(d / box)  # minimum image
    r = np.sqrt(np.sum(d * d, axis=1))
    with np.errstate(invalid="ignore", divide="ignore"):
        v_r = np.where(r > 0, np.sum(snap["Velocities"] * d, axis=1) / r, 0.0)
    rho, pres = snap["Densities"], snap["Pressures"]

    sol = sedov.SedovSolution(args.gamma)
    r_an = float(sol.shock_radius(t, args.E, args.rho0))
    rmax = args.rmax if args.rmax is not None else 1.5 * r_an
    try:
        r_me, width = measured_shock_radius(r, rho, args.rho0, rmax, args.nbins)
    except ValueError as exc:
        common.die("%s: %s" % (args.snapshot, exc))
    print("shock_radius measured %.6g analytic %.6g rel_error %.4g"
          % (r_me, r_an, (r_me - r_an) / r_an))
    print("bin_width %.6g" % width)
    if args.initial:
        try:
            r_mo = moment_shock_radius(snap, args.initial, centre, box, args.rho0, sol)
        except (snapshot.SnapshotError, ValueError) as exc:
            common.die(str(exc))
        print("shock_radius_moment measured %.6g analytic %.6g rel_error %.4g"
              % (r_mo, r_an, (r_mo - r_an) / r_an))
    rho_e, v_e, p_e = sol.profiles(r, t, args.E, args.rho0)
    region = r < rmax
    try:
        for name, values, exact in (("density", rho, rho_e), ("velocity", v_r, v_e),
                                    ("pressure", pres, p_e)):
            print("L1 %s %.6g" % (name, l1.l1_error(values, exact, mask=region)))
    except ValueError as exc:
        common.die("%s: %s" % (args.snapshot, exc))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rs = np.linspace(0.0, rmax, 2001)
    lines = sol.profiles(rs, t, args.E, args.rho0)
    edges = np.linspace(0.0, rmax, args.nbins + 1)
    which = np.clip((r[region] / width).astype(int), 0, args.nbins - 1)
    count = np.bincount(which, minlength=args.nbins)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    for ax, values, line, label in zip(axes, (rho, v_r, pres), lines,
                                       ("density", "radial velocity", "pressure")):
        vals = np.asarray(values, dtype=float)[region]
        ax.plot(r[region], vals, ",", color="0.6", rasterized=True, label="particles")
        with np.errstate(invalid="ignore", divide="ignore"):
            mean = np.bincount(which, weights=vals, minlength=args.nbins) / count
        ax.plot(0.5 * (edges[1:] + edges[:-1]), mean, "o", ms=3, color="C0",
                label="binned mean")
        ax.plot(rs, line, "-", color="C3", lw=1.2, label="similarity solution")
        ax.axvline(r_an, color="C3", lw=0.6, ls=":")
        ax.axvline(r_me, color="C0", lw=0.6, ls="--")
        ax.set_xlabel("r")
        ax.set_ylabel(label)
    axes[0].legend(loc="best", fontsize="small")
    fig.suptitle("Sedov-Taylor blast, t = %.4g, E = %.4g, rho0 = %.4g, gamma = %.4g: "
                 "R measured %.4g, analytic %.4g" % (t, args.E, args.rho0, args.gamma,
                                                     r_me, r_an))
    fig.tight_layout()
    out = args.out or common.default_output(args.snapshot, "_sedov.png")
    common.write_figure(fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
