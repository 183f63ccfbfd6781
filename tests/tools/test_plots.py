"""Smoke tests of the plotting scripts on small synthetic snapshots written
here with h5py, and of the L1 error.

- plot_sod.py on particles carrying the exact solution prints L1 errors ~0
  (< 1e-12) and on a perturbed copy (density, velocity and pressure off by
  5%) L1 errors above 1e-3, so the comparison can fail; the PNG is written.
- plot_sedov.py on particles sampled from the similarity solution measures a
  shock radius within one bin width of the analytic one, and on a snapshot
  of the same solution at a 10% larger radius reports rel_error > 5%.
- plot_stats.py reads columns by the header's names (shuffled order) and
  reports the energy drift put into the synthetic file.
- plot_snapshot.py draws a two-body "collision" by material and by density.
- Bad input (missing file, missing dataset) gives one "error:" line and
  exit status 1.
"""

import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

from bolide_tools import l1, riemann, sedov

TOOLS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools")
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def write_snapshot(path, pos, vel, rho, P, u, time, box, mat=None, h=None):
    """A minimal Bolide snapshot."""
    import h5py

    n = pos.shape[0]
    with h5py.File(path, "w") as f:
        hdr = f.create_group("Header")
        hdr.attrs["Time"] = time
        hdr.attrs["BoxSize"] = np.asarray(box, dtype=float)
        g = f.create_group("PartType0")
        g["Coordinates"] = pos
        g["Velocities"] = vel
        g["Masses"] = np.full(n, 1.0 / n)
        g["SmoothingLengths"] = np.full(n, 0.05) if h is None else h
        g["InternalEnergies"] = u
        g["Densities"] = rho
        g["Pressures"] = P
        g["SoundSpeeds"] = np.sqrt(5.0 / 3.0 * P / rho)
        g["ParticleIDs"] = np.arange(1, n + 1, dtype=np.int64)
        g["MaterialIDs"] = np.zeros(n, dtype=np.int32) if mat is None else mat


def run(script, *args):
    """Run a tool with this interpreter; returns (rc, stdout, stderr)."""
    proc = subprocess.run([sys.executable, os.path.join(TOOLS, script)] + list(args),
                          capture_output=True, text=True, timeout=120)
    return proc.returncode, proc.stdout, proc.stderr


def parse(stdout, key):
    """Values of the line "KEY v1 [name v2 ...]" as a dict or float."""
    for line in stdout.splitlines():
        tokens = line.split()
        if not tokens:
            continue
        if tokens[0] == "L1" and key.startswith("L1 ") and tokens[1] == key[3:]:
            return float(tokens[2])
        if tokens[0] == key:
            if len(tokens) == 2:
                return float(tokens[1])
            return {tokens[i]: float(tokens[i + 1]) for i in range(1, len(tokens) - 1, 2)}
    raise AssertionError("no line %r in output:\n%s" % (key, stdout))


class PlotTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def assertPng(self, path):
        self.assertTrue(os.path.exists(path), path)
        with open(path, "rb") as f:
            self.assertEqual(f.read(8), PNG_MAGIC)
        self.assertGreater(os.path.getsize(path), 5000)
        self.assertFalse(os.path.exists(path + ".tmp"))


class L1(unittest.TestCase):
    def test_definition(self):
        f = np.array([1.0, 2.0, 3.0, 4.0])
        g = np.array([1.0, 2.5, 2.0, 4.0])
        self.assertAlmostEqual(l1.l1_error(f, g), 1.5 / 4)
        self.assertAlmostEqual(l1.l1_error(f, g, mask=f > 1.5), 1.5 / 3)
        self.assertAlmostEqual(l1.l1_error(f, g, weights=[0, 1, 1, 0]), 0.75)
        self.assertAlmostEqual(l1.l1_error(f, g, relative=True), 1.5 / 9.5)
        with self.assertRaises(ValueError):
            l1.l1_error(f, g, mask=f > 10)
        with self.assertRaises(ValueError):
            l1.l1_error(f, g[:3])


