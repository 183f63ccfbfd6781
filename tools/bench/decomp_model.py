#!/usr/bin/env python3
"""
Strong scaling on paper (issue 22 item 7, theory/mpi.md "Scaling on paper"):
the step time of a run over P ranks, estimated from the partitions that
`bolide --partition P --partition-counts FILE --partition-method metis`
printed (one output file per rank count, with its per-rank table), the
measured per-particle step costs and a network model.

Per rank r (n_r particles' worth of work: its share of the estimated cost
times N):
  compute_r = a + b n_r            (a, b: the step cost measured at 1e5 and 1e6
                                    particles on one node, BENCHMARKS.md)
  comm_r    = sum over exchange phases of
                (layer_r * bytes_phase / bandwidth + peers_r * latency)
            + allgather of the top-level multipoles of the other ranks'
              cells ((C - C_r) * multipole_bytes / bandwidth + log2(P) latency)
            + reductions (time step, statistics: log2(P) latency each)
  step      = max_r compute_r + max_r comm_r  (every phase waits for its data)
  overlap   = max(max_r compute_r, max_r comm_r) (communication hidden)
layer_r: particles of other ranks' cells within the kernel support of one of
r's cells (received once per step per phase); with --whole-cells the halo of
whole cells instead (what proxies of whole cells, theory/mpi.md item 2, would
send).

Usage: decomp_model.py DIR [--bandwidth GBIT] [--latency US] [--cost NAME:a,b]
       [--phases name:bytes,...] [--multipole-bytes B] [--plot OUT.png]
DIR holds ranks_P.txt files (tools/bench/decomp.sh -a writes them).
"""
import argparse
import glob
import math
import os
import re
import sys

# the measured step costs (BENCHMARKS.md): s/step = a + b N on one node
COSTS = {
    # planetary reference impact, hydro + self-gravity, --no-gpu -t 16, H200 host
    # (16 Xeon cores): 0.218 s at 99,999, 1.742 s at 999,999 ("Thread scaling on
    # 16 cores", third lease)
    "cpu16": (0.218, 99999, 1.742, 999999),
    # the same problem GPU-only on one H200 (Scheduler:gpu:all): 0.0399 s at
    # 99,999, 0.2953 s at 999,999 ("Self-gravity entirely on the GPU")
    "h200": (0.0399, 99999, 0.2953, 999999),
}


def affine(t1, n1, t2, n2):
    b = (t2 - t1) / (n2 - n1)
    return t1 - b * n1, b


def read_ranks(path):
    """The summary and the per-rank table of one bolide --partition-counts output."""
    info, rows = {}, []
    for line in open(path):
        if line.startswith("partition: method"):
            w = line.split()
            for k in ("ranks", "imbalance", "cut_fraction", "halo_mean", "halo_max"):
                info[k] = float(w[w.index(k) + 1])
        elif line.startswith("exchange:"):
            w = line.split()
            for k in ("particles_max", "layer_mean", "layer_max", "sent_max", "peers_mean",
                      "peers_max", "multipoles"):
                info[k] = float(w[w.index(k) + 1])
        elif line.startswith("partition:") and "particles in" in line:
            info["N"] = float(line.split()[1])
        elif re.match(r"^\s+\d+\s", line):
            r, cells, parts, cost, halo, layer, sent, peers = line.split()
            rows.append(dict(cells=int(cells), parts=int(parts), cost=float(cost),
                             halo=float(halo), layer=float(layer), sent=float(sent),
                             peers=int(peers)))
    if "N" not in info or len(rows) != int(info["ranks"]):
        sys.exit(f"decomp_model: {path} is not a --partition-counts output with its per-rank table")
    return info, rows


def model(info, rows, a, b, o):
    P = int(info["ranks"])
    N = info["N"]
    C = info["multipoles"]
    bw = o.bandwidth * 1e9 / 8.0  # bytes / s
    lat = o.latency * 1e-6
    per_part = sum(o.phase_bytes.values())
    comp = max(a + b * r["cost"] * N / P for r in rows)
    lg = math.log2(P) if P > 1 else 0.0
    comm, bytes_max, halo_t, mp_t = 0.0, 0.0, 0.0, 0.0
    # multipoles: every rank receives those of the other ranks' cells
    for r in rows:
        halo = r["halo"] if o.whole_cells else r["layer"]
        by = halo * per_part + (C - r["cells"]) * o.multipole_bytes
        t = (halo * per_part / bw + len(o.phase_bytes) * r["peers"] * lat
             + (C - r["cells"]) * o.multipole_bytes / bw + lg * lat
             + o.reductions * lg * lat)
        comm = max(comm, t)
        bytes_max = max(bytes_max, by)
        halo_t = max(halo_t, halo * per_part / bw + len(o.phase_bytes) * r["peers"] * lat)
        mp_t = max(mp_t, (C - r["cells"]) * o.multipole_bytes / bw + lg * lat)
    o.parts[P] = (halo_t, mp_t)
    return comp, comm, bytes_max


def parse_phases(s):
    out = {}
    for item in s.split(","):
        k, v = item.split(":")
        out[k] = float(v)
    return out


