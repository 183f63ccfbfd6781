#!/usr/bin/env python3
"""Compare two statistics files (Statistics:energy_file_name) of runs that
should agree within round-off: usage: stats_compare.py A B BOUND BOX

Both files must hold the same number of lines and columns, and every column
of B must lie within BOUND of A's scale: the energies of the largest energy
(E_kin, E_int, E_tot), the momenta of sqrt(2 M E_kin) (sum m|v|), the
angular momenta of that times the box size BOX (or of their own largest
value when larger); any other column of its own largest value.  Used by
tests/program/test_mpi.sh (several ranks against one) and
tests/helpers/restart_compare.py --tol (a run resumed on another number of
ranks against the uninterrupted run)."""
import sys

import numpy as np


def compare_stats(fa, fb, bound, box):
    """None if B agrees with A within bound (see above), else one line."""
    a, b = np.loadtxt(fa, ndmin=2), np.loadtxt(fb, ndmin=2)
    if a.shape != b.shape:
        return "%s: %s lines x columns, %s %s" % (fb, b.shape, fa, a.shape)
    names = open(fa).read().split("names of the columns:")[1].split("\n")[1].split()[1:]
    col = lambda n: a[:, names.index(n)]
    E = max(np.max(np.abs(col(n))) for n in ("E_kin", "E_int", "E_tot"))
    P = np.sqrt(2.0 * np.max(col("mass")) * np.max(col("E_kin")))
    L = max(P * box, max(np.max(np.abs(col(n))) for n in ("Lx", "Ly", "Lz")))
    for k, n in enumerate(names):
        s = np.max(np.abs(a[:, k]))
        if n.startswith("E") or n in ("dE", "W_plastic"):
            s = max(s, E)
        elif n.startswith("p"):
            s = max(s, P)
        elif n.startswith("L"):
            s = max(s, L)
        d = np.max(np.abs(a[:, k] - b[:, k]))
        if not (d <= bound * s if s > 0 else d == 0):
            return "%s: column %s differs by %.3e (scale %.3e)" % (fb, n, d, s)
    return None


def main():
    fa, fb, bound, box = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
    bad = compare_stats(fa, fb, bound, box)
    if bad:
        sys.exit(bad)
    print("%s: %d lines, every column within %g of %s's" % (fb, len(np.loadtxt(fa, ndmin=2)), bound, fa))


if __name__ == "__main__":
    main()
