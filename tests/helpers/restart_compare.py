#!/usr/bin/env python3
"""Compare the outputs of two runs of Bolide (tests/program/test_restart_*.sh):
usage: restart_compare.py DIR_A DIR_B [--tol REL]

Every snapshot (*.hdf5) of either folder must exist in both, with the same
time and, particle by particle (matched by ParticleIDs), the same value of
every dataset of PartType0: bit for bit by default, within the relative
tolerance REL with --tol.  The statistics files (statistics.txt) must hold
the same data lines (comment lines, such as the one a resumed run adds, are
skipped); with --tol every column within REL of its scale
(tests/helpers/stats_compare.py, the box size from the snapshots' header).
Prints one line per difference; exit 1 if any."""
import glob
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from stats_compare import compare_stats  # noqa: E402


def snaps(d):
    return sorted(os.path.basename(f) for f in glob.glob(os.path.join(d, "*.hdf5")))


def main():
    args = sys.argv[1:]
    tol = 0.0
    if "--tol" in args:
        k = args.index("--tol")
        tol = float(args[k + 1])
        del args[k:k + 2]
    a, b = args
    bad = []
    worst = 0.0
    sa, sb = snaps(a), snaps(b)
    if sa != sb:
        bad.append("snapshot files differ: %s has %s, %s has %s" % (a, sa, b, sb))
    for name in sorted(set(sa) & set(sb)):
        try:
            fa, fb = h5py.File(os.path.join(a, name), "r"), h5py.File(os.path.join(b, name), "r")
        except OSError as err:
            bad.append("%s: unreadable (%s)" % (name, err))
            continue
        ta, tb = fa["Header"].attrs["Time"], fb["Header"].attrs["Time"]
        if not np.array_equal(ta, tb):
            bad.append("%s: time %r vs %r" % (name, ta, tb))
        ga, gb = fa["PartType0"], fb["PartType0"]
        if sorted(ga.keys()) != sorted(gb.keys()):
            bad.append("%s: datasets differ" % name)
            continue
        ia, ib = np.argsort(ga["ParticleIDs"][:], kind="stable"), np.argsort(gb["ParticleIDs"][:], kind="stable")
        if len(ia) != len(ib):
            bad.append("%s: %d vs %d particles" % (name, len(ia), len(ib)))
            continue
        for k in sorted(ga.keys()):
            x, y = ga[k][:][ia], gb[k][:][ib]
            if tol == 0.0:
                same = np.array_equal(x.view(np.uint8) if x.dtype.kind == "f" else x,
                                      y.view(np.uint8) if y.dtype.kind == "f" else y)
                if not same:
                    d = np.abs(x.astype(float) - y.astype(float)).max()
                    bad.append("%s: %s differs (max abs difference %.3g)" % (name, k, d))
            else:
                scale = max(np.abs(x.astype(float)).max(), 1e-300)
                d = np.abs(x.astype(float) - y.astype(float)).max() / scale
                worst = max(worst, d)
                if not d <= tol:
                    bad.append("%s: %s differs by %.3g relative" % (name, k, d))
    def lines(d):
        path = os.path.join(d, "statistics.txt")
        if not os.path.exists(path):
            return None
        with open(path) as f:
            return [l for l in f if not l.startswith("#")]
    la, lb = lines(a), lines(b)
    if tol > 0.0 and la is not None and lb is not None:
        box = 0.0
        for name in sa:
            with h5py.File(os.path.join(a, name), "r") as f:
                box = max(box, float(np.max(f["Header"].attrs["BoxSize"])))
        box = box if box > 0.0 else 1.0
        diff = compare_stats(os.path.join(a, "statistics.txt"), os.path.join(b, "statistics.txt"),
                             tol, box)
        if diff:
            bad.append(diff)
    elif la != lb:
        if la is None or lb is None:
            bad.append("statistics.txt missing in one folder")
        else:
            n = next((i for i, (x, y) in enumerate(zip(la, lb)) if x != y), min(len(la), len(lb)))
            bad.append("statistics differ: %d vs %d lines, first difference at data line %d" % (len(la), len(lb), n + 1))
    for line in bad:
        print("DIFF " + line)
    if not bad:
        print("same: %d snapshots%s, statistics %d lines" % (len(sa), " (bit for bit)" if tol == 0 else " (within %g, largest difference %.2e)" % (tol, worst), len(la or [])))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
