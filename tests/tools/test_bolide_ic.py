"""bolide-ic: the lattices, the Sod and Sedov set-ups and the command-line
contract, checked from the files with h5py and scipy."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np
from scipy.spatial import cKDTree

build = os.environ["BOLIDE_BUILDDIR"]
exe = os.path.join(build, "bolide-ic")
failures = []


def check(cond, msg):
    if not cond:
        failures.append(msg)
        print("FAIL", msg)


def make(tmp, name, *args):
    path = os.path.join(tmp, name + ".hdf5")
    subprocess.run([exe, *args, "-o", path], check=True, stdout=subprocess.DEVNULL)
    with h5py.File(path, "r") as f:
        g = f["PartType0"]
        d = {k: g[k][:] for k in g}
        d["box"] = f["Header"].attrs["BoxSize"]
        d["periodic"] = f["RuntimePars"].attrs["PeriodicBoundariesOn"][0]
    return d


def neighbour_distances(d, k):
    tree = cKDTree(d["Coordinates"], boxsize=d["box"] if d["periodic"] else None)
    dist, _ = tree.query(d["Coordinates"], k + 1)
    return dist[:, 1:]


with tempfile.TemporaryDirectory() as tmp:
    # cubic lattice: 6 neighbours at the spacing, masses rho V / N, h = eta dx
    d = make(tmp, "cubic", "box", "--n", "8", "--size", "2", "--rho", "3", "--periodic",
             "--eta", "1.2348")
    x = d["Coordinates"]
    check(len(x) == 512, f"cubic count {len(x)}")
    check(np.all((x >= 0) & (x < 2)), "cubic: particle outside the box")
    nd = neighbour_distances(d, 7)
    check(np.allclose(nd[:, :6], 0.25, rtol=1e-12) and np.all(nd[:, 6] > 0.3),
          "cubic: not 6 neighbours at the spacing")
    check(np.isclose(d["Masses"].sum(), 3 * 8, rtol=1e-12), "cubic: total mass != rho V")
    check(np.allclose(d["SmoothingLengths"], 1.2348 * 0.25, rtol=1e-12), "cubic: h")
    check(np.allclose(d["Densities"], 3) and np.allclose(d["InternalEnergies"], 1), "cubic: rho, u")
    check(np.array_equal(np.sort(d["ParticleIDs"]), np.arange(1, 513)), "cubic: ids")
    check(np.all(d["Velocities"] == 0), "cubic: velocities")

    # close-packed lattices: 12 neighbours at one distance
    d = make(tmp, "fcc", "box", "--n", "4", "--lattice", "fcc", "--periodic", "--mat", "7")
    check(len(d["Masses"]) == 256, "fcc count")
    nd = neighbour_distances(d, 13)
    a = 0.25 / np.sqrt(2)
    check(np.allclose(nd[:, :12], a, rtol=1e-12) and np.all(nd[:, 12] > 1.3 * a),
          "fcc: not 12 neighbours at a/sqrt(2)")
    check(np.all(d["MaterialIDs"] == 7), "fcc: --mat")
    # hcp in a box of the ideal shape: rows a sqrt(3)/2 and layers a sqrt(2/3) apart
    a = 1 / 12
    size = f"1,{float(12 * a * np.sqrt(3) / 2)!r},{float(12 * a * np.sqrt(2 / 3))!r}"
    d = make(tmp, "hcp", "box", "--n", "12", "--lattice", "hcp", "--periodic", "--size", size)
    check(len(d["Masses"]) == 12**3, f"hcp count {len(d['Masses'])}")
    nd = neighbour_distances(d, 13)
    check(np.allclose(nd[:, :12], a, rtol=1e-9) and np.all(nd[:, 12] > 1.3 * a),
          "hcp: not 12 neighbours at the spacing")
    check(np.isclose(d["Masses"].sum(), np.prod(d["box"]), rtol=1e-12), "hcp: total mass")

    # perturbation: bounded by FRAC x spacing, reproducible with the seed
    base = make(tmp, "p0", "box", "--n", "8", "--periodic")
    p1 = make(tmp, "p1", "box", "--n", "8", "--periodic", "--perturb", "0.2", "--seed", "5")
    p2 = make(tmp, "p2", "box", "--n", "8", "--periodic", "--perturb", "0.2", "--seed", "5")
    p3 = make(tmp, "p3", "box", "--n", "8", "--periodic", "--perturb", "0.2", "--seed", "6")
    dx = p1["Coordinates"] - base["Coordinates"]
    dx -= np.round(dx)  # periodic wrap, box 1
    check(np.all(np.abs(dx) <= 0.2 / 8 + 1e-15), "perturbation larger than FRAC x spacing")
    check(np.abs(dx).max() > 0.15 / 8, "perturbation much smaller than asked")
    check(np.array_equal(p1["Coordinates"], p2["Coordinates"]), "same seed, different positions")
    check(not np.array_equal(p1["Coordinates"], p3["Coordinates"]), "seed has no effect")

    # Sod: equal masses, 8 x as many particles on the left, the two states
    d = make(tmp, "sod", "sod", "--nx", "16")
    x, m = d["Coordinates"][:, 0], d["Masses"]
    left = x < 0.5
    check(left.sum() == 8 * (~left).sum(), f"sod: {left.sum()} left, {(~left).sum()} right")
    check(np.all(m == m[0]), "sod: masses differ")
    vol = 0.5 * 0.125 * 0.125
    check(np.isclose(m[left].sum() / vol, 1, rtol=1e-12), "sod: left density from masses")
    check(np.isclose(m[~left].sum() / vol, 0.125, rtol=1e-12), "sod: right density from masses")
    rho, u = d["Densities"], d["InternalEnergies"]
    P = (5 / 3 - 1) * rho * u
    check(np.allclose(P[left], 1) and np.allclose(P[~left], 0.1), "sod: pressures")
    check(np.allclose(rho[left], 1) and np.allclose(rho[~left], 0.125), "sod: densities")
    check(d["periodic"] == 1, "sod: not periodic")

    # Sedov: sum m du = E, only near the centre; uniform weighting: equal du
    for w in ("kernel", "uniform"):
        d = make(tmp, "sedov_" + w, "sedov", "--n", "16", "--energy", "2.5", "--u", "1e-6",
                 "--weighting", w)
        du = d["InternalEnergies"] - 1e-6
        e = np.sum(d["Masses"] * du)
        check(np.isclose(e, 2.5, rtol=1e-12), f"sedov {w}: energy {e} != 2.5")
        r = np.linalg.norm(d["Coordinates"] - 0.5, axis=1)
        hot = du > 1e-12
        R = 2 * d["SmoothingLengths"][0]
        check(hot.sum() >= 8 and np.all(r[hot] < R), f"sedov {w}: energy outside the radius")
        if w == "uniform":
            check(np.allclose(du[hot], du[hot][0], rtol=1e-12), "sedov uniform: du differs")
        else:
            o = np.argsort(r[hot])
            check(np.all(np.diff(du[hot][o]) <= 1e-12 * du.max()), "sedov kernel: du not decreasing")

    # the program's contract
    for args in (["sod", "--nx", "15"], ["box", "--lattice", "foo"], ["box", "--energy", "1"],
                 ["box", "--size", "1,2"], ["cube"], ["box", "extra"]):
        r = subprocess.run([exe, *args, "-o", os.path.join(tmp, "x.hdf5")], capture_output=True,
                           text=True)
        lines = r.stderr.splitlines()
        check(r.returncode != 0 and len(lines) == 1 and lines[0].startswith("bolide-ic: error: "),
              f"{args}: rc {r.returncode}, stderr {r.stderr!r}")
    r = subprocess.run([exe, "--help"], capture_output=True, text=True)
    check(r.returncode == 0 and "Usage" in r.stdout, "--help")
    r = subprocess.run([exe, "--version"], capture_output=True, text=True)
    check(r.returncode == 0 and "bolide-ic" in r.stdout, "--version")
    check(not os.path.exists(os.path.join(tmp, "x.hdf5.tmp")), "temporary file left")

print("FAIL" if failures else "PASS")
sys.exit(1 if failures else 0)
