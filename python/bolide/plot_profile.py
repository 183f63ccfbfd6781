#!/usr/bin/env python3
"""Plot a planet profile written by `bolide-ic planet --profile FILE`:
density, pressure, temperature and enclosed mass against radius.

usage: plot_profile.py PROFILE.txt [OUT.png]"""
import sys

import numpy as np

from bolide import common

#: The columns of a profile file (bolide-ic planet --profile), SI.
COLUMNS = ("r", "m", "rho", "P", "T", "u", "layer")


def read_profile(path):
    """The profile's columns as a dict (COLUMNS, SI); ValueError for a file
    that is not one."""
    try:
        d = np.loadtxt(path, ndmin=2)
    except (OSError, ValueError) as e:
        raise ValueError(f"{path}: {e}")
    if d.shape[1] != len(COLUMNS):
        raise ValueError(f"{path}: expected {len(COLUMNS)} columns ({' '.join(COLUMNS)})")
    return {name: d[:, k] for k, name in enumerate(COLUMNS)}


def profile_figure(prof):
    """Density, pressure, temperature and enclosed mass against radius (km),
    one line per layer, of a profile (read_profile's dict or a file name)
    as a matplotlib figure."""
    import matplotlib.pyplot as plt
    if isinstance(prof, str):
        prof = read_profile(prof)
    r = prof["r"] / 1e3
    fig, ax = plt.subplots(2, 2, figsize=(9, 7), sharex=True)
    for a, col, lab, log in ((ax[0, 0], "rho", r"$\rho$ [kg m$^{-3}$]", False),
                             (ax[0, 1], "P", "P [Pa]", True),
                             (ax[1, 0], "T", "T [K]", False),
                             (ax[1, 1], "m", "m(<r) [kg]", False)):
        for k in np.unique(prof["layer"]):
            s = prof["layer"] == k
            a.plot(r[s], prof[col][s], label=f"layer {int(k)}")
        a.set_ylabel(lab)
        if log:
            a.set_yscale("log")
    for a in ax[1]:
        a.set_xlabel("r [km]")
    ax[0, 0].legend()
    fig.tight_layout()
    return fig


def main(argv=None):
    """Command line (console script bolide-plot-profile); returns the exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if len(argv) not in (1, 2) or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv and argv[0] in ("-h", "--help") else 2
    path = argv[0]
    out = argv[1] if len(argv) == 2 else path.rsplit(".", 1)[0] + ".png"
    try:
        prof = read_profile(path)
    except ValueError as e:
        common.die(str(e))
    import matplotlib
    matplotlib.use("Agg")
    common.write_figure(profile_figure(prof), out, dpi=100)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
