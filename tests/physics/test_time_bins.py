#!/usr/bin/env python3
"""Individual time steps in time bins (TimeIntegration:global_step: false;
src/timeline.h, theory/sph.md "Time bins").

1. A Kepler orbit in bins against the analytic orbit: a light particle
   (m = 1e-6) on an orbit of eccentricity 0.5 and semi-major axis 1 about
   a heavy one (M = 1, G = 1), gravity only, softening 1e-3 (Newtonian
   beyond 2.8e-3; periapsis 0.5).  The gravitational criterion
   dt = sqrt(2 eta eps / |a|) puts the light particle in bins that change
   along the orbit (|a| varies by 9 between periapsis and apoapsis) and the
   heavy one in the longest (dt_max).  Asserts, after three orbits: the
   timesteps file shows more than one bin in use, and the light particle's
   bin changed at least 4 times; its position is within 2e-3 of Kepler's
   (measured 9.5e-4 with bins, 2.2e-3 with the global step, whose steps are
   up to twice as long) and its specific orbital energy within 1e-5
   (relative) of the start (measured 4.5e-7; 6.8e-7 global).
2. The Evrard collapse (theory/validation.md) at 16^3 cells of its
   lattice, with bins, to t = 1.4: the total energy within 1% of its start
   at every statistics line (the bound of tests/physics/test_evrard.sh for the
   global step) and the thermal energy's peak within 15% of the free-fall
   time of the outer shell.
3. The Sedov blast of tests/physics/test_sedov.sh (32^3, a hot centre in a
   cold medium) in bins: without the time-step limiter
   (TimeIntegration:max_bin_ratio 56) the blast runs into sleeping
   particles and is wrong (measured: radius -28%, energy +134%); with the
   default limiter the shock radius is within 3% of the similarity solution
   and the energy within 0.5%, the bounds of the global step's test
   (measured +2.5%, +0.19%).
4. The prediction of sleeping particles (drift_predict_hydro): the Evrard
   collapse in bins with a snapshot at t = 0.3, a time at which every
   particle is in the middle of its step; the snapshot's pressure of every
   particle is the ideal gas's (gamma - 1) rho u at its density and
   energy of now, to 1e-9 (without the prediction the pressure is that of
   the step's start: 3.5e-2 off).
5. Angular momentum of the small planetary reference impact (bolide-ic
   impact, 2,200 granite particles, as tests/physics/test_energy_budget.sh)
   in bins to 1000 s: |dL| / |L| at the end (a time that ends every
   particle's step) within 8e-3 (measured 5.3e-3; 1.04e-2 before the
   prediction of sleeping particles, 2.0e-2 without the limiter, 3.4e-7
   with the global step: the pairwise exchange of momentum between
   particles in different bins, theory/sph.md section 8).
6. Gravity for the particles that end their step only (Gravity:active_only,
   the default; item 4): the impact of 5 again with gravity computed for
   every particle at every step; the two runs end within 1e-6 of |E_pot(0)|
   in total energy and 1e-6 of |L| in angular momentum (measured 2.6e-9
   and 1.8e-8: the adaptive opening criterion of a cell whose particles did
   not move to a new step reads their acceleration of their last
   evaluation, not of the last step), and most steps (more than half) were
   steps of active particles only.
7. The timesteps file of the impact of 5: its Updates column counts the
   particles that ended their step (fewer than all at some step) and sums
   to the log's total of particle updates, one line per step."""
import os
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

build = os.environ.get("BOLIDE_BUILDDIR", ".")
src = os.environ.get("BOLIDE_SRCDIR", os.path.join(os.path.dirname(__file__), "..", ".."))
bolide = os.path.join(build, "bolide")
python = os.environ.get("PYTHON", sys.executable)
A, ECC, M, m = 1.0, 0.5, 1.0, 1e-6
ORBITS = 3
fail = 0


def check(ok, what):
    global fail
    print(("ok: " if ok else "FAIL: ") + what)
    fail += not ok


