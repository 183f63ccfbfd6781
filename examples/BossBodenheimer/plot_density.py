#!/usr/bin/env python3
"""Maximum density against time in units of the free-fall time for the
Boss-Bodenheimer collapse, from every snapshot in the folder.
Usage: plot_density.py [SNAPSHOT_GLOB] [--out PNG]"""
import argparse
import glob
import os
import sys

import numpy as np

sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from bolide import snapshot  # noqa: E402  (python/bolide, unless the package is installed)

TFF = 5.529e11
RHO0 = 1.44e-14


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("pattern", nargs="?", default="cloud_*.hdf5")
    ap.add_argument("--out", default="max_density.png")
    a = ap.parse_args()
    files = sorted(glob.glob(a.pattern))
    if not files:
        raise SystemExit("plot_density.py: error: no snapshot matches %s" % a.pattern)
    t, rmax = [], []
    for f in files:
        s = snapshot.load(f, ["Densities"], si=True)
        t.append(snapshot.snapshot_time(s) / TFF)
        rmax.append(float(s["Densities"].max()))
    for ti, ri in zip(t, rmax):
        print("t/t_ff %.3f max_density %.4e kg/m^3 (%.3g rho0)" % (ti, ri, ri / RHO0))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.semilogy(t, np.array(rmax) / RHO0, "o-")
    ax.set_xlabel("t / t_ff")
    ax.set_ylabel("max density / rho0")
    ax.set_title("Boss-Bodenheimer collapse")
    fig.tight_layout()
    fig.savefig(a.out + ".tmp.png", dpi=120)
    os.replace(a.out + ".tmp.png", a.out)
    print("plot:", a.out)


if __name__ == "__main__":
    main()
