"""VALIDATION "SEA planet", first half: a 1e5-particle Earth-mass Tillotson
granite planet (isothermal 300 K) on SEA shells has every particle's SPH
density within 1 % of the profile, the outermost shell excepted.

The planet is made by `bolide-ic planet` with its defaults: shells 1.2
particle spacings thick, stretching a = 0.2 -> 0.15, the shells' placement
density iterated against their SPH density (6 iterations; the outermost
shell takes the mass that is left) and 30 steps of relaxation along the
shells (theory/planets.md, "SEA planet: the 1 % bar").  The SPH density is
the one Bolide computes at start-up with its defaults (the kernel the build
was configured with and its default resolution_eta: Wendland C2 and 1.7,
149 neighbours, since issue 17 item 5; the cubic spline and 1.2348, 48
neighbours, before; tools/sph_density.py is the same estimator, written
independently of the C code that the generator uses, and takes the kernel
from the file's header and eta from `bolide --param-reference`).  The test asserts the
bar as written and prints, per shell, where the deviation comes from:

* surface: the SPH density of the *continuous* profile (no particles at all,
  sph_density.profile_density) at each shell.  Within a kernel radius of
  the free surface the kernel reaches into vacuum: even a perfect continuum
  gives a density ~1 % below the profile on the second shell from the top;
  the generator compensates by placing slightly more mass there.
* discretisation: the particles' SPH densities about that continuum value.
* seagen (Kegerreis et al. 2019's own implementation) on the same profile
  and N, with the same estimator, for comparison (~2 %)."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

import sph_density

build = os.environ["BOLIDE_BUILDDIR"]
exe = os.path.join(build, "bolide-ic")
N = 100000
M_E = 5.972e24
failures = []


def check(cond, msg):
    print("ok  " if cond else "FAIL", msg)
    if not cond:
        failures.append(msg)


LIB = """granite:
  reference: "Tillotson granite (SWIFT id 101) with woma's P_min = 0"
  swift_id: 101
  eos: tillotson
  rho0: 2680
  A: 18e9
  B: 18e9
  E0: 16e6
  Eiv: 3.5e6
  Ecv: 18e6
  a: 0.5
  b: 1.3
  alpha: 5
  beta: 5
  cv: 790
  P_min: 0
"""

# the continuum estimate itself: a uniform sphere, deep inside, gives rho
rp = np.linspace(0, 10.0, 1001)
val = sph_density.profile_density(np.array([5.0]), np.array([0.5]), rp, np.full_like(rp, 3.0))
if abs(val[0] / 3.0 - 1) > 1e-6:  # a broken tool is a hard error, not the expected failure
    print(f"continuum SPH density of a uniform profile {val[0]:.8f}, not 3")
    sys.exit(99)


def shells_of(rr):
    radii, inv = np.unique(np.round(rr, 0), return_inverse=True)
    return radii, inv


with tempfile.TemporaryDirectory() as tmp:
    lib = os.path.join(tmp, "lib.yml")
    with open(lib, "w") as f:
        f.write(LIB)
    prof = os.path.join(tmp, "prof.txt")
    path = os.path.join(tmp, "planet.hdf5")
    r = subprocess.run([exe, "planet", "--library", lib, "--materials", "granite", "--mass",
                    str(M_E), "--T-surface", "300", "--n", str(N), "--profile", prof,
                    "-o", path], capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stderr)
        sys.exit(99)
    P = np.loadtxt(prof)
    r_prof, rho_prof = P[:, 0], P[:, 2]
    with h5py.File(path, "r") as f:
        d = {k: f["PartType0"][k][:] for k in f["PartType0"]}
        x = d["Coordinates"] - 0.5 * f["Header"].attrs["BoxSize"]
    rr = np.linalg.norm(x, axis=1)
    kern = sph_density.kernel_of(path)
    eta = sph_density.eta_default(os.path.join(build, "bolide"))
    kn = int(2 * sph_density.neighbours(eta, kern)) + 1
    print(f"     estimator: {kern}, resolution_eta {eta}, {kn} neighbours searched")
    rho_sph, h = sph_density.density(x, d["Masses"], eta=eta, k=max(100, kn), kernel=kern)
    radii, inv = shells_of(rr)
    outer = inv == len(radii) - 1
    dev = rho_sph / d["Densities"] - 1
    cont = sph_density.profile_density(rr, h, r_prof, rho_prof, kernel=kern)
    surf = cont / d["Densities"] - 1  # continuum SPH vs profile
    disc = rho_sph / cont - 1  # particles vs continuum SPH
    print(f"     {len(radii)} shells; per shell: r/R, N, SPH vs profile mean [min, max],"
          " continuum SPH vs profile, particles vs continuum [min, max]")
    for k in range(len(radii)):
        s = inv == k
        print(f"     {k:3d} {radii[k] / r_prof[-1]:.4f} {s.sum():6d}  {dev[s].mean():+.4f} "
              f"[{dev[s].min():+.4f}, {dev[s].max():+.4f}]  {surf[s].mean():+.4f}  "
              f"[{disc[s].min():+.4f}, {disc[s].max():+.4f}]")
    worst = np.argmax(np.where(outer, 0, np.abs(dev)))
    kw = inv[worst]
    try:
        import seagen
        s = seagen.GenSphere(N, r_prof[1:], rho_prof[1:], A1_mat_prof=np.zeros(len(r_prof) - 1),
                             A1_u_prof=P[1:, 5], verbosity=0)
        xs = np.c_[s.A1_x, s.A1_y, s.A1_z]
        rs_sg, _ = sph_density.density(xs, s.A1_m, eta=eta, k=max(100, kn), kernel=kern)
        rr_sg = np.linalg.norm(xs, axis=1)
        rad_sg, inv_sg = shells_of(rr_sg)
        dsg = np.abs(rs_sg / s.A1_rho - 1)[inv_sg < len(rad_sg) - 1]
        print(f"     seagen, same profile and N: largest deviation {dsg.max():.4f} (outer shell"
              " excepted)")
    except ImportError:
        print("     seagen not installed: no comparison")
    print(f"     worst particle: shell {kw} of {len(radii)} (r/R {radii[kw] / r_prof[-1]:.4f}):"
          f" {dev[worst]:+.4f} = continuum {surf[worst]:+.4f} and particles "
          f"{disc[worst]:+.4f}")
    check(np.abs(dev[~outer]).max() < 0.01,
          f"every SPH density within 1 % of the profile, outermost shell excepted: largest "
          f"deviation {np.abs(dev[~outer]).max():.4f}")

sys.exit(1 if failures else 0)