def kepler_ic(path):
    # periapsis on the x axis, velocity along +y; the centre of mass at rest
    rp = A * (1 - ECC)
    mu = M + m
    vp = np.sqrt(mu * (1 + ECC) / rp)
    rel_x = np.array([rp, 0.0, 0.0])
    rel_v = np.array([0.0, vp, 0.0])
    c = np.array([5.0, 5.0, 5.0])
    x = np.array([c - m / mu * rel_x, c + M / mu * rel_x])
    v = np.array([-m / mu * rel_v, M / mu * rel_v])
    with h5py.File(path, "w") as f:
        h = f.create_group("Header")
        h.attrs["BoxSize"] = [10.0, 10.0, 10.0]
        h.attrs["NumPart_Total"] = [2, 0, 0, 0, 0, 0]
        h.attrs["Dimension"] = 3
        p = f.create_group("PartType0")
        p["Coordinates"] = x
        p["Velocities"] = v
        p["Masses"] = np.array([M, m])
        p["SmoothingLengths"] = np.full(2, 0.01)
        p["InternalEnergies"] = np.zeros(2)
        p["ParticleIDs"] = np.array([1, 2])
        p["MaterialIDs"] = np.zeros(2, dtype=np.int32)


def kepler_position(t):
    # relative position of the light particle at time t from periapsis
    mu = M + m
    n = np.sqrt(mu / A**3)
    Mean = n * t
    E = Mean
    for _ in range(50):
        E -= (E - ECC * np.sin(E) - Mean) / (1 - ECC * np.cos(E))
    return np.array([A * (np.cos(E) - ECC), A * np.sqrt(1 - ECC**2) * np.sin(E), 0.0])


KEPLER = """
InternalUnitSystem: {{UnitMass_in_cgs: 1, UnitLength_in_cgs: 1, UnitVelocity_in_cgs: 2.583466663225984e-04, UnitCurrent_in_cgs: 1, UnitTemp_in_cgs: 1}}
InitialConditions: {{file_name: kepler.hdf5, periodic: false}}
TimeIntegration: {{time_end: {t_end}, dt_max: 0.05, global_step: {glob}}}
Snapshots: {{basename: kepler, subdir: out_{tag}, delta_time: {t_end}}}
Statistics: {{delta_time: {t_end}}}
SPH: {{hydro: false}}
Gravity: {{enabled: true, eta: 0.025, softening: 0.001}}
Materials:
  0: {{name: dust, eos: ideal_gas, gamma: 1.6666666666666667}}
"""


def kepler(d, glob):
    tag = "global" if glob else "bins"
    t_end = ORBITS * 2 * np.pi * np.sqrt(A**3 / (M + m))
    with open(os.path.join(d, f"k_{tag}.yml"), "w") as f:
        f.write(KEPLER.format(t_end=t_end, tag=tag, glob="true" if glob else "false"))
    r = subprocess.run([bolide, "-t", "1", f"k_{tag}.yml"], cwd=d, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-2000:])
        sys.exit(1)
    out = os.path.join(d, f"out_{tag}")
    snaps = sorted(s for s in os.listdir(out) if s.startswith("kepler_") and s.endswith(".hdf5"))
    with h5py.File(os.path.join(out, snaps[-1]), "r") as f:
        t = f["Header"].attrs["Time"]
        t = float(np.ravel(t)[0])
        ids = f["PartType0/ParticleIDs"][:]
        x = f["PartType0/Coordinates"][:][np.argsort(ids)]
        v = f["PartType0/Velocities"][:][np.argsort(ids)]
    rel = x[1] - x[0]
    relv = v[1] - v[0]
    err = np.linalg.norm(rel - kepler_position(t))
    energy = 0.5 * relv @ relv - (M + m) / np.linalg.norm(rel)
    e0 = -(M + m) / (2 * A)
    bins = []
    with open(os.path.join(out, "timesteps.txt")) as f:
        for line in f:
            if not line.startswith("#"):
                # Step Time Time-step Updates Wall-clock Bin-min Bin-max Active-fraction
                w = line.split()
                bins.append((int(w[5]), int(w[6])))
    print(f"{tag}: t = {t:.6f}, {len(bins)} steps, position error {err:.3e}, "
          f"energy error {abs(energy / e0 - 1):.3e}")
    return err, abs(energy / e0 - 1), bins