class Sod(PlotTest):
    def make(self, name, perturb):
        rng = np.random.default_rng(1)
        n = 6000
        box = np.array([2.0, 0.25, 0.25])
        pos = rng.random((n, 3)) * box
        t = 0.2
        rho, v, P = riemann.shock_tube(pos[:, 0], t, (1, 0, 1), (0.125, 0, 0.1), 5 / 3,
                                       0.0, 1.0, 2.0)
        scale = 1.0 + perturb * rng.standard_normal(n)
        rho, P = rho * scale, P * scale
        vel = np.zeros((n, 3))
        vel[:, 0] = v + perturb * rng.standard_normal(n)
        u = P / (2.0 / 3.0 * rho)
        path = os.path.join(self.dir, name)
        write_snapshot(path, pos, vel, rho, P, u, t, box)
        return path

    def test_exact_and_perturbed(self):
        for perturb, check in ((0.0, lambda e: self.assertLess(e, 1e-12)),
                               (0.05, lambda e: self.assertGreater(e, 1e-3))):
            snap = self.make("sod_%g.hdf5" % perturb, perturb)
            out = os.path.join(self.dir, "sod_%g.png" % perturb)
            rc, so, se = run("plot_sod.py", snap, "--out", out)
            self.assertEqual(rc, 0, se)
            for field in ("density", "velocity", "pressure"):
                check(parse(so, "L1 " + field))
            self.assertPng(out)

    def test_wrong_interfaces_detected(self):
        """The exact solution of a different set-up gives a large L1."""
        snap = self.make("sod.hdf5", 0.0)
        rc, so, se = run("plot_sod.py", snap, "--x0", "0.1", "1.1",
                         "--out", os.path.join(self.dir, "x.png"))
        self.assertEqual(rc, 0, se)
        self.assertGreater(parse(so, "L1 density"), 0.01)

    def test_errors(self):
        rc, so, se = run("plot_sod.py", os.path.join(self.dir, "missing.hdf5"))
        self.assertEqual(rc, 1)
        self.assertEqual(len(se.strip().splitlines()), 1)
        self.assertIn("error:", se)
        import h5py
        bad = os.path.join(self.dir, "bad.hdf5")
        with h5py.File(bad, "w") as f:
            f.create_group("PartType0")["Coordinates"] = np.zeros((3, 3))
        rc, so, se = run("plot_sod.py", bad)
        self.assertEqual(rc, 1)
        self.assertIn("Velocities", se)
        rc, so, se = run("plot_sod.py", "--help")
        self.assertEqual(rc, 0)
        self.assertIn("--x0", so)


class Sedov(PlotTest):
    def make(self, name, stretch):
        """Particles at random radii carrying the similarity solution of a
        blast whose radius is STRETCH times the analytic one."""
        rng = np.random.default_rng(2)
        n = 40000
        box = np.ones(3)
        pos = rng.random((n, 3))
        d = pos - 0.5
        r = np.sqrt(np.sum(d * d, axis=1))
        sol = sedov.SedovSolution(5.0 / 3.0)
        t = 0.05
        rho, v, P = sol.profiles(r / stretch, t)
        vel = v[:, None] * d / np.maximum(r, 1e-30)[:, None] * stretch
        path = os.path.join(self.dir, name)
        write_snapshot(path, pos, vel, rho, P + 1e-6, 1.5 * P / rho, t, box)
        return path, float(sol.shock_radius(t))

    def test_shock_radius(self):
        snap, R = self.make("sedov.hdf5", 1.0)
        out = os.path.join(self.dir, "sedov.png")
        rc, so, se = run("plot_sedov.py", snap, "--out", out)
        self.assertEqual(rc, 0, se)
        vals = parse(so, "shock_radius")
        width = parse(so, "bin_width")
        self.assertAlmostEqual(vals["analytic"], R, delta=1e-5 * R)
        self.assertLess(abs(vals["measured"] - R), width)
        self.assertLess(parse(so, "L1 density"), 1e-12)
        self.assertPng(out)
        snap, R = self.make("sedov_big.hdf5", 1.1)
        rc, so, se = run("plot_sedov.py", snap, "--out", out)
        self.assertEqual(rc, 0, se)
        self.assertGreater(parse(so, "shock_radius")["rel_error"], 0.05)
        self.assertGreater(parse(so, "L1 density"), 0.05)


