#!/usr/bin/env python3
"""Where and under which stress the target of a NakamuraBasalt run breaks.

For each snapshot of RUN (or the ones given by index), the basalt particles
are binned by their distance from the impact point (the first contact point,
from the initial snapshot: 30 degrees off the line of centres, in the x-y
plane, as bolide-ic impact sets it up).  Per bin: the fraction of particles
with d > 0 and with d = 1, the median pressure, the median largest principal
stress of the still undamaged particles (the stress that activates the next
flaws, theory/damage.md D3), and the fraction of particles in tension whose
largest principal axis is radial (|cos| > 0.7 against the direction from the
impact point): near 0 means the tension is hoop (tangential) tension behind
the diverging compressive wave, near 1 radial tension (spallation).

Usage: diagnose.py RUN [SNAPSHOT_INDEX ...]
"""
import glob
import os
import sys

import numpy as np

sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from bolide import snapshot  # noqa: E402  (python/bolide, unless the package is installed)

BASALT = 103
ANGLE = np.radians(30.0)
# snapshot component order of DeviatoricStress: xx xy xz yy yz zz (src/part.h)
COMP = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)]


def load(path):
    """The fields of the diagnosis, in SI (bolide.snapshot); "t" the time."""
    out = snapshot.load(path, ("Coordinates", "Damage", "Pressures", "DeviatoricStress",
                               "MaterialIDs", "Masses"), si=True)
    out["t"] = snapshot.snapshot_time(out)
    return out


def damaged_stress(d, P, S):
    """sigma = -P_d I + (1 - d) S, P_d = (1 - d) P in tension (theory/damage.md D5)."""
    n = len(P)
    sig = np.zeros((n, 3, 3))
    for a, (i, j) in enumerate(COMP):
        sig[:, i, j] = sig[:, j, i] = S[:, a]
    sig *= (1.0 - d)[:, None, None]
    Pd = np.where(P < 0.0, (1.0 - d) * P, P)
    for i in range(3):
        sig[:, i, i] -= Pd
    return sig


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    run = sys.argv[1]
    snaps = sorted(glob.glob(os.path.join(run, "nakamura_[0-9]*.hdf5")))
    if not snaps:
        sys.exit("%s: no snapshots" % run)
    first = load(snaps[0])
    tg = first["MaterialIDs"] == BASALT
    x0 = first["Coordinates"][tg]
    m0 = first["Masses"][tg]
    centre = (x0 * m0[:, None]).sum(0) / m0.sum()
    radius = np.max(np.linalg.norm(x0 - centre, axis=1))
    # the impactor arrives along +x, offset along +y (bolide-ic impact)
    impact = centre + radius * np.array([-np.cos(ANGLE), np.sin(ANGLE), 0.0])
    pick = [snaps[int(k)] for k in sys.argv[2:]] or snaps[1:]
    edges = np.linspace(0.0, 2.0 * radius, 13)
    for s in pick:
        d = load(s)
        tg = d["MaterialIDs"] == BASALT
        x, D, P, S = d["Coordinates"][tg], d["Damage"][tg], d["Pressures"][tg], d["DeviatoricStress"][tg]
        lam, vec = np.linalg.eigh(damaged_stress(D, P, S))
        smax, axis = lam[:, 2], vec[:, :, 2]
        rel = x - impact
        dist = np.linalg.norm(rel, axis=1)
        radial = np.abs(np.sum(axis * rel / np.maximum(dist, 1e-30)[:, None], axis=1)) > 0.7
        print("t = %.1f us" % (d["t"] * 1e6))
        print("  dist [mm]     n  d>0   d=1   P_med[MPa]  smax_med(d=0)[MPa]  radial(smax>0)")
        k = np.digitize(dist, edges)
        for b in range(1, len(edges)):
            sel = k == b
            if not sel.any():
                continue
            und = sel & (D == 0.0)
            ten = sel & (smax > 0.0)
            print("  %4.0f-%4.0f %5d  %.2f  %.2f  %9.1f  %12s  %14s" % (
                1e3 * edges[b - 1], 1e3 * edges[b], sel.sum(), np.mean(D[sel] > 0), np.mean(D[sel] >= 1),
                np.median(P[sel]) / 1e6,
                "%.1f" % (np.median(smax[und]) / 1e6) if und.any() else "-",
                "%.2f" % np.mean(radial[ten]) if ten.any() else "-"))


if __name__ == "__main__":
    main()
