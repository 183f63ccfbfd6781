#!/usr/bin/env python3
"""Plot the cumulative fragment mass spectrum of bolide-fof tables.

Reads one or more fragment tables written by `bolide-fof --out` (the last
'#' header line names the columns; "# total mass M kg" gives the total) and
draws N(>= m) against m / M_total on log-log axes, one curve per table (for
example one per resolution), with the largest fragment's mass fraction in
the legend.  Prints "largest_fraction TABLE X" for each table.
"""

import argparse
import os
import sys

import numpy as np

from bolide import common, snapshot


def read_table(path):
    """Columns (dict name -> array) and the total mass of a fragment table
    (bolide.snapshot.read_fragments); a table that cannot be read ends the
    program with one line."""
    try:
        cols, info = snapshot.read_fragments(path)
    except snapshot.SnapshotError as exc:
        common.die(str(exc))
    return cols, info["total_mass"]


def main(argv=None):
    """Plot; returns the exit status."""
    p = argparse.ArgumentParser(description="Cumulative fragment mass spectrum from bolide-fof.")
    p.add_argument("tables", nargs="+", help="fragment tables (bolide-fof --out)")
    p.add_argument("-o", "--out", help="output PNG (default: FIRST-stem_spectrum.png)")
    p.add_argument("--labels", help="comma-separated legend labels, one per table")
    args = p.parse_args(sys.argv[1:] if argv is None else argv)
    labels = args.labels.split(",") if args.labels else [os.path.basename(t) for t in args.tables]
    if len(labels) != len(args.tables):
        common.die("--labels has %d names for %d tables" % (len(labels), len(args.tables)))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4.5))
    for path, label in zip(args.tables, labels):
        cols, total = read_table(path)
        m = np.sort(cols["mass"])[::-1]
        if m.size == 0:
            common.warn("%s: no fragments" % path)
            continue
        n_ge = np.arange(1, m.size + 1)
        frac = m[0] / total
        print("largest_fraction %s %.6f" % (path, frac))
        ax.step(m / total, n_ge, where="post", label="%s (largest %.1f%%)" % (label, 100 * frac))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"fragment mass $m / M_\mathrm{total}$")
    ax.set_ylabel(r"cumulative number $N(\geq m)$")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    out = args.out or common.default_output(args.tables[0], "_spectrum.png")
    try:
        common.save_figure(fig, out)
    except OSError as e:
        common.die(str(e))
    return 0


if __name__ == "__main__":
    sys.exit(main())
