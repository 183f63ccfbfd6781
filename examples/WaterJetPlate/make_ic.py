#!/usr/bin/env python3
"""Initial conditions of the water jet on a thin plate (issue 24 item 6;
the fluid-structure impacts of Eghtesad & Knezevic 2018, Comp. Part. Mech.
5, 387): a cylinder of water (the `water_wc` library entry, rho0 = 1000
kg/m^3) of diameter --diameter and length --length moving at --speed along
-z onto an Al 6061-T6 plate (`aluminium_6061`, rho0 = 2710 kg/m^3) of
half-width --half-width and thickness --thick, front face at z = 0.

Both bodies are cut from one cubic lattice of spacing dx (cell centres):
the plate's top layer is at z = -dx/2 and the jet's lowest layer at
+dx/2, so fluid and solid start one spacing apart, the gap the interface
treatment keeps (theory/fluids.md, "Fluid-solid interface").  rho = rho0,
u = 0, h = eta dx.  Material ids: 0 plate, 1 water.

Usage: make_ic.py [--dx 0.0005] [-o jet.hdf5]  (SI units; an example input,
not part of bolide-ic)."""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import ichelpers  # noqa: E402  (examples/common/ichelpers.py)

RHO_PLATE = 2710.0
RHO_WATER = 1000.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dx", type=float, default=0.0005, help="lattice spacing [m]")
    ap.add_argument("--half-width", type=float, default=0.012, help="half-width of the plate [m]")
    ap.add_argument("--thick", type=float, default=0.002, help="plate thickness [m]")
    ap.add_argument("--diameter", type=float, default=0.004, help="jet diameter [m]")
    ap.add_argument("--length", type=float, default=0.008, help="jet length [m]")
    ap.add_argument("--speed", type=float, default=500.0, help="jet speed [m/s]")
    ap.add_argument("--eta", type=float, default=1.7, help="h = eta dx (SPH:resolution_eta)")
    ap.add_argument("-o", "--output", default="jet.hdf5")
    a = ap.parse_args()
    dx = a.dx
    nw = int(round(a.half_width / dx))
    nl = int(round(a.thick / dx))
    plate = ichelpers.lattice((-nw, -nw, -nl), (nw - 1, nw - 1, -1), dx) + 0.5 * dx
    nr = int(np.ceil(0.5 * a.diameter / dx))
    nj = int(round(a.length / dx))
    jet = ichelpers.lattice((-nr, -nr, 0), (nr - 1, nr - 1, nj - 1), dx) + 0.5 * dx
    jet = jet[np.hypot(jet[:, 0], jet[:, 1]) < 0.5 * a.diameter]
    n0, n1 = len(plate), len(jet)
    pos = np.concatenate([plate, jet])
    vel = np.zeros_like(pos)
    vel[n0:, 2] = -a.speed
    rho = np.r_[np.full(n0, RHO_PLATE), np.full(n1, RHO_WATER)]
    span = 2 * a.half_width + 0.02
    box = np.array([span, span, a.length + a.thick + 0.03])
    shift = np.array([0.5 * span, 0.5 * span, a.thick + 0.01])
    fields = {
        "Coordinates": pos + shift,
        "Velocities": vel,
        "Masses": rho * dx**3,
        "SmoothingLengths": np.full(n0 + n1, a.eta * dx),
        "InternalEnergies": np.zeros(n0 + n1),
        "Densities": rho,
        "ParticleIDs": np.arange(1, n0 + n1 + 1),
        "MaterialIDs": np.r_[np.zeros(n0, dtype=np.int32), np.ones(n1, dtype=np.int32)],
    }
    ichelpers.write_ic(a.output, box, fields)
    print(f"{a.output}: {n0 + n1} particles ({n0} plate, {n1} water), dx = {dx} m, {nl} layers through the "
          f"plate, jet {a.diameter * 1e3:.1f} x {a.length * 1e3:.1f} mm at {a.speed:.0f} m/s")


if __name__ == "__main__":
    main()
