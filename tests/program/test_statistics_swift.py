"""The statistics file in SWIFT's layout (issue 23 item 4), round trip
through swiftsimio with units.

A rotating, drifting box of rock runs 3 steps with self-gravity in SWIFT's
planetary units (Earth mass and radius); then
1. swiftsimio.load_statistics reads the statistics file and gives time,
   energies, momenta and angular momentum under SWIFT's names with the
   right dimensions;
2. its first line (t = 0) equals the totals computed from the t = 0
   snapshot loaded with swiftsimio, both converted to SI by unyt;
3. every step has one line (-n 3: steps 0..3, none twice), and Bolide's
   reader (tools/bolide_tools) still finds its own column names;
4. the timesteps file has one line per step with the statistics' times,
   time steps, particle updates and a wall-clock time."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

try:
    import swiftsimio
    import unyt
except ImportError as e:
    print("skip:", e)
    sys.exit(77)

build = os.environ["BOLIDE_BUILDDIR"]
src = os.environ["BOLIDE_SRCDIR"]
sys.path.insert(0, os.path.join(src, "tools"))
from bolide_tools import snapshot as bsnap  # noqa: E402

failures = []


def check(cond, msg):
    print(("ok  " if cond else "FAIL") + " " + msg)
    if not cond:
        failures.append(msg)


with tempfile.TemporaryDirectory() as tmp:
    ic = os.path.join(tmp, "box.hdf5")
    subprocess.run([os.path.join(build, "bolide-ic"), "box", "--n", "8", "--size", "1e6", "--rho",
                    "3000", "--u", "1e5", "-o", ic], check=True, capture_output=True)
    with h5py.File(ic, "r+") as f:  # SI: drift plus rotation about z
        x = f["PartType0/Coordinates"][...]
        c = x - x.mean(axis=0)
        v = np.stack([-1e-3 * c[:, 1] + 30.0, 1e-3 * c[:, 0] - 10.0, np.full(len(x), 5.0)], axis=1)
        f["PartType0/Velocities"][...] = v
    params = os.path.join(tmp, "p.yml")
    with open(params, "w") as f:
        f.write("""InternalUnitSystem:
  UnitMass_in_cgs:     5.9724e27
  UnitLength_in_cgs:   6.371e8
  UnitVelocity_in_cgs: 6.371e8
  UnitCurrent_in_cgs:  1
  UnitTemp_in_cgs:     1
InitialConditions:
  file_name: box.hdf5
TimeIntegration:
  time_end: 100
Snapshots:
  subdir: out
Statistics:
  delta_time: 0
Gravity:
  max_physical_baryon_softening: 1e-3
""")
    run = subprocess.run([os.path.join(build, "bolide"), "-s", "-G", "-n", "3", "-t", "2", params],
                         cwd=tmp, capture_output=True, text=True)
    if run.returncode != 0:
        print(run.stdout[-2000:], run.stderr[-2000:])
        sys.exit(1)
    out = os.path.join(tmp, "out")
    st = swiftsimio.load_statistics(os.path.join(out, "statistics.txt"))

    # 1. SWIFT's names and units
    dims = {"time": unyt.dimensions.time, "kin_energy": unyt.dimensions.energy,
            "int_energy": unyt.dimensions.energy, "pot_energy": unyt.dimensions.energy,
            "total_mass": unyt.dimensions.mass, "mom_x": unyt.dimensions.momentum,
            "ang_mom_z": unyt.dimensions.angular_momentum, "tot_energy": unyt.dimensions.energy,
            "energy_error": unyt.dimensions.energy}
    for name, dim in dims.items():
        check(hasattr(st, name) and getattr(st, name).units.dimensions == dim,
              "load_statistics: %s with dimension %s" % (name, dim))
    check(np.array_equal(st.step.value, [0, 1, 2, 3]), "one line per step, none twice: steps %s"
          % list(st.step.value))

    # 2. the t = 0 line against the t = 0 snapshot, in SI through unyt: the
    # snapshot's values times its /Units (h5py; to 1e-9), and swiftsimio's
    # load of it (to 1e-5: swiftsimio takes U_M = 5.9724e27 g for unyt's
    # Earth mass, 5.97237e24 kg, 5e-6 away)
    path = os.path.join(out, "snapshot_0000.hdf5")
    with h5py.File(path, "r") as f:
        U = f["Units"].attrs
        UM, UL, Ut = (float(U[k][0]) for k in ("Unit mass in cgs (U_M)", "Unit length in cgs (U_L)",
                                                 "Unit time in cgs (U_t)"))
        g = f["PartType0"]
        raw = (g["Masses"][...] * UM * 1e-3, g["Velocities"][...] * UL / Ut * 1e-2,
               g["Coordinates"][...] * UL * 1e-2, g["InternalEnergies"][...] * (UL / Ut) ** 2 * 1e-4)
    snap = swiftsimio.load(path)
    viasw = (snap.gas.masses.to("kg").value, snap.gas.velocities.to("m/s").value,
             snap.gas.coordinates.to("m").value, snap.gas.internal_energies.to("J/kg").value)
    for label, (m, vel, pos, u), tol in (("h5py", raw, 1e-9), ("swiftsimio", viasw, 1e-5)):
        ref = {"kin_energy": (0.5 * (m * (vel ** 2).sum(axis=1)).sum(), "J"),
               "int_energy": ((m * u).sum(), "J"),
               "total_mass": (m.sum(), "kg"),
               "mom_x": ((m * vel[:, 0]).sum(), "kg*m/s"),
               "mom_y": ((m * vel[:, 1]).sum(), "kg*m/s"),
               "ang_mom_z": ((m * (pos[:, 0] * vel[:, 1] - pos[:, 1] * vel[:, 0])).sum(), "kg*m**2/s")}
        for name, (value, unit) in ref.items():
            got = getattr(st, name)[0].to(unit).value
            check(abs(got - value) <= tol * abs(value), "%s(t=0) = %.9e %s (snapshot via %s: %.9e)"
                  % (name, got, unit, label, value))
    check(st.pot_energy[0].to("J").value < 0, "pot_energy(t=0) < 0 with self-gravity")
    check(st.time[0].to("s").value == 0 and st.time[-1].to("s").value > 0, "time in s")

    # 3. Bolide's own reader
    cols = bsnap.read_stats(os.path.join(out, "statistics.txt"))
    check("E_tot" in cols and np.allclose(cols["E_tot"], st.tot_energy.value),
          "tools/bolide_tools read_stats finds Bolide's names (E_tot)")

    # 4. the timesteps file
    ts = np.loadtxt(os.path.join(out, "timesteps.txt"), ndmin=2)
    check(ts.shape[0] == 3 and np.array_equal(ts[:, 0], [1, 2, 3]), "timesteps: one line per step")
    check(np.allclose(ts[:, 1], st.time.value[1:], rtol=1e-9), "timesteps: the times of the statistics")
    check(np.allclose(ts[:, 2], np.diff(st.time.value), rtol=1e-9), "timesteps: dt, the step from the time before")
    check(np.array_equal(ts[:, 3], np.full(3, 512)), "timesteps: updates, every one of the 512 particles per step")
    check(np.all(ts[:, 4] > 0), "timesteps: wall-clock time of each step > 0")

print("FAIL" if failures else "PASS")
sys.exit(1 if failures else 0)
