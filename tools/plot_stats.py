#!/usr/bin/env python3
"""Plot Bolide's statistics file: energies and conservation drifts vs time.

Columns are found by the names of the '#' header line (time, mass, px py pz,
Lx Ly Lz, E_kin E_int E_pot E_tot, ...); missing optional columns are
skipped.  Prints

    max_rel_energy_drift X      max_t |E_tot(t) - E_tot(0)| / E_scale
    max_rel_momentum_drift X    max_t |p(t) - p(0)| / p_scale
    max_rel_angular_momentum_drift X   max_t |L(t) - L(0)| / L_scale
    max_rel_energy_budget X     max_t |dE(t)| / |E_pot(0)| (or / E_scale without
                                gravity), dE = E_tot + E_removed - E_clamp - E_tot(0),
                                when the file has the budget columns

The momenta include what left an open box (the *_removed columns) when the
file has them.

E_scale is |E_tot(0)|, or |E_kin(0)| + |E_int(0)| + |E_pot(0)| when E_tot(0)
is less than 1e-3 of that sum (a system whose energies cancel).  The total
momentum of a collision is usually zero, so p_scale = sqrt(2 M max_t E_kin),
the momentum the kinetic energy would have if all the mass moved together
(max_t |p| when mass or E_kin is missing).  The angular momentum drift is
relative to max_t |L| and is not printed when L is identically zero.
"""

import argparse
import os
import sys

import numpy as np

# an installed bolide first, else the source tree's (python/ beside tools/)
# or an install's (PREFIX/bin/SCRIPT: PREFIX/share/bolide/python)
_here = os.path.dirname(os.path.abspath(__file__))
sys.path += [os.path.join(_here, "..", "python"), os.path.join(_here, "..", "share", "bolide", "python")]
from bolide import common, snapshot  # noqa: E402


def parse_args(argv):
    """Command line."""
    p = argparse.ArgumentParser(
        description="Plot energies and the relative drift of total energy and momentum "
        "from a Bolide statistics file.")
    p.add_argument("stats", help="statistics file (whitespace columns, '#' header naming them)")
    p.add_argument("--out", help="output PNG (default: STATS-stem_stats.png)")
    return p.parse_args(argv)


def energy_scale(cols):
    """|E_tot(0)|, or the sum of the magnitudes of the parts when E_tot(0)
    nearly cancels (see module doc)."""
    parts = sum(abs(cols[k][0]) for k in ("E_kin", "E_int", "E_pot") if k in cols)
    e0 = abs(cols["E_tot"][0])
    if parts > 0 and e0 < 1e-3 * parts:
        return parts
    return e0


def main(argv=None):
    """Plot and print the drifts; returns the exit status."""
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        cols = snapshot.read_stats(args.stats)
    except snapshot.SnapshotError as exc:
        common.die(str(exc))
    if "time" not in cols:
        common.die("%s: no 'time' column in the header" % args.stats)
    if cols["time"].size == 0:
        common.die("%s: no data rows" % args.stats)
    if "E_tot" not in cols:
        parts = [k for k in ("E_kin", "E_int", "E_pot") if k in cols]
        if not parts:
            common.die("%s: neither E_tot nor E_kin/E_int/E_pot columns" % args.stats)
        cols["E_tot"] = sum(cols[k] for k in parts)
    t = cols["time"]

    e_scale = energy_scale(cols)
    e_drift = (cols["E_tot"] - cols["E_tot"][0]) / e_scale if e_scale > 0 else None
    if e_drift is not None:
        print("max_rel_energy_drift %.6g" % np.max(np.abs(e_drift)))
    p_drift = None
    for k in ("px", "py", "pz", "Lx", "Ly", "Lz"):
        if k in cols and k + "_removed" in cols:
            cols[k] = cols[k] + cols[k + "_removed"]
    budget = None
    if "dE" in cols:
        b_scale = abs(cols["E_pot"][0]) if "E_pot" in cols and cols["E_pot"][0] != 0 else e_scale
        if b_scale > 0:
            budget = cols["dE"] / b_scale
            print("max_rel_energy_budget %.6g" % np.max(np.abs(budget)))
    if all(k in cols for k in ("px", "py", "pz")):
        p = np.stack([cols["px"], cols["py"], cols["pz"]], axis=1)
        dp = np.sqrt(np.sum((p - p[0]) ** 2, axis=1))
        scale = 0.0
        if "mass" in cols and "E_kin" in cols:
            scale = np.sqrt(2.0 * cols["mass"][0] * np.max(cols["E_kin"]))
        if not scale > 0:
            scale = np.max(np.sqrt(np.sum(p * p, axis=1)))
        if scale > 0:
            p_drift = dp / scale
            print("max_rel_momentum_drift %.6g" % np.max(p_drift))
    l_drift = None
    if all(k in cols for k in ("Lx", "Ly", "Lz")):
        L = np.stack([cols["Lx"], cols["Ly"], cols["Lz"]], axis=1)
        dl = np.sqrt(np.sum((L - L[0]) ** 2, axis=1))
        scale = np.max(np.sqrt(np.sum(L * L, axis=1)))
        l_max = scale
        if scale > 0:
            l_drift = dl / scale
            print("max_rel_angular_momentum_drift %.6g" % np.max(l_drift))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for key, label in (("E_kin", "kinetic"), ("E_int", "internal"), ("E_pot", "potential"),
                       ("E_tot", "total")):
        if key in cols:
            ax1.plot(t, cols[key], label=label, lw=2.0 if key == "E_tot" else 1.2)
    ax1.set_ylabel("energy")
    ax1.legend(loc="best", fontsize="small")
    # magnitudes on a log axis: drifts of 1e-4 and of order 1 side by side
    # (a body without net spin has max|L| at rounding level: its L curve is
    # then of order 1 and says nothing; the legend gives max|L|)
    floor = 1e-16
    if e_drift is not None:
        ax2.semilogy(t, np.maximum(np.abs(e_drift), floor), label=r"$|E_{tot} - E_{tot,0}| / E_{scale}$")
    if budget is not None:
        ax2.semilogy(t, np.maximum(np.abs(budget), floor),
                     label=r"budget $|dE| / |E_{pot,0}|$ (removed and clamps counted)")
    if p_drift is not None:
        ax2.semilogy(t, np.maximum(p_drift, floor), label=r"$|p - p_0| / p_{scale}$")
    if l_drift is not None:
        ax2.semilogy(t, np.maximum(l_drift, floor),
                     label=r"$|L - L_0| / \max|L|$ (max|L| = %.2g)" % l_max)
    ax2.set_xlabel("time")
    ax2.set_ylabel("relative drift (magnitude)")
    ax2.legend(loc="best", fontsize="small")
    fig.suptitle("Conservation: %s" % args.stats)
    fig.tight_layout()
    out = args.out or common.default_output(args.stats, "_stats.png")
    common.write_figure(fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
