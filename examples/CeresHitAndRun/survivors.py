#!/usr/bin/env python3
"""The two largest fragments of a bolide-fof table next to Schaefer et al.
(2016): masses 9.55e20 and 9.17e20 kg, escaping each other, damaged 61% and
70%.  Prints one table; exits 1 when there are not two fragments.

Usage: survivors.py FRAGMENTS.txt [SNAPSHOT]   (the snapshot only names the time)
"""
import os
import sys

import numpy as np

sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from bolide import snapshot  # noqa: E402  (python/bolide, unless the package is installed)

G = 6.67430e-11
PAPER_MASS = (9.55e20, 9.17e20)
PAPER_DAMAGE = (0.61, 0.70)


def main(argv):
    if len(argv) < 2:
        print("usage: survivors.py FRAGMENTS.txt [SNAPSHOT]", file=sys.stderr)
        return 2
    try:
        t, info = snapshot.read_fragments(argv[1])
    except snapshot.SnapshotError as exc:
        print("survivors.py: error: %s" % exc, file=sys.stderr)
        return 1
    names, total, nrows = list(t), info["total_mass"], len(t["mass"])
    time = "%.9g" % info["time"] if info["time"] is not None else "?"
    if nrows < 2:
        print("survivors.py: %s: fewer than two fragments" % argv[1], file=sys.stderr)
        return 1
    order = np.argsort(-t["mass"])[:2]
    fracs = [k for k in names if k.startswith("frac_mat")]
    print("# Ceres hit-and-run survivors at t = %s s (bolide-fof, the two largest fragments)"
          % time)
    print("# %-8s %12s %12s %8s %10s %10s %s" % ("survivor", "mass[kg]", "paper[kg]", "ratio",
                                                 "damage", "paper", " ".join(fracs)))
    for k, i in enumerate(order):
        print("  %-8d %12.4e %12.4e %8.3f %10.3f %10.2f %s"
              % (k + 1, t["mass"][i], PAPER_MASS[k], t["mass"][i] / PAPER_MASS[k],
                 t["damage"][i], PAPER_DAMAGE[k], " ".join("%.3f" % t[f][i] for f in fracs)))
    a, b = order
    dx = np.array([t[c][a] - t[c][b] for c in ("x", "y", "z")])
    dv = np.array([t[c][a] - t[c][b] for c in ("vx", "vy", "vz")])
    r, v = np.linalg.norm(dx), np.linalg.norm(dv)
    e = 0.5 * v * v - G * (t["mass"][a] + t["mass"][b]) / r
    print("# separation %.4g m, relative speed %.4g m/s, two-body energy %.4g J/kg: %s"
          % (r, v, e, "they escape each other" if e > 0 else "bound to each other"))
    print("# the rest: %.4e kg (%d more listed fragments, the others below --min-count)"
          % (total - t["mass"][order].sum(), nrows - 2))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
