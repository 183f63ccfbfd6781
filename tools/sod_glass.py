#!/usr/bin/env python3
"""Turn a lattice Sod tube of `bolide-ic sod` into a glass-like one.

The lattice tube holds, in a box Lx x Ly x Lz periodic in all directions,
the dense gas on a cubic lattice of spacing a in 0 <= x < Lx/2 and the
light gas on one of spacing 2a in Lx/2 <= x < Lx, left particles first, all
of one mass.  This script replaces the positions of each half by copies of
a periodic glass cube (16^3 particles of unit spacing for the left half,
8^3 for the right, each relaxed once from its own seeded random positions)
scaled to the half's spacing and tiled over it, and keeps every other field
(masses, energies, ids; h is only the first guess of the ghost iteration).
The tiles are periodic, so each half is periodic on its own and the
particle numbers are those of the lattice; the tile period (16 spacings)
is several kernel diameters, so that no kernel sees the repetition.  The
tube's lattice counts must be multiples of the cubes' (N_x a multiple of
64 with Ly = Lz = 0.25, of 32 with 0.5).

Relaxation (a discrete version of the pressure-driven settling with which
glass initial conditions are usually made, e.g. White 1994; Price 2012,
Sec. 5.1): from uniformly random positions, each particle is moved along
the isothermal SPH pressure force of unit sound speed,

    a_i = - sum_j (1/rho_i + 1/rho_j) grad_i W(r_ij, h),   rho_i = sum_j W(r_ij, h),

(cubic spline, h = 1.3 a, unit masses), by dx_i = c a^2 a_i with |dx_i| at
most 0.1 a and c = 0.3; the force vanishes for a uniform density, so the
iteration settles into a disordered, nearly uniform arrangement (a glass)
with no preferred direction.  Iterations stop after --iterations or when
the rms density contrast falls below --tolerance (about 0.004 after the
300 default steps); --cache keeps the cubes, so that a resolution series
relaxes them once.

Usage:
    sod_glass.py LATTICE.hdf5 GLASS.hdf5 [--seed S] [--iterations N] [--cache DIR]
"""

import argparse
import os
import sys

import numpy as np

# an installed bolide first, else the source tree's (python/ beside tools/)
sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from bolide import common  # noqa: E402

STEP = 0.3
GLASS_LEFT = 16  # particles along an edge of the left half's glass cube
GLASS_RIGHT = 8  # and of the right half's (twice the spacing)


def cubic_w(q):
    """Cubic spline M4 shape with support q < 2 (Monaghan & Lattanzio 1985),
    3-D normalisation 1/pi (h = 1): W = w(q) / (pi h^3)."""
    w = np.where(q < 1.0, 1.0 - 1.5 * q * q + 0.75 * q ** 3, 0.25 * (2.0 - q) ** 3)
    return np.where(q < 2.0, w, 0.0) / np.pi


def cubic_dw(q):
    """dw/dq of cubic_w."""
    d = np.where(q < 1.0, -3.0 * q + 2.25 * q * q, -0.75 * (2.0 - q) ** 2)
    return np.where(q < 2.0, d, 0.0) / np.pi


def relax(n, box, seed, iterations, tolerance, log=None):
    """A glass of n equal particles in the periodic box (3 lengths)."""
    from scipy.spatial import cKDTree

    box = np.asarray(box, dtype=float)
    a = (np.prod(box) / n) ** (1.0 / 3.0)
    h = 1.3 * a
    rng = np.random.default_rng(seed)
    x = rng.random((n, 3)) * box
    contrast = np.inf
    it = 0
    for it in range(1, iterations + 1):
        tree = cKDTree(x, boxsize=box)
        pairs = tree.query_pairs(2.0 * h, output_type="ndarray")
        i, j = pairs[:, 0], pairs[:, 1]
        d = x[i] - x[j]
        d -= box * np.round(d / box)  # nearest periodic image
        r = np.sqrt(np.sum(d * d, axis=1))
        q = r / h
        w = cubic_w(q)
        rho = np.full(n, cubic_w(np.zeros(1))[0])
        rho += np.bincount(i, w, n) + np.bincount(j, w, n)
        rho /= h ** 3
        contrast = np.std(rho) / np.mean(rho)
        if contrast < tolerance:
            break
        # grad_i W = dw/dq / h^4 * d / r (points from j to i times dw/dq < 0)
        coef = -(1.0 / rho[i] + 1.0 / rho[j]) * cubic_dw(q) / h ** 4 / np.maximum(r, 1e-300)
        f = d * coef[:, None]
        acc = np.empty((n, 3))
        for k in range(3):
            acc[:, k] = np.bincount(i, f[:, k], n) - np.bincount(j, f[:, k], n)
        dx = STEP * a * a * acc
        norm = np.sqrt(np.sum(dx * dx, axis=1))
        big = norm > 0.1 * a
        dx[big] *= (0.1 * a / norm[big])[:, None]
        x = np.mod(x + dx, box)
        if log and (it % 50 == 0):
            log("  iteration %d: rms density contrast %.3g" % (it, contrast))
    return x, it, contrast