def main():
    ap = argparse.ArgumentParser(description="strong scaling on paper from bolide's partitions")
    ap.add_argument("dir")
    ap.add_argument("--bandwidth", type=float, default=100.0, help="Gbit/s per rank (100: HDR/EDR IB)")
    ap.add_argument("--latency", type=float, default=2.0, help="microseconds per message")
    ap.add_argument("--phases", default="xv:72,rho:64",
                    help="bytes per halo particle per exchange phase (hydro: x, predicted v, m, "
                         "h as doubles, flags, material after the drift: 72; h, rho, P, cs, "
                         "balsara, f_gradh, alpha, u after the ghost: 64); solids add e.g. "
                         "gradient:160 (stress, artificial stress, correction tensor, damage)")
    ap.add_argument("--multipole-bytes", type=float, default=528.0,
                    help="bytes of one top-level multipole (order 5: 56 moments, centre, "
                         "r_max, 6 powers: 66 doubles)")
    ap.add_argument("--reductions", type=int, default=2, help="allreduces per step (dt, statistics)")
    ap.add_argument("--cost", action="append", default=[],
                    help="NAME:a,b step cost a + b n per rank (default: cpu16 and h200 of BENCHMARKS.md)")
    ap.add_argument("--whole-cells", action="store_true",
                    help="exchange whole foreign cells (the halo), not the ghost layer")
    ap.add_argument("--plot", help="write the step time against ranks here (PNG)")
    o = ap.parse_args()
    o.phase_bytes = parse_phases(o.phases)
    o.parts = {}
    costs = {}
    for c in o.cost:
        name, ab = c.split(":")
        a, b = map(float, ab.split(","))
        costs[name] = (a, b)
    if not costs:
        costs = {k: affine(*v) for k, v in COSTS.items()}
    files = sorted(glob.glob(os.path.join(o.dir, "ranks_*.txt")),
                   key=lambda f: int(re.findall(r"ranks_(\d+)", f)[0]))
    if not files:
        sys.exit(f"decomp_model: no ranks_*.txt in {o.dir}")
    data = [read_ranks(f) for f in files]
    N = data[0][0]["N"]
    print(f"# N = {N:.4g} particles, {int(data[0][0]['multipoles'])} non-empty top-level cells; "
          f"network {o.bandwidth:g} Gbit/s, {o.latency:g} us; "
          f"{sum(o.phase_bytes.values()):g} B per halo particle per step "
          f"({', '.join(f'{k} {v:g}' for k, v in o.phase_bytes.items())}), "
          f"multipoles {o.multipole_bytes:g} B; exchange of "
          f"{'whole foreign cells' if o.whole_cells else 'the ghost layer'}")
    for name, (a, b) in costs.items():
        print(f"# cost {name}: {a:.4g} s + {b:.4g} s per particle per step "
              f"(one rank, all N: {a + b * N:.4g} s)")
    hdr = ("| ranks | imbalance | particles/rank (max) | layer mean / max | halo (whole cells) "
           "mean / max | peers max | MB received per step (max) |")
    cols = " | ".join(f"{n}: compute / comm / step s, comm share" for n in costs)
    print(hdr + " " + cols + " |")
    print("|" + "---|" * (7 + len(costs)))
    curves = {n: [] for n in costs}
    cross = {n: None for n in costs}
    for info, rows in data:
        P = int(info["ranks"])
        cells = []
        for n, (a, b) in costs.items():
            comp, comm, by = model(info, rows, a, b, o)
            curves[n].append((P, comp, comm))
            if comm > comp and cross[n] is None:
                cross[n] = P
            cells.append(f"{comp:.4g} / {comm:.3g} / {comp + comm:.4g}, {comm / (comp + comm):.0%}")
        print(f"| {P} | {info['imbalance']:.3f} | {info['particles_max']:,.0f} | "
              f"{info['layer_mean']:,.0f} / {info['layer_max']:,.0f} | "
              f"{info['halo_mean']:,.0f} / {info['halo_max']:,.0f} | {info['peers_max']:.0f} | "
              f"{by / 1e6:.2f} | " + " | ".join(cells) + " |")
    imb = data[-1][0]["imbalance"]
    for n, (a, b) in costs.items():
        t1 = a + b * N
        P, comp, comm = curves[n][-1]
        if cross[n]:
            where = f"from {cross[n]} ranks"
        elif comm > a:
            # beyond the last rank count: compute a + b imb N / P against the
            # last communication time (its multipole part does not shrink)
            where = f"beyond {P} ranks (extrapolated: about {b * imb * N / (comm - a):,.0f})"
        else:
            where = f"never (compute's fixed part {a:.3g} s exceeds the communication {comm:.3g} s)"
        print(f"# {n}: communication exceeds compute {where}; "
              f"speed-up at {P} ranks {t1 / (comp + comm):.0f} "
              f"(efficiency {t1 / (comp + comm) / P:.2f}; with full overlap "
              f"{t1 / max(comp, comm) / P:.2f})")
    if o.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 5))
        colours = ["C0", "C3", "C2", "C1"]
        for (n, cv), col in zip(curves.items(), colours):
            P = [c[0] for c in cv]
            ax.loglog(P, [c[1] + c[2] for c in cv], "-o", color=col, label=f"{n}: step")
            ax.loglog(P, [c[1] for c in cv], "--", color=col, label=f"{n}: compute")
            a, b = costs[n]
            ax.loglog(P, [(a + b * N) / p for p in P], "-", color=col, lw=0.5, alpha=0.5,
                      label=f"{n}: ideal (one rank's time / ranks)")
        P = sorted(o.parts)
        cv = next(iter(curves.values()))
        ax.loglog(P, [c[2] for c in cv], ":", color="k", label="communication (the same for both)")
        ax.loglog(P, [o.parts[p][0] for p in P], ":", color="0.5", lw=1,
                  label="  of which the halo exchanges")
        ax.loglog(P, [o.parts[p][1] for p in P], "-.", color="0.5", lw=1,
                  label="  of which the top-level multipoles")
        ax.set_xlabel("ranks")
        ax.set_ylabel("s per step")
        ax.set_title(f"{N:.3g} particles, {o.bandwidth:g} Gbit/s, {o.latency:g} us "
                     f"({'whole cells' if o.whole_cells else 'ghost layer'})", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(o.plot, dpi=120)
        print(f"# wrote {o.plot}")


if __name__ == "__main__":
    main()
