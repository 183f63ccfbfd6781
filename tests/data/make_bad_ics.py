"""Write small malformed initial-condition files, one per error that ic_read
must report, plus one valid file.  Usage: make_bad_ics.py OUTDIR

Each file name is CASE.hdf5; tests/program/test_ic_errors.sh runs the reader on it and
checks the one-line message."""
import os
import sys

import h5py
import numpy as np

N = 20


def good(n=N, seed=3, mass=0.05, h=0.1):
    """Arrays of a valid IC (SI) of n particles at random positions."""
    rng = np.random.default_rng(seed)
    return {
        "Coordinates": rng.random((n, 3)),
        "Velocities": rng.standard_normal((n, 3)),
        "Masses": np.full(n, mass),
        "SmoothingLengths": np.full(n, h),
        "InternalEnergies": np.full(n, 1e3),
        "Densities": np.full(n, 2700.0),
        "ParticleIDs": np.arange(1, n + 1, dtype=np.int64),
        "MaterialIDs": np.full(n, 101, dtype=np.int32),
    }


MANY = 600000


def _mix(z):
    """splitmix64's finaliser (Steele et al. 2014), on uint64 arrays."""
    with np.errstate(over="ignore"):
        z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


def position_hash_collisions(x):
    """Pairs of distinct positions that share the reader's 33-bit hash (the
    positions as read: the file's SI metres in units of 100 m, -0 as +0)."""
    b = [np.ascontiguousarray(x[:, k] / 100.0 + 0.0).view(np.uint64) for k in range(3)]
    key = _mix(b[0] ^ _mix(b[1] ^ _mix(b[2]))) >> np.uint64(31)
    _, counts = np.unique(key, return_counts=True)
    return int((counts * (counts - 1) // 2).sum())


def write(path, data, units=True, header=True, attrs=None):
    with h5py.File(path, "w") as f:
        if header:
            h = f.create_group("Header")
            h.attrs["BoxSize"] = [1.0, 1.0, 1.0]
            n = len(data["Coordinates"]) if "Coordinates" in data else N
            h.attrs["NumPart_Total"] = [n, 0, 0, 0, 0, 0]
            h.attrs["NumPart_Total_HighWord"] = [0] * 6
            h.attrs["Dimension"] = [3]
            for k, v in (attrs or {}).items():
                h.attrs[k] = v
        if units:
            u = f.create_group("Units")
            u.attrs["Unit mass in cgs (U_M)"] = [1000.0]
            u.attrs["Unit length in cgs (U_L)"] = [100.0]
            u.attrs["Unit time in cgs (U_t)"] = [1.0]
            u.attrs["Unit current in cgs (U_I)"] = [1.0]
            u.attrs["Unit temperature in cgs (U_T)"] = [1.0]
        g = f.create_group("PartType0")
        for k, v in data.items():
            g.create_dataset(k, data=v)


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    p = lambda name: os.path.join(out, name + ".hdf5")

    write(p("good"), good())

    d = good()
    d["Coordinates"][7, 1] = np.nan
    write(p("nan_position"), d)

    d = good()
    d["Masses"][5] = -1.0
    write(p("negative_mass"), d)

    d = good()
    d["SmoothingLengths"][9] = 0.0
    write(p("zero_h"), d)

    d = good()
    d["ParticleIDs"][12] = d["ParticleIDs"][3]
    write(p("duplicate_ids"), d)

    d = good()
    d["Masses"] = d["Masses"][:-1]
    write(p("mismatched_lengths"), d)

    d = good()
    del d["Masses"]
    write(p("missing_dataset"), d)

    d = good()
    d["MaterialIDs"][4] = 999
    write(p("unknown_material"), d)

    d = good()
    d["Velocities"] = d["Velocities"][:, :2]
    write(p("wrong_shape"), d)

    d = good()
    d["ParticleIDs"] = d["ParticleIDs"].astype(np.uint64)
    d["ParticleIDs"][2] = np.uint64(2**63 + 5)
    write(p("id_too_large"), d)

    d = good()
    d["MaterialIDs"] = d["MaterialIDs"].astype(np.int64)
    d["MaterialIDs"][6] = 2**40
    write(p("material_out_of_range"), d)

    d = good()
    d["MaterialIDs"] = d["MaterialIDs"].astype(np.float64)
    d["MaterialIDs"][8] = 101.5
    write(p("material_not_integer"), d)

    # another tool's conventions: singular aliases, float32, uint64 ids, no /Units
    d = good()
    alias = {
        "Coordinates": d["Coordinates"],
        "Velocities": d["Velocities"].astype(np.float32),
        "Mass": d["Masses"].astype(np.float32),
        "SmoothingLength": d["SmoothingLengths"].astype(np.float32),
        "InternalEnergy": d["InternalEnergies"].astype(np.float32),
        "Density": d["Densities"].astype(np.float32),
        "ParticleIDs": d["ParticleIDs"].astype(np.uint64),
        "MaterialID": d["MaterialIDs"].astype(np.int16),
    }
    write(p("aliases_no_units"), alias, units=False)

    # hostile values (issue 18)
    d = good()
    d["InternalEnergies"][4] = -1.0
    write(p("negative_u"), d)

    d = good()
    d["Densities"][2] = -2700.0
    write(p("negative_density"), d)

    d = good()
    d["Damage"] = np.zeros(N)
    d["Damage"][11] = 1.5
    write(p("damage_above_one"), d)

    d = good()
    d["ShearDamage"] = np.zeros(N)
    d["ShearDamage"][1] = -0.25
    write(p("shear_damage_negative"), d)

    write(p("numpart_minus_one"), good(), attrs={"NumPart_Total": [-1, 0, 0, 0, 0, 0]})
    write(p("nan_time"), good(), attrs={"Time": [np.nan]})
    write(p("inf_box"), good(), attrs={"BoxSize": [1.0, np.inf, 1.0]})

    write(p("zero_particles"), {k: v[:0] for k, v in good().items()})

    d = good()
    d["Coordinates"][:] = 0.5
    write(p("one_point"), d)

    d = good()
    d["Coordinates"][13] = d["Coordinates"][6]
    write(p("same_position"), d)

    # many particles, some of which share the reader's 33-bit hash of their
    # position (ic_check_distinct_positions) without sharing the position:
    # the file loads; with one true duplicate among them, that pair is named
    d = good(MANY, seed=5, mass=1e-6, h=0.01)
    assert position_hash_collisions(d["Coordinates"]) > 0
    write(p("many_hash_collisions"), d)
    d["Coordinates"][400000] = d["Coordinates"][123456]
    write(p("many_same_position"), d)

    with open(p("not_hdf5"), "w") as f:
        f.write("this is not an HDF5 file\n")


if __name__ == "__main__":
    main()
