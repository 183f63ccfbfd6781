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


def spectrum(tables, labels=None):
    """The cumulative fragment mass spectra N(>= m) against m / M_total of
    bolide-fof tables (file names), one curve per table, as a matplotlib
    figure.  Returns (figure, fractions): fractions[k] the largest
    fragment's share of the total mass of table k, None for a table without
    fragments.  Raises bolide.snapshot.SnapshotError for a table that
    cannot be read."""
    import matplotlib.pyplot as plt

    labels = labels or [os.path.basename(t) for t in tables]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    fractions = []
    for path, label in zip(tables, labels):
        cols, info = snapshot.read_fragments(path)
        m = np.sort(cols["mass"])[::-1]
        if m.size == 0:
            fractions.append(None)
            continue
        n_ge = np.arange(1, m.size + 1)
        frac = m[0] / info["total_mass"]
        fractions.append(frac)
        ax.step(m / info["total_mass"], n_ge, where="post",
                label="%s (largest %.1f%%)" % (label, 100 * frac))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"fragment mass $m / M_\mathrm{total}$")
    ax.set_ylabel(r"cumulative number $N(\geq m)$")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig, fractions


def main(argv=None):
    """Plot; returns the exit status."""
    p = argparse.ArgumentParser(description="Cumulative fragment mass spectrum from bolide-fof.")
    p.add_argument("tables", nargs="+", help="fragment tables (bolide-fof --out)")
    p.add_argument("-o", "--out", help="output PNG (default: FIRST-stem_spectrum.png)")
    p.add_argument("--labels", help="comma-separated legend labels, one per table")
    args = p.parse_args(sys.argv[1:] if argv is None else argv)
    labels = args.labels.split(",") if args.labels else None
    if labels is not None and len(labels) != len(args.tables):
        common.die("--labels has %d names for %d tables" % (len(labels), len(args.tables)))

    import matplotlib
    matplotlib.use("Agg")

    try:
        fig, fractions = spectrum(args.tables, labels)
    except snapshot.SnapshotError as exc:
        common.die(str(exc))
    for path, frac in zip(args.tables, fractions):
        if frac is None:
            common.warn("%s: no fragments" % path)
        else:
            print("largest_fraction %s %.6f" % (path, frac))
    out = args.out or common.default_output(args.tables[0], "_spectrum.png")
    common.write_figure(fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