def evrard(d):
    subprocess.run([python, os.path.join(src, "examples/EvrardCollapse/make_ic.py"), "16",
                    os.path.join(d, "evrard.hdf5")], check=True, capture_output=True)
    with open(os.path.join(src, "examples/EvrardCollapse/params.yml")) as f:
        text = f.read()
    with open(os.path.join(d, "evrard.yml"), "w") as f:
        f.write(text)
    r = subprocess.run([bolide, "-t", "2", "evrard.yml",
                        "-P", "TimeIntegration:time_end:1.4", "-P", "Snapshots:delta_time:10",
                        "-P", "TimeIntegration:global_step:false"],
                       cwd=d, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-2000:])
        sys.exit(1)
    rows, cols = [], None
    with open(os.path.join(d, "statistics.txt")) as f:
        for line in f:
            if line.startswith("# step"):
                cols = line[1:].split()
            elif not line.startswith("#"):
                rows.append([float(w) for w in line.split()])
    a = np.array(rows)
    E = a[:, cols.index("E_tot")]
    U = a[:, cols.index("E_int")]
    t = a[:, cols.index("time")]
    dmax = np.max(np.abs(E / E[0] - 1))
    tff = np.pi / (2 * np.sqrt(2))
    tu = t[np.argmax(U)]
    print(f"Evrard with bins: max |dE/E| {dmax:.3e}, E_int peaks at t = {tu:.4f} (t_ff {tff:.4f})")
    check(dmax < 0.01, "Evrard with bins: total energy within 1%")
    check(abs(tu / tff - 1) < 0.15, "Evrard with bins: thermal peak within 15% of t_ff")


def sedov(d):
    bolide_ic = os.path.join(build, "bolide-ic")
    subprocess.run([bolide_ic, "sedov", "--n", "32", "--energy", "1", "--rho", "1", "-o",
                    os.path.join(d, "sedov.hdf5")], check=True, capture_output=True)
    with open(os.path.join(src, "examples/SedovBlast3D/params.yml")) as f:
        text = f.read()
    with open(os.path.join(d, "sedov.yml"), "w") as f:
        f.write(text)
    out = {}
    variants = {"no limiter": ["-P", "TimeIntegration:max_bin_ratio:56"],
                "default limiter": [],
                "limiter_wake density": ["-P", "TimeIntegration:limiter_wake:density"]}
    for tag, extra in variants.items():
        args = [bolide, "-t", "2", "sedov.yml", "-P", "TimeIntegration:global_step:false"] + extra
        r = subprocess.run(args, cwd=d, capture_output=True, text=True)
        if r.returncode != 0:
            print(r.stdout[-2000:], r.stderr[-2000:])
            sys.exit(1)
        r = subprocess.run([python, os.path.join(src, "tools/plot_sedov.py"), "sedov_0002.hdf5",
                            "--initial", "sedov.hdf5", "--out", "sedov.png"],
                           cwd=d, capture_output=True, text=True, check=True)
        rel = [float(line.split()[6]) for line in r.stdout.splitlines()
               if line.startswith("shock_radius_moment")][0]
        rows, cols = [], None
        with open(os.path.join(d, "statistics.txt")) as f:
            for line in f:
                if line.startswith("# step"):
                    cols = line[1:].split()
                elif not line.startswith("#"):
                    rows.append(float(line.split()[cols.index("E_tot")]))
        dE = rows[-1] / rows[0] - 1
        print(f"Sedov in bins, {tag}: shock radius {rel:+.4f} of the similarity solution, "
              f"energy {dE:+.3e}")
        out[tag] = (rel, dE)
    rel, dE = out["no limiter"]
    check(abs(rel) > 0.1 or abs(dE) > 0.05,
          "Sedov in bins without the limiter is wrong (the test can see the limiter's work)")
    rel, dE = out["default limiter"]
    check(abs(rel) < 0.03, "Sedov in bins with the limiter: shock radius within 3% (test_sedov.sh's bound)")
    check(abs(dE) < 0.005, "Sedov in bins with the limiter: energy within 0.5% (test_sedov.sh's bound)")
    # the wakes decided in the density phase (by the bin rule and by signal
    # velocity), the woken particles computed at the wake time (measured:
    # energy +0.08%, against +0.11% with the force loop's wake)
    rel, dE = out["limiter_wake density"]
    check(abs(rel) < 0.03, "Sedov in bins, limiter_wake density: shock radius within 3%")
    check(abs(dE) < 0.005, "Sedov in bins, limiter_wake density: energy within 0.5%")


