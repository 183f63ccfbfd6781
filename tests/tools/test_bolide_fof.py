"""bolide-fof and bolide-flaws from the command line, checked with h5py,
numpy and scipy:
  - fragments of synthetic clumps: count, mass, centre of mass, velocity,
    material fractions, mean damage, order, against numpy;
  - the partition of random points against scipy (k-d tree pairs +
    connected components), an independent implementation;
  - --min-damage-drop leaves fully damaged particles out;
  - the escape test: bound and unbound satellites of a massive body;
  - the default linking length (--link-local 1.5: 1.5 x the larger smoothing
    length of a pair) keeps an intact layered planet of bolide-ic planet
    (iron, granite, water on SEA shells) in one fragment, which the
    median-h length (--link-h 1) cuts into many; the local lengths against
    scipy;
  - the spectrum file and the PNG (tools/plot_fragments.py);
  - bolide-flaws: every particle of the material has flaws, the sorted
    thresholds are (j/(kV))^(1/m), reproducible from the seed;
  - bad input: one line "PROGRAM: error: ...", exit 1."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

build = os.environ["BOLIDE_BUILDDIR"]
fof = os.path.join(build, "bolide-fof")
flaws = os.path.join(build, "bolide-flaws")
failures = []
G = 6.67430e-11


def check(cond, msg):
    print(("ok   " if cond else "FAIL ") + msg)
    if not cond:
        failures.append(msg)


def write_ic(path, pos, vel, mass, mat, h, rho, damage=None):
    """A snapshot-like file in SI."""
    n = len(mass)
    with h5py.File(path, "w") as f:
        hd = f.create_group("Header")
        hd.attrs["NumPart_Total"] = np.array([n, 0, 0, 0, 0, 0], dtype=np.uint32)
        hd.attrs["NumPart_Total_HighWord"] = np.zeros(6, dtype=np.uint32)
        hd.attrs["BoxSize"] = np.array([1e9, 1e9, 1e9])
        hd.attrs["Time"] = np.array([1.5])
        u = f.create_group("Units")
        for k, v in (("Unit mass in cgs (U_M)", 1e3), ("Unit length in cgs (U_L)", 1e2),
                     ("Unit time in cgs (U_t)", 1.0), ("Unit current in cgs (U_I)", 1.0),
                     ("Unit temperature in cgs (U_T)", 1.0)):
            u.attrs[k] = np.array([v])
        g = f.create_group("PartType0")
        g["Coordinates"] = pos
        g["Velocities"] = vel
        g["Masses"] = mass
        g["SmoothingLengths"] = h
        g["Densities"] = rho
        g["InternalEnergies"] = np.zeros(n)
        g["ParticleIDs"] = np.arange(1, n + 1, dtype=np.int64)
        g["MaterialIDs"] = mat.astype(np.int32)
        if damage is not None:
            g["Damage"] = damage


def read_table(path):
    with open(path) as f:
        lines = f.read().splitlines()
    names = [ln for ln in lines if ln.startswith("#")][-1].lstrip("#").split()
    rows = np.array([ln.split() for ln in lines if not ln.startswith("#")], dtype=float)
    rows = rows.reshape(-1, len(names))
    return {n: rows[:, i] for i, n in enumerate(names)}, lines


def ball(rng, n, r):
    p = rng.uniform(-1, 1, (4 * n, 3))
    p = p[(p ** 2).sum(1) < 1][:n]
    return r * p


def run(*args):
    return subprocess.run(list(args), capture_output=True, text=True)


rng = np.random.default_rng(3)
with tempfile.TemporaryDirectory() as tmp:
    # ---- clumps with materials, velocities and damage
    centres = np.array([[0, 0, 0], [20, 0, 0], [0, 30, 5], [-40, -40, 0]], float)
    sizes = [900, 500, 300, 200]
    pos, vel, mass, mat, dmg, lab = [], [], [], [], [], []
    for c, (x0, n) in enumerate(zip(centres, sizes)):
        pos.append(x0 + ball(rng, n, 2.0))
        vel.append(np.tile([c, -2.0 * c, 0.5], (n, 1)) + rng.normal(0, 0.1, (n, 3)))
        mass.append(rng.uniform(1, 2, n))
        mat.append(np.where(rng.uniform(size=n) < 0.3 * c / 3, 1, 0) if c < 3 else np.full(n, 7))
        dmg.append(np.full(n, 1.0) if c == 3 else rng.uniform(0, 0.5, n))
        lab.append(np.full(n, c))
    pos, vel, mass, mat, dmg, lab = map(np.concatenate, (pos, vel, mass, mat, dmg, lab))
    n = len(mass)
    ic = os.path.join(tmp, "clumps.hdf5")
    write_ic(ic, pos, vel, mass, mat, np.full(n, 0.3), np.full(n, 2700.0), dmg)
    out = os.path.join(tmp, "frag.txt")
    spec = os.path.join(tmp, "spec.txt")
    png = os.path.join(tmp, "spec.png")
    r = run(fof, ic, "--link-length", "0.8", "--out", out, "--spectrum", spec, "--plot", png)
    check(r.returncode == 0, "bolide-fof runs (%s)" % r.stderr.strip())
    t, lines = read_table(out)
    check(len(t["mass"]) == 4, "4 clumps -> 4 fragments (got %d)" % len(t["mass"]))
    order = np.argsort([-mass[lab == c].sum() for c in range(4)])
    ok_m = ok_x = ok_v = ok_f = ok_d = True
    for k, c in enumerate(order):
        s = lab == c
        m = mass[s].sum()
        ok_m &= abs(t["mass"][k] - m) <= 1e-8 * m and t["count"][k] == s.sum()
        com = (mass[s, None] * pos[s]).sum(0) / m
        ok_x &= np.allclose([t["x"][k], t["y"][k], t["z"][k]], com, rtol=0, atol=1e-7)
        cv = (mass[s, None] * vel[s]).sum(0) / m
        ok_v &= np.allclose([t["vx"][k], t["vy"][k], t["vz"][k]], cv, rtol=0, atol=1e-7)
        ok_d &= abs(t["damage"][k] - (mass[s] * dmg[s]).sum() / m) < 2e-6
        for mid in (0, 1, 7):
            ok_f &= abs(t["frac_mat%d" % mid][k] - mass[s & (mat == mid)].sum() / m) < 2e-6
    check(ok_m, "fragment masses and counts")
    check(ok_x, "fragment centres of mass")
    check(ok_v, "fragment velocities")
    check(ok_f, "material mass fractions")
    check(ok_d, "mass-weighted mean damage")
    check(np.all(np.diff(t["mass"]) <= 0), "sorted by mass, largest first")
    sp = np.loadtxt(spec)
    check(sp.shape == (4, 4) and np.array_equal(sp[:, 2], [1, 2, 3, 4])
          and abs(sp[-1, 3] - 1) < 1e-8, "spectrum: N(>=m) 1..4, all mass in fragments")
    check(os.path.getsize(png) > 1000, "spectrum PNG written")

    # ---- damaged particles dropped (the Nakamura analysis)
    r = run(fof, ic, "--link-length", "0.8", "--min-damage-drop", "1", "--out", out)
    t, lines = read_table(out)
    check(r.returncode == 0 and len(t["mass"]) == 3 and t["count"].sum() == n - sizes[3],
          "--min-damage-drop 1 drops the fully damaged clump")

    # ---- against scipy on random points
    pr = rng.uniform(0, 1, (4000, 3))
    ic2 = os.path.join(tmp, "random.hdf5")
    write_ic(ic2, pr, np.zeros_like(pr), np.ones(4000), np.zeros(4000), np.full(4000, 0.05),
             np.ones(4000))
    for L in (0.04, 0.055, 0.07):
        r = run(fof, ic2, "--link-length", str(L), "--out", out)
        t, _ = read_table(out)
        pairs = cKDTree(pr).query_pairs(L, output_type="ndarray")
        adj = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(4000, 4000))
        ng, labels = connected_components(adj, directed=False)
        sizes_ref = np.sort(np.bincount(labels))[::-1]
        check(r.returncode == 0 and len(t["count"]) == ng
              and np.array_equal(np.sort(t["count"])[::-1], sizes_ref),
              "L = %.3f: %d groups and their sizes as scipy's" % (L, ng))
    r = run(fof, ic2, "--link-h", "1.1", "--out", out)
    _, lines = read_table(out)
    check(r.returncode == 0 and any("linking length 0.055" in ln for ln in lines),
          "--link-h 1.1 -> L = 1.1 x median h = 0.055")

    # ---- an intact layered planet is one fragment with the default
    planet = os.path.join(tmp, "planet.hdf5")
    r = run(os.path.join(build, "bolide-ic"), "planet", "--materials", "iron,granite,water",
            "--mass", "5.97e24", "--mass-fractions", "0.3,0.6,0.1", "--n", "3000", "-o", planet)
    check(r.returncode == 0, "bolide-ic planet (%s)" % r.stderr.strip()[-200:])
    r = run(fof, planet, "--out", out)
    t, lines = read_table(out)
    check(r.returncode == 0 and len(t["count"]) == 1 and int(t["count"][0]) == 3000,
          "default: the intact planet is one fragment (%d fragments)" % len(t["count"]))
    check(any("--link-local" in ln for ln in lines), "the table names the default linking")
    # the former default, one global length of the median h, with h as the
    # cubic spline at eta 1.2348 sets it (1.2348 spacings): with the build's
    # kernel at its default eta that is --link-h 1.2348 / eta
    ref = run(os.path.join(build, "bolide"), "--param-reference").stdout.splitlines()
    sec, eta = "", None
    for ln in ref:
        if ln and not ln[0].isspace() and not ln.startswith("#"):
            sec = ln.split()[0]
        elif sec == "SPH:" and ln.split()[:1] == ["resolution_eta:"]:
            eta = float(ln.split()[1])
    check(eta is not None, "bolide --param-reference gives SPH:resolution_eta")
    F = 1.2348 / eta
    r = run(fof, planet, "--link-h", "%.4f" % F, "--out", out)
    t1, _ = read_table(out)
    check(len(t1["count"]) > 1, "--link-h %.4f (the median h of the cubic spline at eta 1.2348) splits it "
          "(%d fragments): why the default changed" % (F, len(t1["count"])))
    with h5py.File(planet, "r") as f:
        pp, hh = f["PartType0/Coordinates"][...], f["PartType0/SmoothingLengths"][...]
    for F in (0.9, 1.0):
        r = run(fof, planet, "--link-local", str(F), "--out", out)
        t, _ = read_table(out)
        pairs = cKDTree(pp).query_pairs(F * hh.max(), output_type="ndarray")
        d = np.linalg.norm(pp[pairs[:, 0]] - pp[pairs[:, 1]], axis=1)
        pairs = pairs[d < F * np.maximum(hh[pairs[:, 0]], hh[pairs[:, 1]])]
        adj = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(pp),) * 2)
        ng, labels = connected_components(adj, directed=False)
        check(r.returncode == 0 and np.array_equal(np.sort(t["count"])[::-1],
                                                   np.sort(np.bincount(labels))[::-1]),
              "--link-local %.1f: %d groups and their sizes as scipy's" % (F, ng))

    # ---- escape test: satellites of a massive body
    M = 1e20
    core = ball(rng, 2000, 1e4)
    rs = 1e5
    vesc = np.sqrt(2 * G * M / rs)
    sat_x = np.array([[rs, 0, 0], [-rs, 0, 0], [0, rs, 0]])
    sat_v = np.array([[0, 0.5 * vesc, 0], [0, 0, 2 * vesc], [-0.9 * vesc, 0, 0]])
    pos3 = np.concatenate([core] + [x + ball(rng, 20, 100.0) for x in sat_x])
    vel3 = np.concatenate([np.zeros((2000, 3))] + [np.tile(v, (20, 1)) for v in sat_v])
    m3 = np.concatenate([np.full(2000, M / 2000), np.full(60, 1e6)])
    ic3 = os.path.join(tmp, "sats.hdf5")
    write_ic(ic3, pos3, vel3, m3, np.zeros(2060), np.full(2060, 1e3), np.full(2060, 2700.0))
    r = run(fof, ic3, "--link-length", "3000", "--out", out)
    t, _ = read_table(out)
    check(r.returncode == 0 and len(t["mass"]) == 4, "escape set-up: 4 fragments")
    if len(t["mass"]) == 4:
        check(t["bound"][0] == 1, "central body bound")
        sat = {round(x / rs): b for x, b in zip(t["x"][1:] + 2 * t["y"][1:], t["bound"][1:])}
        check(sat == {1: 1, -1: 0, 2: 1},
              "satellites: 0.5 v_esc bound, 2 v_esc unbound, 0.9 v_esc bound (%s)" % sat)
        check(np.allclose(t["v_esc"][1:], vesc, rtol=1e-3), "v_esc = sqrt(2 G M / r)")

    # ---- bolide-flaws
    out_ic = os.path.join(tmp, "flawed.hdf5")
    r = run(flaws, ic, out_ic, "--mat", "1", "--k", "5e34", "--m", "8", "--seed", "9")
    check(r.returncode == 0, "bolide-flaws runs (%s)" % r.stderr.strip())
    with h5py.File(out_ic) as f:
        off = f["PartType0/FlawOffsets"][:]
        eps = f["PartType0/FlawThresholds"][:]
        same = np.array_equal(f["PartType0/Coordinates"][:], pos)
    cnt = np.diff(off)
    check(same and len(off) == n + 1, "particles copied, N + 1 offsets")
    check(np.all(cnt[mat == 1] >= 1) and np.all(cnt[mat != 1] == 0),
          "every particle of material 1 has flaws, the others none")
    V = (mass[mat == 1] / 2700.0).sum()
    j = np.arange(1, len(eps) + 1)
    check(np.allclose(np.sort(eps), (j / (5e34 * V)) ** (1 / 8), rtol=1e-13, atol=0),
          "sorted thresholds = (j/(kV))^(1/m)")
    out_ic2 = os.path.join(tmp, "flawed2.hdf5")
    run(flaws, ic, out_ic2, "--mat", "1", "--k", "5e34", "--m", "8", "--seed", "9")
    with h5py.File(out_ic2) as f:
        check(np.array_equal(f["PartType0/FlawThresholds"][:], eps), "same seed, same flaws")
    r = run(flaws, out_ic, out_ic2, "--mat", "7", "--k", "1e40", "--m", "9", "--seed", "2")
    with h5py.File(out_ic2) as f:
        off2 = f["PartType0/FlawOffsets"][:]
        eps2 = f["PartType0/FlawThresholds"][:]
    c2 = np.diff(off2)
    kept = all(np.array_equal(eps2[off2[i]:off2[i + 1]], eps[off[i]:off[i + 1]])
               for i in np.flatnonzero(mat == 1))
    check(r.returncode == 0 and kept and np.all(c2[mat == 7] >= 1) and np.all(c2[mat == 0] == 0),
          "second material added, first kept")

    # ---- bad input
    for args, what in (([fof, os.path.join(tmp, "none.hdf5")], "missing snapshot"),
                       ([fof, ic, "--link-length", "-1"], "negative linking length"),
                       ([flaws, ic, out_ic, "--k", "1", "--m", "2"], "missing --mat"),
                       ([flaws, ic, out_ic, "--mat", "5", "--k", "1", "--m", "2"],
                        "material absent")):
        r = run(*args)
        err = r.stderr.strip().splitlines()
        check(r.returncode == 1 and len(err) == 1 and ": error: " in err[0],
              "%s: one error line, exit 1 (%s)" % (what, err[0] if err else ""))

sys.exit(1 if failures else 0)