class Stats(PlotTest):
    def test_drift(self):
        t = np.linspace(0.0, 1.0, 51)
        e_kin = 0.5 + 0.1 * t
        e_int = 1.0 - 0.1 * t
        e_pot = -0.5 * np.ones_like(t)
        e_tot = e_kin + e_int + e_pot + 0.004 * t  # 0.4% drift of E_tot(0) = 1
        zeros = np.zeros_like(t)
        cols = {"step": np.arange(51), "time": t, "dt": np.full(51, 0.02), "mass": zeros + 2.0,
                "px": 1e-3 * t, "py": zeros, "pz": zeros, "Lx": zeros, "Ly": zeros,
                "Lz": zeros + 3.0, "E_kin": e_kin, "E_int": e_int, "E_pot": e_pot,
                "E_tot": e_tot, "n_particles": zeros + 1000, "n_removed": zeros}
        names = list(cols)
        names.reverse()  # the tool must not rely on positions
        path = os.path.join(self.dir, "statistics.txt")
        with open(path, "w") as f:
            f.write("# " + " ".join(names) + "\n")
            for i in range(t.size):
                f.write(" ".join("%.10g" % cols[k][i] for k in names) + "\n")
        out = os.path.join(self.dir, "stats.png")
        rc, so, se = run("plot_stats.py", path, "--out", out)
        self.assertEqual(rc, 0, se)
        self.assertAlmostEqual(parse(so, "max_rel_energy_drift"), 0.004, delta=1e-8)
        p_scale = np.sqrt(2.0 * 2.0 * 0.6)
        self.assertAlmostEqual(parse(so, "max_rel_momentum_drift"), 1e-3 / p_scale, delta=1e-9)
        self.assertPng(out)
        with open(path, "a") as f:
            f.write("1 2 3\n")
        rc, so, se = run("plot_stats.py", path, "--out", out)
        self.assertEqual(rc, 1)
        self.assertIn("statistics.txt:53:", se)


class Picture(PlotTest):
    def test_collision(self):
        rng = np.random.default_rng(3)
        n = 3000
        a = rng.standard_normal((n, 3)) * 0.3
        b = rng.standard_normal((n // 3, 3)) * 0.2 + [1.0, 0.3, 0.0]
        pos = np.concatenate([a, b])
        m = pos.shape[0]
        mat = np.concatenate([np.zeros(n, np.int32), np.ones(n // 3, np.int32)])
        rho = np.exp(-np.sum(pos * pos, axis=1))
        vel = np.zeros((m, 3))
        vel[n:, 0] = -1.0
        write_snapshot(os.path.join(self.dir, "impact.hdf5"), pos, vel, rho, rho, rho,
                       0.0, [4, 4, 4], mat=mat)
        snap = os.path.join(self.dir, "impact.hdf5")
        for colour, extra in (("material", []), ("density", ["--log"]),
                              ("velocity", ["--slice", "0"])):
            out = os.path.join(self.dir, "%s.png" % colour)
            rc, so, se = run("plot_snapshot.py", snap, "--colour", colour, "--out", out, *extra)
            self.assertEqual(rc, 0, se)
            self.assertPng(out)
        rc, so, se = run("plot_snapshot.py", snap, "--colour", "Damage")
        self.assertEqual(rc, 1)
        self.assertIn("Damage", se)


if __name__ == "__main__":
    unittest.main()
