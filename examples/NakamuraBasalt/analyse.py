#!/usr/bin/env python3
"""Fragments and intact core of NakamuraBasalt runs.

For every snapshot of each run folder: bolide-fof with the fully damaged
particles left out (--min-damage-drop 1, linking length 1 x the median h),
the basalt mass of each fragment (mass x frac_mat103), and the intact-core
fraction: the largest fragment's basalt mass over the target's mass in the
first snapshot.  Writes RUN/fragments_XXXX.txt, RUN/core.txt (time, core
fraction, fragments) and RUN/spectrum.png (cumulative fragment mass
spectrum of the last snapshot); with several runs also core_resolution.png
(core fraction against the number of target particles) here.

Usage: analyse.py RUN [RUN ...]     (BOLIDE_BUILD: the build folder)
"""
import glob
import os
import subprocess
import sys

import numpy as np

sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from bolide import snapshot  # noqa: E402  (python/bolide, unless the package is installed)

BASALT = 103          # material id of the target (bolide-ic: the library's swift_id)
EXPERIMENT = 0.31     # intact core of Nakamura & Fujiwara (1991)


def fof(snap, build):
    """Run bolide-fof on snap; returns (column dict, table path)."""
    out = snap.replace("nakamura_", "fragments_").replace(".hdf5", ".txt")
    subprocess.run([os.path.join(build, "bolide-fof"), snap, "--min-damage-drop", "1",
                    "--link-h", "1", "-o", out], check=True, stdout=subprocess.DEVNULL)
    return snapshot.read_fragments(out)[0], out


def analyse(run, build):
    snaps = sorted(glob.glob(os.path.join(run, "nakamura_[0-9]*.hdf5")))
    if not snaps:
        sys.exit("%s: no snapshots" % run)
    first = snapshot.load(snaps[0], ["MaterialIDs", "Masses"], si=True)
    mat = first["MaterialIDs"]
    m_target = first["Masses"][mat == BASALT].sum()
    n_target = int((mat == BASALT).sum())
    rows = []
    for s in snaps:
        snap = snapshot.load(s, ["Damage", "MaterialIDs"], si=True)
        t = snapshot.snapshot_time(snap)
        d = snap["Damage"][snap["MaterialIDs"] == BASALT]
        cols, _ = fof(s, build)
        basalt = cols["mass"] * cols.get("frac_mat%d" % BASALT, np.ones_like(cols["mass"]))
        core = basalt.max() / m_target if basalt.size else 0.0
        rows.append((t, core, int((basalt > 0).sum()), float(np.mean(d >= 1.0))))
    with open(os.path.join(run, "core.txt"), "w") as f:
        f.write("# NakamuraBasalt %s: %d target particles, target mass %.6g kg\n" % (run, n_target, m_target))
        f.write("# time[s] core_fraction fragments fully_damaged_fraction\n")
        for r in rows:
            f.write("%.6e %.6f %d %.6f\n" % r)
    print("%s: %d target particles" % (run, n_target))
    for t, c, k, fd in rows:
        print("  t = %5.1f us: intact core %5.1f%% of the target, %4d fragments, %5.1f%% of the particles fully damaged"
              % (t * 1e6, 100 * c, k, 100 * fd))
    # cumulative spectrum of the last snapshot (basalt fragments, not fully damaged particles)
    cols, _ = fof(snaps[-1], build)
    basalt = np.sort(cols["mass"] * cols.get("frac_mat%d" % BASALT, 1.0))[::-1]
    basalt = basalt[basalt > 0] / m_target
    return n_target, rows[-1][0], rows[-1][1], basalt


def main():
    build = os.environ.get("BOLIDE_BUILD", "../../_build")
    runs = sys.argv[1:] or sorted(glob.glob("run_*"))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    results = []
    for run in runs:
        n, t, core, spec = analyse(run, build)
        results.append((n, t, core, spec, run))
        fig, ax = plt.subplots(figsize=(6, 4.5))
        ax.step(spec, np.arange(1, spec.size + 1), where="post",
                label="Bolide, %d particles, t = %.0f us (core %.1f%%)" % (n, t * 1e6, 100 * core))
        ax.axvline(EXPERIMENT, color="k", ls="--", lw=1, label="intact core, experiment (31%)")
        ax.set_xscale("log"), ax.set_yscale("log")
        ax.set_xlabel(r"fragment mass / target mass")
        ax.set_ylabel(r"cumulative number $N(\geq m)$")
        ax.set_title("Nakamura basalt: fragments of not fully damaged particles", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(run, "spectrum.png"), dpi=120)
        plt.close(fig)
    if len(results) > 1:
        results.sort()
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.5))
        for n, t, core, spec, run in results:
            a1.step(spec, np.arange(1, spec.size + 1), where="post", label="%d particles" % n)
        a1.axvline(EXPERIMENT, color="k", ls="--", lw=1, label="experiment core 31%")
        a1.set_xscale("log"), a1.set_yscale("log")
        a1.set_xlabel("fragment mass / target mass"), a1.set_ylabel(r"$N(\geq m)$")
        a1.grid(True, which="both", alpha=0.3), a1.legend(fontsize=8)
        ns = [r[0] for r in results]
        a2.semilogx(ns, [100 * r[2] for r in results], "o-", label="Bolide (t = %.0f us)" % (1e6 * results[0][1]))
        a2.axhline(31, color="k", ls="--", lw=1, label="experiment (Nakamura & Fujiwara 1991)")
        a2.plot([5.2e5], [31], "s", color="C3", label="Schaefer et al. 2016 (miluphcuda)")
        a2.plot([1.4e4], [8.8], "^", color="C2", label="SWIFT strength branch")
        a2.set_xlabel("target particles"), a2.set_ylabel("intact core [% of target mass]")
        a2.set_ylim(0, 40), a2.grid(True, alpha=0.3), a2.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig("core_resolution.png", dpi=120)
        print("core against resolution: core_resolution.png")
        for n, t, core, spec, run in results:
            print("  %8d particles: core %.1f%% at t = %.0f us" % (n, 100 * core, 1e6 * t))


if __name__ == "__main__":
    main()