def prediction(d):
    """Item 4: the pressure of sleeping particles at the time of a snapshot."""
    sub = os.path.join(d, "pred")
    os.makedirs(sub, exist_ok=True)
    subprocess.run([python, os.path.join(src, "examples/EvrardCollapse/make_ic.py"), "16",
                    os.path.join(sub, "evrard.hdf5")], check=True, capture_output=True)
    with open(os.path.join(src, "examples/EvrardCollapse/params.yml")) as f:
        text = f.read()
    with open(os.path.join(sub, "evrard.yml"), "w") as f:
        f.write(text)
    r = subprocess.run([bolide, "-t", "2", "evrard.yml",
                        "-P", "TimeIntegration:time_end:0.31", "-P", "Snapshots:delta_time:0.3",
                        "-P", "TimeIntegration:global_step:false"],
                       cwd=sub, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-2000:])
        sys.exit(1)
    with h5py.File(os.path.join(sub, "evrard_0001.hdf5"), "r") as f:
        t = float(np.ravel(f["Header"].attrs["Time"])[0])
        rho = f["PartType0/Densities"][:]
        u = f["PartType0/InternalEnergies"][:]
        P = f["PartType0/Pressures"][:]
    gamma = 5.0 / 3.0
    err = np.max(np.abs(P - (gamma - 1) * rho * u) / np.abs((gamma - 1) * rho * u))
    print(f"Evrard in bins, snapshot at t = {t}: max |P - (gamma - 1) rho u| / P = {err:.3e}")
    check(abs(t - 0.3) < 1e-12, "Evrard in bins: a snapshot at t = 0.3")
    check(err < 1e-9, "sleeping particles: pressure of the predicted density and energy")


