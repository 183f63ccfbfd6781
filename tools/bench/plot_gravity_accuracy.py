#!/usr/bin/env python3
"""Gravity's error against its cost from tools/bench/gravity_accuracy.sh.

    plot_gravity_accuracy.py OUTDIR/acc_*.txt [-o acc.png] [--eval 2]

Two panels: median and 99th-percentile relative acceleration error against
the time of one evaluation, one line per table (size, mode), theta and order,
points labelled with epsilon_fmm; the first evaluation hollow, the later
one(s) filled; SWIFT's figures on the reference impact (median 3.3e-5, p99
1.7e-4) as horizontal lines.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SWIFT = {"median": 3.3e-5, "p99": 1.7e-4}


def read(path):
    rows = []
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        w = line.split()
        rows.append({"mode": w[0], "eps": float(w[1]), "theta": float(w[2]), "order": int(w[3]),
                     "eval": int(w[4]), "median": float(w[5]), "p90": float(w[6]),
                     "p99": float(w[7]), "max": float(w[8]), "t": float(w[9])})
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("tables", nargs="+")
    ap.add_argument("-o", "--output", default="gravity_accuracy.png")
    a = ap.parse_args(argv)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharex=True)
    for path in a.tables:
        rows = read(path)
        tag = os.path.basename(path).replace("acc_", "").replace(".txt", "")
        keys = sorted({(r["theta"], r["order"]) for r in rows})
        for theta, order in keys:
            for ev, fill in ((1, "none"), (2, None)):
                sel = [r for r in rows if r["theta"] == theta and r["order"] == order
                       and r["eval"] == ev]
                if not sel:
                    continue
                sel.sort(key=lambda r: -r["eps"] if r["eps"] > 0 else -1e9)  # geometric first, then falling eps
                for ax, q in zip(axes, ("median", "p99")):
                    line, = ax.plot([r["t"] for r in sel], [r[q] for r in sel], "o-" if ev == 2 else "o--",
                                    mfc=fill, label=f"{tag} theta {theta} p {order} eval {ev}")
                    if ev == 2:
                        for r in sel:
                            ax.annotate(f"{r['eps']:g}", (r["t"], r[q]), fontsize=7,
                                        textcoords="offset points", xytext=(3, 3))
    for ax, q in zip(axes, ("median", "p99")):
        ax.axhline(SWIFT[q], color="k", ls=":", label=f"SWIFT {q} {SWIFT[q]:g}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("gravity time per evaluation [s]")
        ax.set_ylabel(f"{q} |da|/|a|")
        ax.grid(alpha=0.3, which="both")
    axes[1].legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)
    print("wrote", a.output)


if __name__ == "__main__":
    sys.exit(main())
