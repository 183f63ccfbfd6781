#!/usr/bin/env python3
"""Plot an EOS table written by bolide-eos: pressure and sound speed against
density, one curve per specific internal energy.

Usage: plot_eos.py TABLE PNG [TITLE]

TABLE has one header line naming the columns (density,
specific_internal_energy, pressure, sound_speed[, temperature]) and
whitespace-separated SI values.  The PNG is written to a temporary name and
renamed, so a failed plot leaves no partial file."""
import os
import sys


def main(argv):
    if len(argv) not in (3, 4):
        sys.stderr.write("plot_eos.py: error: usage: plot_eos.py TABLE PNG [TITLE]\n")
        return 1
    table, png = argv[1], argv[2]
    title = argv[3] if len(argv) == 4 else os.path.basename(table)
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with open(table) as f:
        names = f.readline().split()
    need = ("density", "specific_internal_energy", "pressure", "sound_speed")
    if any(n not in names for n in need):
        sys.stderr.write(f"plot_eos.py: error: {table}: header must name {' '.join(need)}\n")
        return 1
    data = np.atleast_2d(np.loadtxt(table, skiprows=1))
    col = {n: data[:, names.index(n)] for n in names}
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for u in np.unique(col["specific_internal_energy"]):
        sel = col["specific_internal_energy"] == u
        order = np.argsort(col["density"][sel])
        rho = col["density"][sel][order]
        ax1.plot(rho, col["pressure"][sel][order], label=f"u = {u:.3g} J/kg")
        ax2.plot(rho, col["sound_speed"][sel][order])
    ax1.axhline(0.0, color="0.7", lw=0.5)
    ax1.set_xlabel("density [kg m$^{-3}$]")
    ax1.set_ylabel("pressure [Pa]")
    ax2.set_xlabel("density [kg m$^{-3}$]")
    ax2.set_ylabel("sound speed [m s$^{-1}$]")
    ax1.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    tmp = png + ".tmp.png"
    try:
        fig.savefig(tmp, dpi=110)
        os.replace(tmp, png)
    except OSError as err:  # one line, no traceback (issue 18)
        if os.path.exists(tmp):
            os.remove(tmp)
        sys.stderr.write(f"plot_eos.py: error: {png}: {err.strerror or err}\n")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
