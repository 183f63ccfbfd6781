#!/usr/bin/env python3
"""Pictures and budgets of a planetary impact run (examples/EarthImpact,
examples/CeresHitAndRun).

* collision.png: x-y slices through the centre of mass of up to six
  snapshots (evenly chosen), particles coloured by material; the impactor's
  materials (ids >= --impactor-offset) in lighter shades.
* bound.png and a table on standard output: the mass bound to the largest
  remnant against time, total and per material.  The remnant is found by
  the usual iteration (e.g. Marcus et al. 2009, ApJ 700, L118): start from
  the target's particles (material id < --impactor-offset), take the mass
  M_b, centre x_b and velocity v_b of the bound set, call a particle bound
  when |v - v_b|^2 / 2 - G M_b / |x - x_b| < 0 (the remnant as a point
  mass), and repeat until the set no longer changes.
* energy.png: kinetic, internal, potential and total energy from the
  statistics file, and the drift of the total, |E_tot(t) - E_tot(0)| /
  max|E_pot|.  Units as in the files (SI for SI runs).
"""
import argparse
import sys

import numpy as np

from bolide import common, snapshot

G_SI = 6.67430e-11


def parse_args(argv):
    p = argparse.ArgumentParser(description="Pictures, bound mass and energy budget of an impact.")
    p.add_argument("snapshots", nargs="+", help="HDF5 snapshots, in time order")
    p.add_argument("--stats", help="statistics file (energy budget); none: no energy plot")
    p.add_argument("--impactor-offset", type=int, default=1000,
                   help="material ids >= this belong to the impactor (default 1000)")
    p.add_argument("--G", type=float, default=G_SI, help="gravitational constant (default SI)")
    p.add_argument("--length-unit", type=float, default=6.371e6,
                   help="length unit of the pictures in m (default the Earth radius)")
    p.add_argument("--length-name", default="R_E", help="its name (default R_E)")
    p.add_argument("--prefix", default="", help="prefix of the PNG names")
    return p.parse_args(argv)


def bound_mass(pos, vel, m, seed, G, iters=100):
    """Mask of the particles bound to the remnant grown from the mask seed."""
    bound = seed.copy()
    for _ in range(iters):
        if not bound.any():
            return bound
        mb = m[bound].sum()
        xb = (m[bound, None] * pos[bound]).sum(0) / mb
        vb = (m[bound, None] * vel[bound]).sum(0) / mb
        r = np.linalg.norm(pos - xb, axis=1)
        e = 0.5 * np.sum((vel - vb) ** 2, axis=1) - G * mb / np.maximum(r, 1e-300)
        new = e < 0
        if np.array_equal(new, bound):
            break
        bound = new
    return bound


def load_snapshots(paths):
    """The snapshots' positions, velocities, masses, material ids (and
    smoothing lengths) in SI whatever their units (SWIFT's planetary runs
    use Earth masses and radii; G is in SI).  Raises SnapshotError."""
    return [snapshot.load(path, ["Coordinates", "Velocities", "Masses", "MaterialIDs"],
                          optional=["SmoothingLengths"], si=True) for path in paths]


def bound_history(snaps, impactor_offset=1000, G=G_SI):
    """The mass bound to the largest remnant in each snapshot (loaded with
    load_snapshots or snapshot.load(si=True)), grown from the target's
    particles (material id < impactor_offset).  Returns a dict: "time" (s),
    "bound" (kg), "fraction" (of the total mass), "materials" (the ids) and
    "per_material" (kg, one column per id)."""
    mats = np.unique(np.concatenate([s["MaterialIDs"] for s in snaps]).astype(int))
    times, bound, frac, per = [], [], [], []
    for s in snaps:
        pos, vel, m = s["Coordinates"], s["Velocities"], s["Masses"]
        mat = s["MaterialIDs"].astype(int)
        b = bound_mass(pos, vel, m, mat < impactor_offset, G)
        times.append(float(s["header"].get("Time", np.nan)))
        bound.append(m[b].sum())
        frac.append(m[b].sum() / m.sum())
        per.append([m[b & (mat == k)].sum() for k in mats])
    return {"time": np.array(times), "bound": np.array(bound), "fraction": np.array(frac),
            "materials": mats, "per_material": np.array(per).reshape(len(snaps), len(mats))}


