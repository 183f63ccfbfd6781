#!/usr/bin/env python3
"""bolide-ic import-mesh (issue 24 item 4): a graded mesh's nodes as a
graded particle body.

The test writes the nodes of a graded block: a fine cubic lattice of
spacing d (x < 0, 6 x 8 x 8 nodes) next to a coarse one of spacing 2 d
(x > 0, 4 x 4 x 4 nodes on every other line of the fine one), d = 1 mm,
the coarse first plane 1.5 d from the fine last one, node ids shuffled.  The same nodes go into
  - a node file with a volume column (d^3 and 8 d^3; comments, blank lines),
  - a keyword deck (*KEYWORD, *NODE in fixed columns, a second *NODE in
    free format, *ELEMENT_SOLID between them, '$' comments, *END), read
    with --scale 1e-3 (coordinates in mm) and volumes from the spacing.

Asserts:
  - node file: the total mass equals rho x the sum of the volumes (to
    round-off), every particle has m = rho V, rho, h = eta V^(1/3) and its
    node id; h is eta d on the fine side and eta 2 d on the coarse side;
  - keyword deck: the positions agree with the node file's (times 1e-3);
    h is eta d for every fine node and eta 2 d for every coarse node but
    those of the coarse plane next to the interface (nearest neighbour
    1.5 d there: h = 1.5 eta d), and the total mass is rho x the sum of
    s^3 over the nodes, s the nearest-neighbour distance;
  - the result passes `bolide --check` with a Materials section for its id;
  - bad inputs are refused with one error line naming the file (and the
    line where there is one), a non-zero exit and no output: a missing
    file, a NaN coordinate, a duplicate id, a deck without *NODE, a line
    with a volume among lines without, a negative volume, two nodes at the
    same place (volumes from the spacing)."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

build = os.environ.get("BOLIDE_BUILDDIR", ".")
ic = os.path.join(build, "bolide-ic")
bolide = os.path.join(build, "bolide")
RHO = 2700.0
D = 1.0  # mm in the deck, m in the node file
bad = 0


def check(cond, msg):
    global bad
    print(("ok   " if cond else "FAIL ") + msg)
    bad += not cond


def graded_nodes():
    fine = np.stack(np.meshgrid(-(np.arange(6) + 0.5) * D, (np.arange(8) - 3.5) * D,
                                (np.arange(8) - 3.5) * D, indexing="ij"), -1).reshape(-1, 3)
    # coarse y, z on every other fine line: -3.5 d, -1.5 d, 0.5 d, 2.5 d
    coarse = np.stack(np.meshgrid(D + np.arange(4) * 2 * D, (np.arange(4) * 2 - 3.5) * D,
                                  (np.arange(4) * 2 - 3.5) * D, indexing="ij"), -1).reshape(-1, 3)
    x = np.concatenate([fine, coarse])
    V = np.concatenate([np.full(len(fine), D**3), np.full(len(coarse), 8 * D**3)])
    rng = np.random.default_rng(3)
    ids = rng.permutation(len(x)) * 7 + 11
    return x, V, ids, len(fine)


def run(args, expect_ok=True):
    r = subprocess.run([ic] + args, capture_output=True, text=True)
    if expect_ok and r.returncode != 0:
        print(r.stdout + r.stderr)
    return r


def read(path):
    with h5py.File(path, "r") as f:
        g = f["PartType0"]
        return {k: g[k][...] for k in ("Coordinates", "Masses", "Densities", "SmoothingLengths",
                                       "ParticleIDs", "MaterialIDs", "Velocities")}


def eta_default():
    out = subprocess.run([ic, "import-mesh", "--help"], capture_output=True, text=True).stdout
    return float(out.split("SPH:resolution_eta's, ")[1].split(")")[0])


def main():
    x, V, ids, nfine = graded_nodes()
    n = len(x)
    eta = eta_default()
    with tempfile.TemporaryDirectory() as tmp:
        os.chdir(tmp)
        with open("graded.nodes", "w") as f:
            f.write("# graded block: id x y z volume (m, m^3)\n\n")
            for i in range(n):
                f.write("%d %.17g %.17g %.17g %.17g%s\n" % (ids[i], *x[i], V[i],
                                                          "  # fine" if i == 0 else ""))
        with open("graded.k", "w") as f:
            f.write("*KEYWORD\n*TITLE\ngraded block\n$ nodes in mm\n*NODE\n")
            f.write("$#   nid               x               y               z      tc      rc\n")
            half = n // 2
            for i in range(half):
                f.write("%8d%16.9e%16.9e%16.9e%8d%8d\n" % (ids[i], *x[i], 0, 0))
            f.write("*ELEMENT_SOLID\n       1       1       1       2       3       4"
                    "       5       6       7       8\n*NODE\n")
            for i in range(half, n):
                f.write("%d,%.17g,%.17g,%.17g\n" % (ids[i], *x[i]))
            f.write("*END\n")

        r = run(["import-mesh", "graded.nodes", "--rho", str(RHO), "--mat", "3", "-o", "nodes.hdf5"])
        check(r.returncode == 0, "node file imported: " + r.stdout.strip())
        if r.returncode == 0:
            p = read("nodes.hdf5")
            order = np.argsort(p["ParticleIDs"])
            ref = np.argsort(ids)
            m, h = p["Masses"][order], p["SmoothingLengths"][order]
            Vs = V[ref]
            check(abs(m.sum() - RHO * V.sum()) <= 1e-12 * RHO * V.sum(),
                  "node file: total mass %.10g = rho x sum V = %.10g" % (m.sum(), RHO * V.sum()))
            check(np.allclose(m, RHO * Vs, rtol=1e-14, atol=0), "node file: m = rho V per particle")
            check(np.allclose(h, eta * np.cbrt(Vs), rtol=1e-14, atol=0),
                  "node file: h = eta V^(1/3) (eta %g)" % eta)
            fine = Vs == D**3
            check(np.allclose(h[fine], eta * D) and np.allclose(h[~fine], 2 * eta * D),
                  "node file: h follows the grading (%g on %d fine, %g on %d coarse nodes)"
                  % (h[fine].mean(), fine.sum(), h[~fine].mean(), (~fine).sum()))
            check(np.all(p["Densities"] == RHO) and np.all(p["MaterialIDs"] == 3)
                  and np.all(p["Velocities"] == 0), "node file: rho, material 3, at rest")
            xs = p["Coordinates"][order]
            check(np.abs((xs - xs.mean(0)) - (x[ref] - x[ref].mean(0))).max() < 1e-12,
                  "node file: positions (shifted into the box)")
            with open("p.yml", "w") as f:
                f.write("InitialConditions:\n  file_name: nodes.hdf5\nTimeIntegration:\n"
                        "  time_end: 1e-6\nMaterials:\n  3: {name: granite}\n")
            c = subprocess.run([bolide, "--check", "p.yml"], capture_output=True, text=True)
            check(c.returncode == 0, "bolide --check accepts the import" +
                  ("" if c.returncode == 0 else ": " + c.stdout + c.stderr))

        r = run(["import-mesh", "graded.k", "--rho", str(RHO), "--scale", "1e-3", "-o", "deck.hdf5"])
        check(r.returncode == 0, "keyword deck imported: " + r.stdout.strip())
        if r.returncode == 0 and os.path.exists("nodes.hdf5"):
            p = read("deck.hdf5")
            q = read("nodes.hdf5")
            po, qo = np.argsort(p["ParticleIDs"]), np.argsort(q["ParticleIDs"])
            check(np.array_equal(p["ParticleIDs"][po], q["ParticleIDs"][qo]), "deck: the same node ids")
            xp, xq = p["Coordinates"][po], q["Coordinates"][qo]
            check(np.abs((xp - xp.mean(0)) - 1e-3 * (xq - xq.mean(0))).max() < 1e-12,
                  "deck: positions = node file's x 1e-3 (fixed columns and free format)")
            xr = x[np.argsort(ids)]
            # nearest-neighbour distance, brute force (in mm)
            d2 = ((xr[:, None, :] - xr[None, :, :]) ** 2).sum(-1)
            np.fill_diagonal(d2, np.inf)
            s = np.sqrt(d2.min(1)) * 1e-3
            h = p["SmoothingLengths"][po]
            m = p["Masses"][po]
            check(np.allclose(h, eta * s, rtol=1e-12, atol=0), "deck: h = eta x nearest-neighbour distance")
            fine = xr[:, 0] < 0
            iface = np.isclose(xr[:, 0], D)
            check(np.allclose(h[fine], eta * D * 1e-3, rtol=1e-12)
                  and np.allclose(h[~fine & ~iface], 2 * eta * D * 1e-3, rtol=1e-12)
                  and np.allclose(h[iface], 1.5 * eta * D * 1e-3, rtol=1e-12),
                  "deck: h follows the grading (fine %d: eta d, coarse %d: 2 eta d, interface "
                  "plane %d: 1.5 eta d)" % (fine.sum(), (~fine & ~iface).sum(), iface.sum()))
            check(abs(m.sum() - RHO * (s**3).sum()) <= 1e-12 * m.sum(),
                  "deck: total mass %.6g = rho x sum s^3 (node file's %.6g x 1e-9)"
                  % (m.sum(), q["Masses"].sum()))

        # bad inputs: one line naming the file (and line), non-zero exit, no output
        lines = open("graded.nodes").read().splitlines(True)
        first = next(k for k, l in enumerate(lines) if l.strip() and not l.startswith("#"))
        def variant(name, k, new):
            v = list(lines)
            v[k] = new
            open(name, "w").writelines(v)
            return name
        nan = variant("nan.nodes", first + 4, "%d nan 0 0 1\n" % (ids[4],))
        dup = variant("dup.nodes", first + 9, "%d 100 0 0 1\n" % ids[2])
        mixed = variant("mixed.nodes", first + 5, "%d %.17g %.17g %.17g\n" % (ids[5], *x[5]))
        neg = variant("neg.nodes", first + 6, "%d %.17g %.17g %.17g -1\n" % (ids[6], *x[6]))
        with open("same.nodes", "w") as f:
            f.write("1 0 0 0\n2 1 0 0\n3 0 0 0\n")
        with open("nonode.k", "w") as f:
            f.write("*KEYWORD\n*ELEMENT_SOLID\n1 1 1 2 3 4 5 6 7 8\n*END\n")
        cases = [
            ("missing file", ["missing.nodes"], "missing.nodes: cannot open"),
            ("NaN coordinate", [nan], "%s:%d: column 2 is not finite" % (nan, first + 5)),
            ("duplicate id", [dup], "%s:%d: duplicate node id %d (first on line %d)"
             % (dup, first + 10, ids[2], first + 3)),
            ("no *NODE section", ["nonode.k"], "nonode.k: no *NODE section"),
            ("mixed volume columns", [mixed], "%s:%d: 4 columns, but line %d has 5" % (mixed, first + 6, first + 1)),
            ("negative volume", [neg], "%s:%d: volume -1 must be positive" % (neg, first + 7)),
            ("coincident nodes", ["same.nodes"], "same.nodes:3: node 3 at the same position as node 1 (line 1)"),
        ]
        for what, args, msg in cases:
            r = run(["import-mesh"] + args + ["--rho", "1", "-o", "bad.hdf5"], expect_ok=False)
            err = r.stderr.strip().splitlines()
            ok = (r.returncode != 0 and len(err) == 1 and msg in err[0]
                  and not os.path.exists("bad.hdf5"))
            check(ok, "refused, %s: %s" % (what, " | ".join(err) if err else "(no message), exit %d"
                                         % r.returncode))
        r = run(["import-mesh", "graded.nodes", "-o", "bad.hdf5"], expect_ok=False)
        check(r.returncode != 0 and "--rho" in r.stderr and not os.path.exists("bad.hdf5"),
              "refused without --rho: " + r.stderr.strip())
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
