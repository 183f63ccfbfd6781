#!/usr/bin/env python3
"""Colliding rubber rings through bolide (Gray, Monaghan & Swift 2001;
theory/validation.md "Colliding rubber rings"; examples/RubberRings): plane strain
(rings 8 layers tall in a box periodic in z), dx = 2.5 mm, 5696 particles,
the example's own initial conditions and parameter files.

Asserts what theory/validation.md asks for:
  - without artificial stress the rings are whole before maximum compression
    (1 + 1 pieces at 0.5 ms) and broken after it (at 1.5 ms each ring in at
    least 3 friends-of-friends pieces of 10 or more particles, the largest
    under 80% of the ring; measured 4 + 4, largest 39%);
  - with artificial stress (eps_s = 0.2, n = 4) they bounce whole: 1 + 1
    pieces at 2 ms and the left ring moving back at more than half its
    approach speed (measured -35.5 m/s against +50.3 m/s).
A slow test: two runs of about 2000 steps (several minutes on 2 cores)."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

src = os.environ.get("BOLIDE_SRCDIR", os.path.join(os.path.dirname(__file__), "..", ".."))
build = os.environ.get("BOLIDE_BUILDDIR", ".")
bolide = os.path.join(build, "bolide")
example = os.path.join(src, "examples", "RubberRings")
DX = 0.0025
V0 = 0.059 * 852.0  # each ring's approach speed (examples/RubberRings/make_ic.py)


def pieces(pos):
    """Friends-of-friends groups (linking length 1.5 dx) of >= 10 particles
    and the largest group's fraction of the particles."""
    pairs = cKDTree(pos).query_pairs(1.5 * DX, output_type="ndarray")
    n = len(pos)
    g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, lab = connected_components(g, directed=False)
    sizes = np.bincount(lab)
    return int(np.sum(sizes >= 10)), sizes.max() / n


def state(path):
    with h5py.File(path, "r") as f:
        p = f["PartType0"]
        o = np.argsort(p["ParticleIDs"][:])
        x, v = p["Coordinates"][:][o], p["Velocities"][:][o]
    n1 = len(x) // 2
    pl, fl = pieces(x[:n1])
    pr, fr = pieces(x[n1:])
    return pl, pr, max(fl, fr), v[:n1, 0].mean()


def run(d, params, t_end, sub):
    cmd = [bolide, "-t", "2", "-P", f"InitialConditions:file_name:{d}/rings.hdf5", "-P", f"Snapshots:subdir:{sub}",
           "-P", f"TimeIntegration:time_end:{t_end}", "-P", "Snapshots:delta_time:5e-4",
           "-P", "Statistics:delta_time:1e-3", os.path.join(example, params)]
    r = subprocess.run(cmd, cwd=d, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-2000:])
        sys.exit(1)


def main():
    # The tensile instability that breaks the rings without artificial stress
    # is the cubic spline's: with Wendland C2 at eta 1.7 (the default kernel)
    # the rings stay whole at 1.5 ms (measured 1 + 1 pieces on 12 layers), so
    # this case runs in the cubic-spline build (tools/test_cubic_build.sh, CI)
    ver = subprocess.run([bolide, "--version"], capture_output=True, text=True).stdout
    if "kernel: cubic-spline" not in ver:
        print("skip: the rubber rings' fracture is asserted with the cubic spline (tools/test_cubic_build.sh)")
        return 77
    with tempfile.TemporaryDirectory() as d:
        subprocess.run([sys.executable, os.path.join(example, "make_ic.py"), "--dx", str(DX), "--thickness", "0.02",
                        "--periodic-z", "-o", os.path.join(d, "rings.hdf5")], check=True, capture_output=True)
        run(d, "params_no_as.yml", 1.6e-3, "no_as")
        run(d, "params.yml", 2.1e-3, "with_as")
        a_l, a_r, _, _ = state(os.path.join(d, "no_as", "rings_0001.hdf5"))
        b_l, b_r, b_big, _ = state(os.path.join(d, "no_as", "rings_0003.hdf5"))
        c_l, c_r, c_big, c_vx = state(os.path.join(d, "with_as", "rings_0004.hdf5"))
    v0 = V0
    print("colliding rubber rings, plane strain, dx = 2.5 mm:")
    checks = [
        ("no artificial stress, 0.5 ms: pieces L+R = 1+1", f"{a_l}+{a_r}", a_l == 1 and a_r == 1),
        ("no artificial stress, 1.5 ms: pieces L+R >= 3+3", f"{b_l}+{b_r}", b_l >= 3 and b_r >= 3),
        ("no artificial stress, 1.5 ms: largest piece < 0.8 of a ring", f"{b_big:.3f}", b_big < 0.8),
        ("artificial stress, 2.0 ms: pieces L+R = 1+1", f"{c_l}+{c_r}", c_l == 1 and c_r == 1),
        ("artificial stress, 2.0 ms: left ring vx < -0.5 x approach speed", f"{c_vx:.2f} m/s (approach {v0:.2f})",
         c_vx < -0.5 * v0),
    ]
    ok = True
    for what, val, good in checks:
        print(f"  {what:62s} {val:>26s} {'ok' if good else 'FAIL'}")
        ok = ok and good
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
