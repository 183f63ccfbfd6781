#!/usr/bin/env python3
"""Bad boundary input stops bolide with exit status 1 and one line on stderr
naming the file and the key (theory/boundaries.md): a plane given by other
than six numbers, a zero normal, a boundary flag that is not a boolean, a
moving fixed boundary particle, mirror ghosts that would fall outside the
box, and mirror ghosts with self-gravity, time bins or restart files (not
supported yet); the rk2 and pc integrators with time bins, and an unknown
integrator (TimeIntegration:scheme).  A valid run with both kinds of boundary is checked to
succeed, so that every failure below is the input's."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

build = os.environ.get("BOLIDE_BUILDDIR", ".")
bolide = os.path.join(build, "bolide")

BASE = """InitialConditions: {{file_name: ic.hdf5, periodic: false}}
TimeIntegration: {{time_end: 1e-3}}
Snapshots: {{subdir: out}}
SPH: {{density: continuity}}
{extra}
Materials:
  0: {{name: water, eos: liquid, rho0: 1.0, c0: 10.0}}
  1: {{name: wall, eos: liquid, rho0: 1.0, c0: 10.0, boundary: {flag}}}
"""


def make_ic(path, v_wall=0.0, x0=2.0):
    g = (np.arange(6) + 0.5) * 0.1 + 2.0
    x, y, z = np.meshgrid(g - 2.0 + x0, g, g, indexing="ij")
    pos = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    N = len(pos)
    vel = np.zeros_like(pos)
    mat = (pos[:, 2] < 2.2).astype(np.int32)
    vel[mat == 1, 0] = v_wall
    with h5py.File(path, "w") as f:
        h = f.create_group("Header")
        h.attrs["BoxSize"] = [5.0, 5.0, 5.0]
        h.attrs["NumPart_Total"] = [N, 0, 0, 0, 0, 0]
        h.attrs["Dimension"] = 3
        p = f.create_group("PartType0")
        p["Coordinates"] = pos
        p["Velocities"] = vel
        p["Masses"] = np.full(N, 1e-3)
        p["SmoothingLengths"] = np.full(N, 0.17)
        p["InternalEnergies"] = np.zeros(N)
        p["Densities"] = np.ones(N)
        p["ParticleIDs"] = np.arange(1, N + 1)
        p["MaterialIDs"] = mat


def run(d, name, extra="", flag="true"):
    with open(os.path.join(d, f"{name}.yml"), "w") as f:
        f.write(BASE.format(extra=extra, flag=flag))
    return subprocess.run([bolide, "-t", "1", "-n", "2", f"{name}.yml"], cwd=d,
                          capture_output=True, text=True)


def main():
    fails = 0
    cases = [
        ("five", "Boundaries: {planes: [0, 0, 1, 0, 0]}", "true", "ic.hdf5",
         ["five.yml", "Boundaries:planes"]),
        ("zero_normal", "Boundaries: {planes: [0, 0, 1, 0, 0, 0]}", "true", "ic.hdf5",
         ["zero_normal.yml", "Boundaries:planes", "plane 1", "non-zero"]),
        ("flag", "", "maybe", "ic.hdf5", ["flag.yml", "boundary", "true or false", "maybe"]),
        ("moving", "", "true", "moving.hdf5", ["moving.hdf5", "fixed boundary particle", "at rest"]),
        ("outside", "Boundaries: {planes: [0.05, 0, 0, 1, 0, 0]}", "true", "shifted.hdf5",
         ["outside.yml", "Boundaries:planes", "outside the box"]),
        ("gravity", "Boundaries: {planes: [0, 0, 2.0, 0, 0, 1]}\nGravity: {enabled: true, softening: 0.01}",
         "true", "ic.hdf5", ["gravity.yml", "Boundaries:planes", "self-gravity"]),
        ("bins", "Boundaries: {planes: [0, 0, 2.0, 0, 0, 1]}\n"
         "TimeIntegration: {time_end: 1e-3, global_step: false}", "true", "ic.hdf5",
         ["bins.yml", "Boundaries:planes", "global time step"]),
        ("restarts", "Boundaries: {planes: [0, 0, 2.0, 0, 0, 1]}\nRestarts: {enable: true}",
         "true", "ic.hdf5", ["restarts.yml", "Boundaries:planes", "restart"]),
        # the integrators (theory/integrators.md): rk2 and pc not with time
        # bins; an unknown scheme
        ("pc_bins", "TimeIntegration: {time_end: 1e-3, scheme: pc, global_step: false}", "true", "ic.hdf5",
         ["pc_bins.yml", "TimeIntegration:scheme", "global_step"]),
        ("rk4", "TimeIntegration: {time_end: 1e-3, scheme: rk4}", "true", "ic.hdf5",
         ["rk4.yml", "TimeIntegration:scheme", "rk4", "kdk, rk2, pc"]),
    ]
    with tempfile.TemporaryDirectory() as d:
        make_ic(os.path.join(d, "ic.hdf5"))
        make_ic(os.path.join(d, "moving.hdf5"), v_wall=1.0)
        make_ic(os.path.join(d, "shifted.hdf5"), x0=0.1)
        r = run(d, "valid", "Boundaries: {planes: [0, 0, 2.0, 0, 0, 1], slip: no_slip}")
        if r.returncode != 0:
            print("FAIL: the valid run failed:", r.stderr[-1000:])
            fails += 1
        else:
            print("ok: a run with a fixed wall and a mirror plane")
        for name, extra, flag, ic, wants in cases:
            if "TimeIntegration" in extra:
                text = BASE.replace("TimeIntegration: {{time_end: 1e-3}}\n", "")
            else:
                text = BASE
            text = text.replace("ic.hdf5", ic)
            with open(os.path.join(d, f"{name}.yml"), "w") as f:
                f.write(text.format(extra=extra, flag=flag))
            r = subprocess.run([bolide, "-t", "1", "-n", "2", f"{name}.yml"], cwd=d,
                               capture_output=True, text=True)
            lines = [l for l in r.stderr.splitlines() if l.strip()]
            err = [l for l in lines if "error:" in l]
            if r.returncode != 1 or len(err) != 1 or not err[0].startswith("bolide: error:"):
                print(f"FAIL: {name}: status {r.returncode}, stderr: {r.stderr[-800:]}")
                fails += 1
                continue
            missing = [w for w in wants if w not in err[0]]
            if missing:
                print(f"FAIL: {name}: {missing} missing in: {err[0]}")
                fails += 1
            else:
                print(f"ok: {name}: {err[0]}")
    print("PASS" if not fails else "FAIL")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
