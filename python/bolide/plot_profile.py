#!/usr/bin/env python3
"""Plot a planet profile written by `bolide-ic planet --profile FILE`:
density, pressure, temperature and enclosed mass against radius.

usage: plot_profile.py PROFILE.txt [OUT.png]"""
import sys

import numpy as np

from bolide import common


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if len(argv) not in (1, 2) or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv and argv[0] in ("-h", "--help") else 2
    path = argv[0]
    out = argv[1] if len(argv) == 2 else path.rsplit(".", 1)[0] + ".png"
    try:
        d = np.loadtxt(path, ndmin=2)
    except (OSError, ValueError) as e:
        common.die(f"{path}: {e}")
    if d.shape[1] != 7:
        common.die(f"{path}: expected 7 columns (r m rho P T u layer)")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    r = d[:, 0] / 1e3
    fig, ax = plt.subplots(2, 2, figsize=(9, 7), sharex=True)
    for a, col, lab, log in ((ax[0, 0], 2, r"$\rho$ [kg m$^{-3}$]", False),
                             (ax[0, 1], 3, "P [Pa]", True),
                             (ax[1, 0], 4, "T [K]", False),
                             (ax[1, 1], 1, "m(<r) [kg]", False)):
        for k in np.unique(d[:, 6]):
            s = d[:, 6] == k
            a.plot(r[s], d[s, col], label=f"layer {int(k)}")
        a.set_ylabel(lab)
        if log:
            a.set_yscale("log")
    for a in ax[1]:
        a.set_xlabel("r [km]")
    ax[0, 0].legend()
    fig.tight_layout()
    try:
        common.save_figure(fig, out, dpi=100)
    except OSError as e:
        common.die(str(e))
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
