#!/usr/bin/env python3
"""Radial profile of the plate at the last snapshot of a sphere-on-plate run:
per 1 mm ring of radius r, the condensed plate material in the plate (as in
analyse.py), the fraction fractured (ShearDamage = 1), the median plastic
strain, the median Johnson-Cook damage D and the median specific internal
energy with the Johnson-Cook temperature T = T_ref + u / c_p of the
`aluminium_6061` entry (293 K, 875 J/kg/K).  README.md uses it to show what
the plate at the edge of the experimental hole (r = 1.725 cm) went through.

Usage: radial.py [--dx 0.001] RUN_DIR   (RUN_DIR holds output/plate_*.hdf5)"""
import argparse
import glob
import os
import sys

import numpy as np

sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from bolide import snapshot  # noqa: E402  (python/bolide, unless the package is installed)

RHO0, THICK, T_REF, CP = 2710.0, 0.004, 293.0, 875.0


def read(path):
    """The fields of the profile, in SI (bolide.snapshot)."""
    return snapshot.load(path, ("Coordinates", "Densities", "MaterialIDs", "ShearDamage",
                                "PlasticStrains", "InternalEnergies"), si=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run")
    ap.add_argument("--dx", type=float, default=0.001)
    a = ap.parse_args()
    snaps = sorted(glob.glob(os.path.join(a.run, "output", "plate_*.hdf5")))
    s0 = read(snaps[0])
    x0, m0 = s0["Coordinates"], s0["MaterialIDs"]
    origin = np.array([x0[m0 == 1, 0].mean(), x0[m0 == 1, 1].mean(), x0[m0 == 0, 2].max() + 0.5 * a.dx])
    s = read(snaps[-1])
    d = s["Coordinates"] - origin
    pl = (s["MaterialIDs"] == 0) & (np.abs(d[:, 2] + 0.5 * THICK) < THICK) & (s["Densities"] > 0.5 * RHO0)
    r = np.hypot(d[:, 0], d[:, 1])
    print(f"# {snaps[-1]}")
    print("  r [cm]      n   fractured   median eps_p   median D   median u [kJ/kg]   T [K]")
    for lo in np.arange(1.0, 2.55, 0.1):
        k = pl & (r >= lo / 100) & (r < (lo + 0.1) / 100)
        if not k.any():
            continue
        D, e, u = s["ShearDamage"][k], s["PlasticStrains"][k], s["InternalEnergies"][k]
        print(f"  {lo:4.1f}-{lo + 0.1:3.1f} {k.sum():6d}   {np.mean(D >= 1):9.2f}   {np.median(e):12.3f}"
              f"   {np.median(D):8.2f}   {np.median(u) / 1e3:16.1f}   {T_REF + np.median(u) / CP:5.0f}")


if __name__ == "__main__":
    main()
