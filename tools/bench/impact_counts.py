#!/usr/bin/env python3
"""
Per-cell particle counts of the planetary reference impact for
`bolide --partition N --partition-counts FILE` (issue 22 item 7,
theory/mpi.md "Scaling on paper"), without holding the particles.

The reference IC generator (make_impact_ic.py N_target N_impactor) keeps, for
each body, the n innermost points of a simple cubic lattice of spacing
dx = (4/3 pi R^3 / N_target)^(1/3) offset by half a spacing, jitters them by
+-5% of dx, centres them and places the impactor at a known offset.  The
points at lattice index (a, b, c) have r^2 = (dx/2)^2 q with the integer
q = (2a+1)^2 + (2b+1)^2 + (2c+1)^2, so "the n innermost" is "every q below a
threshold Q, and part of the shell q == Q" (the generator breaks that tie at
random; so does this script, with its own seed).  The points are then
generated one lattice plane at a time, jittered with a seed per plane (the
same in every pass), and counted per top-level cell of the box: memory
grows with the cells, not with the particles.

Three passes over the particles: (1) each body's centre and largest radius
(which place the impactor, as the generator does), (2) each top-level
cell's particle count and bounding box, (3) per particle, the neighbour
cells whose bounding box lies within the kernel support H = kernel_gamma h
(a mask of 26 bits), counted per (cell, mask).  With --from-ic FILE the same
passes (2) and (3) run on the particles of an existing IC file instead
(the check of the analytic path against the real file).  H is taken from
the largest smoothing length (the generator's are all equal), as the pair
estimate of a cell pair takes the larger h_max of the two.

Writes the text file that `bolide --partition-counts` reads:

    # comments
    grid C C C
    box L L L
    support H
    reach R
    loops 2            # pair loops per pair of cells (density, force)
    cell_tasks 3       # tasks on one cell (drift, ghost, kick)
    particles N
    cells NC
    i j k count pairmask      (NC lines)
    masks NM
    cell mask count           (NM lines; cell: the row of the cells list)

Bit d = (oi+1)*9 + (oj+1)*3 + (ok+1) of a mask stands for the neighbour at
offset (oi, oj, ok) (bit 13, the cell itself, is never set).

Usage: impact_counts.py [--cells C] [--kernel K] N_target N_impactor OUT
       impact_counts.py [--cells C] [--kernel K] --from-ic IC.hdf5 OUT
"""
import argparse
import sys
import time

import numpy as np

# the generator's constants (make_impact_ic.py)
RHO0 = 2680.0
R_TARGET = 1.0e6
V_IMP = 2.0e3
B_IMP = np.sin(np.radians(45.0))
GAP_IN_DX = 1.0
BOX = 20.0e6
ETA = 1.2348
UL = 1.0e6

# H / h of the kernels (tasks/hydro/kernel.h), by the name `bolide --version` prints
GAMMAS = {"cubic-spline": 1.825741858350554, "quartic-spline": 2.018932132718121,
          "wendland-C2": 1.936491673103709, "wendland-C4": 2.207940216581962,
          "wendland-C6": 2.449489742783178}
# ENGINE_REACH_FACTOR (src/engine.h): pairs of cells closer than this many supports
REACH_FACTOR = 1.5

OFFSETS = [(oi, oj, ok) for oi in (-1, 0, 1) for oj in (-1, 0, 1) for ok in (-1, 0, 1)]