def impact_am(d):
    """Item 5: the angular momentum of the small reference impact in bins."""
    sub = os.path.join(d, "impact")
    os.makedirs(sub, exist_ok=True)
    r = subprocess.run([os.path.join(build, "bolide-ic"), "impact",
                        "--target", "sphere,material=granite,radius=1e6,n=2000,u=237000",
                        "--impactor", "sphere,material=granite,radius=4.642e5,n=200,u=237000",
                        "--v-contact", "2000", "--angle", "45", "--separation", "1.52e6",
                        "--time-end", "1000", "-o", "impact.hdf5"],
                       cwd=sub, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-2000:])
        sys.exit(1)
    with open(os.path.join(sub, "impact.yml"), "w") as f:
        f.write(IMPACT)
    r = subprocess.run([bolide, "--no-gpu", "-t", "2", "impact.yml"], cwd=sub, capture_output=True,
                       text=True)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-2000:])
        sys.exit(1)
    c, L = impact_stats(sub)
    dL = np.linalg.norm(L[-1] - L[0]) / np.linalg.norm(L[0])
    print(f"reference impact in bins, 2,200 particles, t = {c['time'][-1]:g} s: |dL| / |L| = {dL:.3e}")
    check(abs(c["time"][-1] - 1000) < 1e-6, "impact in bins: the run reached t = 1000 s")
    check(dL < 8e-3, f"impact in bins: angular momentum within 8e-3 ({dL:.2e})")
    m = re.search(r"gravity: (\d+) of (\d+) steps computed it only", r.stdout + r.stderr)
    check(m is not None and 2 * int(m.group(1)) > int(m.group(2)),
          "impact in bins: most steps computed gravity for the active particles only (%s)" %
          (m.group(0) if m else "no such line in the log"))
    # item 7: the timesteps file's Updates column counts the particles that
    # ended their step, and sums to the run's particle updates
    upd = re.search(r"time bins: (\d+) particle updates in (\d+) steps", r.stdout + r.stderr)
    col = [int(line.split()[3]) for line in open(os.path.join(sub, "timesteps.txt"))
           if not line.startswith("#")]
    check(upd is not None and sum(col) == int(upd.group(1)) and len(col) == int(upd.group(2))
          and min(col) < 2200,
          "impact in bins: the timesteps file's updates sum to the log's (%d in %d lines, log: %s)" %
          (sum(col), len(col), upd.group(0) if upd else "no such line"))
    # item 6: the same with gravity for every particle at every step
    full = os.path.join(d, "impact_full")
    os.makedirs(full, exist_ok=True)
    os.link(os.path.join(sub, "impact.hdf5"), os.path.join(full, "impact.hdf5"))
    with open(os.path.join(full, "impact.yml"), "w") as f:
        f.write(IMPACT)
    r = subprocess.run([bolide, "--no-gpu", "-t", "2", "-P", "Gravity:active_only:false",
                        "impact.yml"], cwd=full, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-2000:])
        sys.exit(1)
    cf, Lf = impact_stats(full)
    dE = abs(c["E_tot"][-1] - cf["E_tot"][-1]) / abs(cf["E_pot"][0])
    dLf = np.linalg.norm(L[-1] - Lf[-1]) / np.linalg.norm(Lf[-1])
    print(f"gravity for active particles only against every particle: total energy differs by "
          f"{dE:.2e} of |E_pot(0)|, angular momentum by {dLf:.2e} of |L|")
    check(dE < 1e-6, f"active-only gravity: total energy within 1e-6 of the full run's ({dE:.2e})")
    check(dLf < 1e-6, f"active-only gravity: angular momentum within 1e-6 of the full run's ({dLf:.2e})")


def impact_stats(sub):
    """The statistics columns of the run in sub and its angular momentum
    (removed particles' included) per line."""
    names = None
    for line in open(os.path.join(sub, "statistics.txt")):
        if line.startswith("# step"):
            names = line[1:].split()
    a = np.loadtxt(os.path.join(sub, "statistics.txt"), comments="#", ndmin=2)
    c = {k: a[:, i] for i, k in enumerate(names)}
    return c, np.stack([c[k] + c[k + "_removed"] for k in ("Lx", "Ly", "Lz")], 1)


IMPACT = """
InitialConditions: {file_name: impact.hdf5}
TimeIntegration: {time_end: 1000, global_step: false}
Snapshots: {delta_time: 1e30}
Statistics: {delta_time: 100}
Materials:
  101: {}
SPH: {resolution_eta: 1.2348, CFL_condition: 0.2, viscosity_alpha: 1.5}
Gravity: {enabled: true, theta_cr: 0.5, softening: 1.28e5}
"""


with tempfile.TemporaryDirectory() as d:
    kepler_ic(os.path.join(d, "kepler.hdf5"))
    eg, Eg, _ = kepler(d, True)
    eb, Eb, bins = kepler(d, False)
    in_use = sum(1 for lo, hi in bins if hi > lo)
    changes = sum(1 for a, b in zip(bins, bins[1:]) if a[0] != b[0])
    print(f"bins: {in_use} steps with more than one bin in use, the shortest bin changed {changes} times")
    check(in_use > 0, "more than one time bin in use")
    check(changes >= 4, "the light particle's bin changes along the orbit")
    check(eb < 2e-3, f"Kepler orbit in bins: position within 2e-3 of the analytic orbit ({eb:.2e})")
    check(Eb < 1e-5, f"Kepler orbit in bins: orbital energy within 1e-5 ({Eb:.2e})")
    if os.environ.get("TIME_BINS_EVRARD", "1") == "1":
        evrard(d)
    sedov(d)
    prediction(d)
    impact_am(d)
sys.exit(1 if fail else 0)