def bound_figure(hist, total_mass):
    """The bound mass against time (bound_history's dict), in total and per
    material, as fractions of total_mass; a matplotlib figure."""
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    t = hist["time"]
    ax.plot(t / 3600, hist["fraction"], "k-o", label="all")
    for k, mk in enumerate(hist["materials"]):
        ax.plot(t / 3600, hist["per_material"][:, k] / total_mass, "-", label="material %d" % mk)
    ax.set_xlabel("t [h]")
    ax.set_ylabel("mass bound to the largest remnant / total mass")
    ax.legend(fontsize="small")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def collision_figure(snaps, length_unit=6.371e6, length_name="R_E", panels=6):
    """x-y slices through the centre of mass of up to PANELS snapshots
    (evenly chosen), coloured by material, lengths in length_unit (m); a
    matplotlib figure."""
    import matplotlib.pyplot as plt
    mats = np.unique(np.concatenate([s["MaterialIDs"] for s in snaps]).astype(int))
    pick = np.unique(np.linspace(0, len(snaps) - 1, min(panels, len(snaps))).round().astype(int))
    ncol = min(3, len(pick))
    nrow = (len(pick) + ncol - 1) // ncol
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.2 * ncol, 4.0 * nrow), squeeze=False)
    base = plt.get_cmap("tab10")
    colours = {mk: base(k % 10) for k, mk in enumerate(mats)}
    L = length_unit
    for a, i in zip(axes.flat, pick):
        s = snaps[i]
        pos, m = s["Coordinates"], s["Masses"]
        mat = s["MaterialIDs"].astype(int)
        com = (m[:, None] * pos).sum(0) / m.sum()
        h = s.get("SmoothingLengths")
        thick = 4 * np.median(h) if h is not None else 0.1 * np.ptp(pos[:, 2])
        keep = np.abs(pos[:, 2] - com[2]) < 0.5 * thick
        size = float(np.clip(1.5e4 / max(keep.sum(), 1), 0.3, 20))
        for mk in mats:
            sel = keep & (mat == mk)
            a.scatter((pos[sel, 0] - com[0]) / L, (pos[sel, 1] - com[1]) / L, s=size, lw=0,
                      color=colours[mk], label="mat %d" % mk, rasterized=True)
        a.set_aspect("equal")
        a.set_title("t = %.2f h" % (float(s["header"].get("Time", np.nan)) / 3600))
        a.set_xlabel("x [%s]" % length_name)
        a.set_ylabel("y [%s]" % length_name)
    for a in list(axes.flat)[len(pick):]:
        a.axis("off")
    handles, labels = axes.flat[0].get_legend_handles_labels()
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    fig.legend(handles, labels, loc="lower center", ncol=len(mats), fontsize="small",
               markerscale=5)
    return fig


def energy_figure(stats):
    """Kinetic, internal, potential and total energy against time, and the
    drift |E_tot(t) - E_tot(0)| / max|E_pot|, of a statistics file's columns
    (snapshot.read_stats(path, si=True)).  Returns (figure, drift)."""
    import matplotlib.pyplot as plt
    t = stats["time"]
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True)
    for key in ("E_kin", "E_int", "E_pot", "E_tot"):
        a1.plot(t / 3600, stats[key], label=key)
    a1.set_ylabel("energy")
    a1.legend(fontsize="small")
    a1.grid(alpha=0.3)
    scale = np.abs(stats["E_pot"]).max()
    drift = np.abs(stats["E_tot"] - stats["E_tot"][0]) / scale
    a2.semilogy(t / 3600, np.maximum(drift, 1e-16))
    a2.set_ylabel("|E_tot - E_tot(0)| / max|E_pot|")
    a2.set_xlabel("t [h]")
    a2.grid(alpha=0.3)
    fig.tight_layout()
    return fig, drift


def main(argv=None):
    """Command line (console script bolide-plot-impact); returns the exit status."""
    args = parse_args(sys.argv[1:] if argv is None else argv)
    import matplotlib
    matplotlib.use("Agg")

    try:
        snaps = load_snapshots(args.snapshots)
    except snapshot.SnapshotError as exc:
        common.die(str(exc))

    # ---- bound mass
    hist = bound_history(snaps, args.impactor_offset, args.G)
    print("# t[s] M_bound[kg] M_bound/M_total "
          + " ".join("M_b(mat %d)" % k for k in hist["materials"]))
    for i in range(len(snaps)):
        print("%.6e %.6e %.6f " % (hist["time"][i], hist["bound"][i], hist["fraction"][i])
              + " ".join("%.6e" % v for v in hist["per_material"][i]))
    common.write_figure(bound_figure(hist, snaps[0]["Masses"].sum()), args.prefix + "bound.png")

    # ---- collision pictures
    common.write_figure(collision_figure(snaps, args.length_unit, args.length_name),
                       args.prefix + "collision.png")

    # ---- energy budget
    if args.stats:
        try:
            st = snapshot.read_stats(args.stats, si=True)
        except snapshot.SnapshotError as exc:
            common.die(str(exc))
        fig, drift = energy_figure(st)
        common.write_figure(fig, args.prefix + "energy.png")
        t = st["time"]
        print("# energy: E_tot(0) = %.6e, E_tot(end) = %.6e, drift %.3e of max|E_pot| at t = %.4g s"
              % (st["E_tot"][0], st["E_tot"][-1], drift[-1], t[-1]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
