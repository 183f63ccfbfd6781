#!/usr/bin/env python3
"""Initial conditions of the graded plate impact (issue 24 item 6;
Eghtesad & Knezevic 2018, Comp. Part. Mech. 5, 387): an Al 6061-T6 sphere
at 1000 m/s, normal incidence, onto a steel 4340 plate, the plate from a
uniform or a graded node set imported by `bolide-ic import-mesh`.

The plate (a square of half-width --half-width, --thick thick, front face
at z = 0) is written as a plain node file "id x y z volume", then turned
into particles by `bolide-ic import-mesh` (mass = rho0 V, h = eta V^(1/3)),
the way a graded finite-element mesh would be.  Two node sets:

  uniform  a cubic lattice of spacing dx (cell centres);
  graded   the plate is tiled with blocks of 2 dx: a block whose centre is
           within --fine-radius of the axis holds the 8 nodes of spacing dx
           (as the uniform lattice), every other block one node of spacing
           2 dx at its centre (volume 8 dx^3).  The fine region is a
           cylinder through the whole thickness under the impact point;
           the size jump is 2, the one tests/physics/test_h_evolution.py
           checks.

Both node sets tile the plate exactly (the volumes sum to its volume), and
the fine nodes of the graded set are nodes of the uniform one, so the
crater region starts identical in both.  The sphere (diameter --diameter,
one lattice of spacing dx, masses scaled to the true sphere's mass) is
added by this script, one spacing above the plate, with material id 1;
the plate has id 0.  The box is the one import-mesh chooses (open).

Usage: make_ic.py uniform|graded [--dx 0.001] [-o plate.hdf5]
       [--bolide-ic ../../_build/bolide-ic]   (SI units)"""
import argparse
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import ichelpers  # noqa: E402  (examples/common/ichelpers.py)

sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from bolide import snapshot  # noqa: E402  (python/bolide, unless the package is installed)

RHO_PLATE = 7830.0  # steel_4340 (examples/materials.yml)
RHO_SPHERE = 2710.0  # aluminium_6061


def plate_nodes(kind, dx, half_width, thick, r_fine):
    """Node positions and volumes of the plate (front face z = 0)."""
    nb = int(round(half_width / dx / 2))  # blocks of 2 dx per half-width
    nz = int(round(thick / dx / 2))  # blocks through the thickness
    if 2 * nz * dx != thick and abs(2 * nz * dx - thick) > 1e-9 * thick:
        raise SystemExit(f"make_ic.py: error: thickness {thick} m is not an even number of spacings {dx} m")
    b = (np.arange(-nb, nb) + 0.5) * 2 * dx
    bz = -(np.arange(nz) + 0.5) * 2 * dx
    bx, by, bzz = np.meshgrid(b, b, bz, indexing="ij")
    c = np.stack([bx.ravel(), by.ravel(), bzz.ravel()], axis=1)  # block centres
    sub = np.array([[i, j, k] for i in (-0.5, 0.5) for j in (-0.5, 0.5) for k in (-0.5, 0.5)]) * dx
    if kind == "uniform":
        fine = np.ones(len(c), dtype=bool)
    else:
        fine = np.hypot(c[:, 0], c[:, 1]) < r_fine
    xf = (c[fine, None, :] + sub[None, :, :]).reshape(-1, 3)
    xc = c[~fine]
    x = np.concatenate([xf, xc])
    V = np.concatenate([np.full(len(xf), dx**3), np.full(len(xc), 8 * dx**3)])
    return x, V


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("kind", choices=("uniform", "graded"))
    ap.add_argument("--dx", type=float, default=0.001, help="fine spacing [m]")
    ap.add_argument("--half-width", type=float, default=0.03, help="half-width of the plate [m]")
    ap.add_argument("--thick", type=float, default=0.006, help="plate thickness [m] (an even number of dx)")
    ap.add_argument("--fine-radius", type=float, default=0.0165,
                    help="graded: radius of the fine cylinder under the impact point [m]")
    ap.add_argument("--diameter", type=float, default=0.01, help="sphere diameter [m]")
    ap.add_argument("--speed", type=float, default=1000.0, help="impact speed [m/s]")
    ap.add_argument("--eta", type=float, default=1.7, help="h = eta V^(1/3) (SPH:resolution_eta)")
    ap.add_argument("--bolide-ic", default=os.path.join("..", "..", "_build", "bolide-ic"))
    ap.add_argument("-o", "--output", default="plate.hdf5")
    a = ap.parse_args()
    dx = a.dx
    x, V = plate_nodes(a.kind, dx, a.half_width, a.thick, a.fine_radius)
    nodes = os.path.splitext(a.output)[0] + ".nodes"
    with open(nodes, "w") as f:
        f.write(f"# {a.kind} steel plate, {len(x)} nodes: id x y z volume [m, m^3] (make_ic.py)\n")
        for i, (p, v) in enumerate(zip(x, V)):
            f.write(f"{i + 1} {p[0]:.9e} {p[1]:.9e} {p[2]:.9e} {v:.9e}\n")
    plate = os.path.splitext(a.output)[0] + "_plate.hdf5"
    subprocess.run([a.bolide_ic, "import-mesh", nodes, "--rho", str(RHO_PLATE), "--mat", "0",
                    "--eta", str(a.eta), "-o", plate], check=True, stdout=subprocess.DEVNULL)
    # the file import-mesh wrote, in the units it was given (SI): no conversion
    p = snapshot.load(plate)
    box = p["header"]["BoxSize"]
    # import-mesh shifted the nodes (ids 1..N in file order): recover the shift
    order = np.argsort(p["ParticleIDs"])
    shift = p["Coordinates"][order[0]] - x[0]
    np_ = len(x)
    r = 0.5 * a.diameter
    pj = ichelpers.lattice_ball(r, dx, 0.5 * dx)
    pj[:, 2] += r + dx
    n1 = len(pj)
    m1 = ichelpers.sphere_particle_mass(RHO_SPHERE, r, n1)
    fields = {
        "Coordinates": np.concatenate([p["Coordinates"], pj + shift]),
        "Velocities": np.concatenate([p["Velocities"], np.tile([0.0, 0.0, -a.speed], (n1, 1))]),
        "Masses": np.concatenate([p["Masses"], np.full(n1, m1)]),
        "SmoothingLengths": np.concatenate([p["SmoothingLengths"], np.full(n1, a.eta * (m1 / RHO_SPHERE) ** (1 / 3))]),
        "InternalEnergies": np.concatenate([p["InternalEnergies"], np.zeros(n1)]),
        "Densities": np.concatenate([p["Densities"], np.full(n1, RHO_SPHERE)]),
        "ParticleIDs": np.concatenate([p["ParticleIDs"], np_ + 1 + np.arange(n1)]),
        "MaterialIDs": np.concatenate([p["MaterialIDs"], np.ones(n1, dtype=p["MaterialIDs"].dtype)]),
    }
    # the impact point (the axis on the front face) in the file's coordinates
    origin = shift
    ichelpers.write_ic(a.output, box, fields, header={"ImpactPoint": origin})
    os.remove(plate)
    print(f"{a.output}: {np_ + n1} particles ({np_} plate, {int((V > 1.5 * dx**3).sum())} of them coarse; "
          f"{n1} sphere), {a.kind}, dx = {dx} m, plate {2 * a.half_width * 100:.0f} x "
          f"{2 * a.half_width * 100:.0f} x {a.thick * 100:.1f} cm")


if __name__ == "__main__":
    main()
