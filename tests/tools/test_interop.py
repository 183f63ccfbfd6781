"""Interoperability with the planetary Python tools.

1. An initial condition written by woma's SWIFT-format writer
   (woma.misc.io.save_particle_data: float32 datasets, uint64 ids, alias
   links, units of Earth mass and radius) from a SEAGen sphere of Tillotson
   granite loads with Bolide's ic_read (tests/helpers/ic_dump) and gives the right
   count, SI values and material ids.
2. A Bolide snapshot written from it opens with swiftsimio.load(), and
   swiftsimio's fields carry the values and units h5py reads.

woma.Planet's profile solver is not used: its JIT compilation alone takes
~20 s; the file format, which is what is tested, is the same."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

try:
    import seagen
    import swiftsimio
    import unyt
    import woma.misc.io as wio
    from woma.misc.utils import Conversions
except ImportError as e:  # the venv lacks a package: skip
    print("skip:", e)
    sys.exit(77)

build = os.environ["BOLIDE_BUILDDIR"]
dump = os.path.join(build, "tests", "helpers", "ic_dump")
failures = []


def check(cond, msg):
    if not cond:
        failures.append(msg)
        print("FAIL", msg)


def run_dump(*args):
    out = subprocess.run([dump, *args], check=True, capture_output=True, text=True).stdout
    return {l.split()[0]: l.split()[1:] for l in out.splitlines() if not l.startswith("[")}


M_E, R_E = 5.9722e24, 6.371e6
mat_granite = 301  # woma's id of Til_granite

with tempfile.TemporaryDirectory() as tmp:
    # -------------------------------------------------------------- woma IC
    R = 0.1 * R_E
    A1_r = np.linspace(R / 200, R, 200)
    A1_rho = np.full_like(A1_r, 2700.0)
    sphere = seagen.GenSphere(3000, A1_r, A1_rho, verbosity=0, seed=1)
    n = len(sphere.A1_m)
    pos = np.stack([sphere.A1_x, sphere.A1_y, sphere.A1_z], axis=1)
    rng = np.random.default_rng(2)
    vel = rng.standard_normal((n, 3)) * 100.0
    h = np.cbrt(sphere.A1_m / 2700.0) * 1.2348
    u = np.full(n, 1e5)
    P = np.full(n, 1e8)
    rho = np.full(n, 2700.0)
    mat = np.full(n, mat_granite)
    ic = os.path.join(tmp, "woma_ic.hdf5")
    file_to_SI = Conversions(M_E, R_E, 1.0)  # file in Earth masses and radii
    with h5py.File(ic, "w") as f:
        wio.save_particle_data(f, pos, vel, sphere.A1_m, h, rho, P, u, mat,
                               boxsize=4 * R, file_to_SI=file_to_SI, verbosity=0)

    res = run_dump(ic, "--mat", f"100,{mat_granite},400")
    check(int(res["count"][0]) == n, f"count {res['count']} != {n}")
    with h5py.File(ic, "r") as f:
        # what ic_read must produce: the file's values times the unit factor
        m_file = f["PartType0/Masses"][:].astype(np.float64)
        m_si = m_file * M_E
        pos_si = f["PartType0/Coordinates"][:] * R_E
    mtot = float(res["mass_total"][0])
    check(abs(mtot - m_si.sum()) <= 1e-12 * m_si.sum(), f"mass {mtot} != {m_si.sum()}")
    check(abs(mtot - sphere.A1_m.sum()) <= 1e-6 * mtot, "mass differs from SEAGen's")
    box = [float(x) for x in res["box"]]
    check(np.allclose(box, 4 * R, rtol=1e-12), f"box {box} != {4 * R}")
    check(int(res["periodic"][0]) == 0, "woma's PeriodicBoundariesOn=0 not read")
    check(res["fields"] == "x y z m h rho mat vx vy vz u id".split(), f"fields {res['fields']}")

    # ------------------------------------------ Bolide snapshot in swiftsimio
    snap = os.path.join(tmp, "snap_0000.hdf5")
    run_dump(ic, "--write", snap, "--acc")
    data = swiftsimio.load(snap)
    with h5py.File(snap, "r") as f:
        raw = {k: f["PartType0/" + k][:] for k in f["PartType0"]}
    check(data.metadata.n_gas == n, f"swiftsimio n_gas {data.metadata.n_gas}")
    check(np.allclose(data.metadata.boxsize.to("m").value, 4 * R, rtol=1e-12), "boxsize")
    pairs = [
        (data.gas.coordinates, "Coordinates", "m"),
        (data.gas.velocities, "Velocities", "m/s"),
        (data.gas.masses, "Masses", "kg"),
        (data.gas.smoothing_lengths, "SmoothingLengths", "m"),
        (data.gas.densities, "Densities", "kg/m**3"),
        (data.gas.internal_energies, "InternalEnergies", "J/kg"),
        (data.gas.pressures, "Pressures", "Pa"),
        (data.gas.accelerations, "Accelerations", "m/s**2"),
        (data.gas.potentials, "Potentials", "J/kg"),
    ]
    for arr, name, unit in pairs:
        v = arr.to(unit).value
        check(np.allclose(v, raw[name], rtol=1e-13, atol=0), f"{name} in {unit} differs from h5py")
        check(arr.units.dimensions == unyt.Unit(unit).dimensions, f"{name}: units {arr.units}")
    check(np.array_equal(data.gas.particle_ids.value, raw["ParticleIDs"]), "ids")
    check(np.array_equal(data.gas.material_ids.value, raw["MaterialIDs"]), "material ids")
    check(np.all(raw["MaterialIDs"] == mat_granite), "material ids changed")
    # positions survive woma -> Bolide -> swiftsimio (woma stores them as doubles)
    check(np.allclose(data.gas.coordinates.to("m").value, pos_si, rtol=1e-15, atol=0),
          "coordinates differ from woma's file")
    check(data.metadata.parameters.get("MetaData:run_name") in (b"ic_dump", "ic_dump"),
          f"/Parameters MetaData:run_name = {data.metadata.parameters.get('MetaData:run_name')}")

print("FAIL" if failures else "PASS")
sys.exit(1 if failures else 0)
