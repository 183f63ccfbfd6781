#!/usr/bin/env python3
"""Draw the task timeline of one scheduler run as a PNG.

Input: the file written by scheduler_dump_tasks(): one line per task,
"thread start end type subtype cell" (times in seconds from the start of the
run; lines starting with # are comments).  One row per thread, one bar per
task, one colour per type/subtype pair.  The names come from the file, so
this script never keeps its own copy of the task list.
"""
import argparse
import os
import sys

import numpy as np

from bolide import common


def read_dump(path):
    """Return (thread, start, end, kind) arrays; kind is "type/subtype"."""
    thread, start, end, kind = [], [], [], []
    with open(path) as f:
        for lineno, line in enumerate(f, 1):
            if not line.strip() or line.startswith("#"):
                continue
            w = line.split()
            if len(w) < 5:
                sys.exit(f"plot_tasks.py: error: {path}:{lineno}: expected "
                         "'thread start end type subtype [cell]'")
            try:
                thread.append(int(w[0]))
                start.append(float(w[1]))
                end.append(float(w[2]))
            except ValueError:
                sys.exit(f"plot_tasks.py: error: {path}:{lineno}: bad number")
            kind.append(w[3] if w[4] == "none" else f"{w[3]}/{w[4]}")
    if not thread:
        sys.exit(f"plot_tasks.py: error: {path}: no tasks in the file")
    return np.array(thread), np.array(start), np.array(end), np.array(kind)


def timeline(path, ms=False, title=None):
    """The task timeline of the dump PATH as a matplotlib figure: one row
    per thread (with its busy fraction), one bar per task, one colour per
    type/subtype; ms: the time axis in milliseconds."""
    import matplotlib.pyplot as plt

    thread, start, end, kind = read_dump(path)
    scale, unit = (1e3, "ms") if ms else (1.0, "s")
    kinds = sorted(set(kind))
    cmap = plt.get_cmap("tab20" if len(kinds) > 10 else "tab10")
    colour = {k: cmap(i % cmap.N) for i, k in enumerate(kinds)}
    nthreads = int(thread.max()) + 1

    fig, ax = plt.subplots(figsize=(12, 1.0 + 0.4 * nthreads))
    for k in kinds:
        sel = kind == k
        bars = [(s * scale, max((e - s) * scale, 1e-12)) for s, e in zip(start[sel], end[sel])]
        for tid in np.unique(thread[sel]):
            rows = [b for b, t in zip(bars, thread[sel]) if t == tid]
            ax.broken_barh(rows, (tid - 0.4, 0.8), facecolors=colour[k], linewidth=0)
        ax.plot([], [], linewidth=8, color=colour[k], label=k)  # legend entry
    busy = np.bincount(thread, weights=end - start, minlength=nthreads)
    wall = end.max() - min(start.min(), 0.0)
    ax.set_yticks(range(nthreads))
    ax.set_yticklabels([f"{t} ({100 * busy[t] / wall:.0f}%)" for t in range(nthreads)])
    ax.set_ylim(-0.6, nthreads - 0.4)
    ax.invert_yaxis()
    ax.set_xlabel(f"time since the start of the run [{unit}]")
    ax.set_ylabel("thread (busy fraction)")
    ax.set_title(title or os.path.basename(path))
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small", frameon=False)
    fig.tight_layout()
    return fig


def main(argv=None):
    """Command line (console script bolide-plot-tasks); returns the exit status."""
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dump", help="task dump written by scheduler_dump_tasks()")
    ap.add_argument("-o", "--output", default=None,
                    help="PNG to write (default: the dump's name with .png)")
    ap.add_argument("--title", default=None, help="plot title (default: the file name)")
    ap.add_argument("--ms", action="store_true", help="time axis in milliseconds")
    args = ap.parse_args(argv)

    import matplotlib
    matplotlib.use("Agg")

    fig = timeline(args.dump, ms=args.ms, title=args.title)
    out = args.output or os.path.splitext(args.dump)[0] + ".png"
    common.write_figure(fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