def glass_cube(ng, seed, iterations, tolerance, cache, label):
    """The relaxed ng^3 glass cube of unit spacing (from cache when there)."""
    import os

    path = os.path.join(cache, "glass_%d_s%d.npy" % (ng, seed)) if cache else None
    if path and os.path.exists(path):
        g = np.load(path)
        print("glass cube %d^3 (%s half): read %s" % (ng, label, path), flush=True)
        return g
    g, it, c = relax(ng ** 3, (ng, ng, ng), seed, iterations, tolerance)
    print("glass cube %d^3 (%s half): %d iterations, rms density contrast %.3g"
          % (ng, label, it, c), flush=True)
    if path:
        os.makedirs(cache, exist_ok=True)
        np.save(path, g)
    return g


def tile(glass, ng, n, spacing, x0):
    """Positions of a periodic block of n = (nx, ny, nz) particles of the given
    spacing starting at x = x0, made of copies of the ng^3 glass cube (unit
    spacing); every n[k] must be a multiple of ng."""
    if any(k % ng for k in n):
        common.die("the tube's lattice (%d x %d x %d) is not a multiple of the %d^3 glass"
                   % (n[0], n[1], n[2], ng))
    t = [k // ng for k in n]
    off = np.stack(np.meshgrid(*[np.arange(k) for k in t], indexing="ij"), -1).reshape(-1, 3)
    pos = (glass[None, :, :] + ng * off[:, None, :]).reshape(-1, 3) * spacing
    pos[:, 0] += x0
    return pos


def main(argv=None):
    """Command line; returns the exit status."""
    p = argparse.ArgumentParser(description="Replace the two lattices of a bolide-ic sod "
                                "tube (cubic lattice) by tiled periodic glass cubes.")
    p.add_argument("lattice", help="input: HDF5 file written by bolide-ic sod (cubic lattice)")
    p.add_argument("output", help="output HDF5 file (glass tube)")
    p.add_argument("--seed", type=int, default=1, help="random seed (1)")
    p.add_argument("--iterations", type=int, default=300, help="most relaxation steps (300)")
    p.add_argument("--tolerance", type=float, default=3e-3,
                   help="stop at this rms density contrast (3e-3)")
    p.add_argument("--cache", metavar="DIR",
                   help="keep the relaxed glass cubes in DIR (glass_NG_sSEED.npy) and reuse them")
    args = p.parse_args(sys.argv[1:] if argv is None else argv)
    import shutil

    import h5py

    shutil.copyfile(args.lattice, args.output)
    with h5py.File(args.output, "r+") as f:
        box = np.asarray(f["Header"].attrs["BoxSize"], dtype=float)
        pos = f["PartType0/Coordinates"][...]
        xm = np.mod(pos[:, 0], box[0])
        left = xm < 0.5 * box[0]
        nl = int(np.count_nonzero(left))
        ntot = len(xm)
        if nl == 0 or nl != 8 * (ntot - nl) or not np.all(left[:nl]):
            common.die("%s: not a cubic-lattice bolide-ic sod tube" % args.lattice)
        a = np.cbrt(0.5 * box[0] * box[1] * box[2] / nl)  # left spacing
        n_left = [int(round(L / a)) for L in (0.5 * box[0], box[1], box[2])]
        n_right = [k // 2 for k in n_left]
        for k, (ng, n, sp, x0, sel) in enumerate(((GLASS_LEFT, n_left, a, 0.0, slice(0, nl)),
                                                   (GLASS_RIGHT, n_right, 2 * a, 0.5 * box[0],
                                                    slice(nl, None)))):
            g = glass_cube(ng, args.seed + k, args.iterations, args.tolerance, args.cache,
                           "left" if k == 0 else "right")
            pos[sel] = tile(g, ng, n, sp, x0)
        f["PartType0/Coordinates"][...] = pos
    return 0


if __name__ == "__main__":
    sys.exit(main())