class Body:
    """The n innermost points of the lattice, plane by plane (a = const)."""

    def __init__(self, n, dx, seed, tag):
        self.n, self.dx, self.seed, self.tag = n, dx, seed, tag
        r_est = (3.0 * n / (4.0 * np.pi)) ** (1.0 / 3.0) * dx
        self.k = k = int(np.ceil(r_est / dx)) + 3
        o = (2 * np.arange(-k, k + 1) + 1) ** 2  # (2a+1)^2 for a in -k..k
        self.o = o
        self.bc = (o[:, None] + o[None, :]).ravel()  # the plane's (2b+1)^2 + (2c+1)^2
        qmax = 3 * int(o.max())
        hist = np.zeros(qmax + 1, dtype=np.int64)
        for a in range(2 * k + 1):
            hist += np.bincount(self.bc + o[a], minlength=qmax + 1)
        cum = np.cumsum(hist)
        self.Q = Q = int(np.searchsorted(cum, n))  # first q with cum[q] >= n
        below = int(cum[Q - 1]) if Q > 0 else 0
        # the shell q == Q: take n - below of its points at random
        ties = []
        for a in range(2 * k + 1):
            idx = np.nonzero(self.bc + o[a] == Q)[0]
            for t in idx:
                ties.append((a, t))
        rng = np.random.default_rng([seed, tag, 0])
        pick = rng.permutation(len(ties))[: n - below]
        self.ties = {}
        for p in pick:
            a, t = ties[p]
            self.ties.setdefault(a, []).append(t)
        self.centre = np.zeros(3)
        self.r_max = 0.0

    def planes(self):
        """(positions about the lattice's centre, in m), one plane at a time."""
        k, dx, o = self.k, self.dx, self.o
        g = (np.arange(-k, k + 1) + 0.5) * dx
        m = 2 * k + 1
        for a in range(m):
            sel = np.nonzero(self.bc + o[a] < self.Q)[0]
            if a in self.ties:
                sel = np.sort(np.concatenate([sel, np.array(self.ties[a], dtype=sel.dtype)]))
            if len(sel) == 0:
                continue
            pos = np.empty((len(sel), 3))
            pos[:, 0] = g[a]
            pos[:, 1] = g[sel // m]
            pos[:, 2] = g[sel % m]
            rng = np.random.default_rng([self.seed, self.tag, a + 1])
            pos += rng.uniform(-0.05, 0.05, size=pos.shape) * dx
            yield pos

    def measure(self):
        s = np.zeros(3)
        r2 = 0.0
        cnt = 0
        for pos in self.planes():
            s += pos.sum(axis=0)
            r2 = max(r2, float((pos * pos).sum(axis=1).max()))
            cnt += len(pos)
        assert cnt == self.n, (cnt, self.n)
        self.centre = s / cnt
        # the generator's radius is measured after centring: the centre is
        # ~1e-4 dx off the origin, far below the jitter
        self.r_max = np.sqrt(r2)


def analytic_chunks(n_t, n_i, seed):
    """The particles of make_impact_ic.py n_t n_i, in internal units, plane by plane."""
    dx = (4.0 / 3.0 * np.pi * R_TARGET ** 3 / n_t) ** (1.0 / 3.0)
    t0 = time.time()
    bt, bi = Body(n_t, dx, seed, 1), Body(n_i, dx, seed, 2)
    bt.measure()
    bi.measure()
    print(f"# layout: dx {dx:.6g} m, target Q {bt.Q} R {bt.r_max:.6g} m, impactor Q {bi.Q} "
          f"R {bi.r_max:.6g} m ({time.time() - t0:.0f} s)", file=sys.stderr)
    y_off = B_IMP * (bt.r_max + bi.r_max)
    x_contact = np.sqrt((bt.r_max + bi.r_max) ** 2 - y_off ** 2)
    c_i = np.array([x_contact + GAP_IN_DX * dx, y_off, 0.0])
    c_com = n_i * c_i / (n_t + n_i)  # equal particle masses
    h = ETA * dx / UL
    shift_t = -bt.centre - c_com + 0.5 * BOX
    shift_i = -bi.centre + c_i - c_com + 0.5 * BOX
    # each body's extent, for the block of cells
    ext = np.array([[shift_t - bt.r_max - dx, shift_t + bt.r_max + dx],
                    [shift_i - bi.r_max - dx, shift_i + bi.r_max + dx]]) / UL
    lo, hi = ext[:, 0, :].min(axis=0), ext[:, 1, :].max(axis=0)

    def chunks():
        for body, shift in ((bt, shift_t), (bi, shift_i)):
            for pos in body.planes():
                yield (pos + shift) / UL

    return chunks, float(np.float32(h)), lo, hi, n_t + n_i, BOX / UL


def file_chunks(path, size=1 << 20):
    from bolide import snapshot
    try:
        snap = snapshot.load(path, fields=["SmoothingLengths"])
        h = float(np.max(snap["SmoothingLengths"]))
        box = np.atleast_1d(snap["header"].get("BoxSize", np.zeros(3))).astype(float)
        if np.ptp(box) > 0:
            sys.exit(f"impact_counts: {path}: the box is not a cube ({box})")
        lo, hi, n = np.full(3, np.inf), np.full(3, -np.inf), 0
        for c in snapshot.iter_chunks(path, "Coordinates", size):
            lo, hi = np.minimum(lo, c.min(axis=0)), np.maximum(hi, c.max(axis=0))
            n += c.shape[0]
    except snapshot.SnapshotError as exc:
        sys.exit(f"impact_counts: {exc}")

    def chunks():
        yield from snapshot.iter_chunks(path, "Coordinates", size)

    return chunks, h, lo, hi, n, float(box[0])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cells", type=int, default=640, help="top-level cells per side (default 640)")
    ap.add_argument("--kernel", default="wendland-C2", choices=sorted(GAMMAS),
                    help="the build's kernel, as bolide --version names it (default wendland-C2)")
    ap.add_argument("--seed", type=int, default=12345)
    ap.add_argument("--loops", type=int, default=2,
                    help="pair loops per pair of cells: 2 hydro (density, force), 3 with solids")
    ap.add_argument("--cell-tasks", type=int, default=3,
                    help="tasks on one cell that the estimate counts (drift, ghost, kick: 3)")
    ap.add_argument("--from-ic", metavar="IC", help="count the particles of this IC file instead")
    ap.add_argument("args", nargs="+", help="N_target N_impactor OUT, or OUT with --from-ic")
    o = ap.parse_args()
    if o.from_ic:
        if len(o.args) != 1:
            ap.error("--from-ic takes one more argument: OUT")
        chunks, h, lo, hi, ntot, box = file_chunks(o.from_ic)
        out = o.args[0]
        source = f"the particles of {o.from_ic}"
    else:
        if len(o.args) != 3:
            ap.error("expected N_target N_impactor OUT")
        n_t, n_i = int(float(o.args[0])), int(float(o.args[1]))
        chunks, h, lo, hi, ntot, box = analytic_chunks(n_t, n_i, o.seed)
        out = o.args[2]
        source = f"the analytic layout of make_impact_ic.py {n_t} {n_i} (seed {o.seed})"

    o.gamma = GAMMAS[o.kernel]
    C = o.cells
    width = box / C
    H = o.gamma * h
    reach = min(width, REACH_FACTOR * H)
    if H >= width:
        sys.exit(f"impact_counts: the kernel support {H:g} exceeds the cell width {width:g}")

    def cell_of(x):
        i = np.floor(x / width).astype(np.int64)
        return np.clip(i, 0, C - 1)

    # the block of cells that can hold particles, one cell of margin
    b0 = np.maximum(cell_of(lo) - 1, 0)
    b1 = np.minimum(cell_of(hi) + 2, C)
    bd = b1 - b0
    nb = int(np.prod(bd))

    def local(ijk):
        return ((ijk[:, 0] - b0[0]) * bd[1] + (ijk[:, 1] - b0[1])) * bd[2] + (ijk[:, 2] - b0[2])

    # pass 2: counts and bounding boxes
    t0 = time.time()
    count = np.zeros(nb, dtype=np.int64)
    bmin = np.full((nb, 3), np.inf)
    bmax = np.full((nb, 3), -np.inf)
    seen = 0
    for x in chunks():
        c = local(cell_of(x))
        count += np.bincount(c, minlength=nb)
        for d in range(3):
            np.minimum.at(bmin[:, d], c, x[:, d])
            np.maximum.at(bmax[:, d], c, x[:, d])
        seen += len(x)
    if seen != ntot:
        sys.exit(f"impact_counts: {seen} particles counted, {ntot} expected")
    print(f"# counts: {seen} particles in {int((count > 0).sum())} cells "
          f"({time.time() - t0:.0f} s)", file=sys.stderr)

    # the neighbour of every block cell in each direction (-1: none or empty)
    ii = np.arange(nb)
    ci = np.stack([ii // (bd[1] * bd[2]), (ii // bd[2]) % bd[1], ii % bd[2]], axis=1)
    nbr = np.full((27, nb), -1, dtype=np.int64)
    for d, off in enumerate(OFFSETS):
        if off == (0, 0, 0):
            continue
        q = ci + np.array(off)
        ok = np.all((q >= 0) & (q < bd), axis=1)
        idx = np.where(ok, (q[:, 0] * bd[1] + q[:, 1]) * bd[2] + q[:, 2], 0)
        nbr[d] = np.where(ok & (count[idx] > 0) & (count > 0), idx, -1)
    # pairs: non-empty neighbours whose bounding boxes come closer than the reach
    pairmask = np.zeros(nb, dtype=np.int64)
    for d in range(27):
        j = nbr[d]
        has = j >= 0
        jj = np.where(has, j, 0)
        g = np.maximum(bmin[jj] - bmax, bmin - bmax[jj])
        d2 = (np.maximum(g, 0.0) ** 2).sum(axis=1)
        pairmask |= np.where(has & (d2 < reach * reach), 1 << d, 0)
    for d in range(27):
        nbr[d] = np.where((pairmask >> d) & 1 == 1, nbr[d], -1)

    # pass 3: per particle, the neighbours within the support (partition_near's test)
    t0 = time.time()
    keys_acc, cnt_acc = [], []
    for x in chunks():
        c = local(cell_of(x))
        mask = np.zeros(len(x), dtype=np.int64)
        for d in range(27):
            j = nbr[d][c]
            has = j >= 0
            if not has.any():
                continue
            jj = np.where(has, j, 0)
            g = np.maximum(bmin[jj] - x, x - bmax[jj])
            d2 = (np.maximum(g, 0.0) ** 2).sum(axis=1)
            mask |= np.where(has & (d2 <= H * H), 1 << d, 0)
        k, n = np.unique(c * (1 << 27) + mask, return_counts=True)
        keys_acc.append(k)
        cnt_acc.append(n)
        if len(keys_acc) > 64:
            k, inv = np.unique(np.concatenate(keys_acc), return_inverse=True)
            n = np.bincount(inv, weights=np.concatenate(cnt_acc)).astype(np.int64)
            keys_acc, cnt_acc = [k], [n]
    k, inv = np.unique(np.concatenate(keys_acc), return_inverse=True)
    n = np.bincount(inv, weights=np.concatenate(cnt_acc)).astype(np.int64)
    print(f"# masks: {len(k)} (cell, mask) rows ({time.time() - t0:.0f} s)", file=sys.stderr)

    # the rows: non-empty cells in block order
    full = np.nonzero(count > 0)[0]
    row = np.full(nb, -1, dtype=np.int64)
    row[full] = np.arange(len(full))
    with open(out, "w") as f:
        f.write(f"# bolide partition counts: {source}\n")
        f.write(f"# top-level cells per side {C}, h {h:.9g}, kernel gamma {o.gamma:.12g}\n")
        f.write(f"grid {C} {C} {C}\nbox {box:.17g} {box:.17g} {box:.17g}\n")
        f.write(f"support {H:.17g}\nreach {reach:.17g}\n")
        f.write(f"loops {o.loops}\ncell_tasks {o.cell_tasks}\nparticles {seen}\n")
        f.write(f"cells {len(full)}\n")
        g = ci[full] + b0
        np.savetxt(f, np.column_stack([g, count[full], pairmask[full]]), fmt="%d")
        f.write(f"masks {len(k)}\n")
        np.savetxt(f, np.column_stack([row[k >> 27], k & ((1 << 27) - 1), n]), fmt="%d")
    print(f"# wrote {out}", file=sys.stderr)


if __name__ == "__main__":
    main()
