#!/usr/bin/env python3
"""Write equation-of-state tables from an analytic EOS, in the file formats
that Bolide reads, for tests and for trying a set-up without the real tables.

The real tables cannot be generated here: SWIFT's planetary tables (ANEOS
forsterite, iron, Fe85Si15; SESAME; AQUA; CMS19; CD21) come with SWIFT
(examples/Planetary/EoSTables/get_eos_tables.sh) and with woma; README.md
says where.  This script writes tables of the same layout from an analytic
EOS, so that the readers can be tested against the formula.

Formats:
  swift   SWIFT's planetary (SESAME-like) layout, material ids 300-307,
          400-402, 900-909: 12 header lines, the version date, N_RHO N_T,
          the densities, the temperatures, then "u P c s" for every (rho, T)
          with rho varying fastest; SI.
  rho_T   Bolide's own: first line N_RHO N_T, then rows "rho T u P c"
          (rho varying slowest).
  miluphcuda
          miluphcuda's ANEOS lookup tables (its material.cfg: eos.type = 7,
          eos.table_path, eos.n_rho, eos.n_e): 3 header lines, then one row
          "rho e P T cs s phase_flag" for every (rho, e) node, e varying
          fastest (rho slowest); SI.  The nodes are on (rho, e), not (rho, T):
          --u gives the energy range, --n N_RHO N_E, --spacing the spacing
          of both axes: log (default), linear, or irregular (log-spaced
          nodes each moved by up to 30% of their spacing, --seed; miluphcuda
          takes any increasing axes).

EOS (SI):
  ideal_gas  P = (gamma - 1) rho u, u = c_v T, c^2 = gamma (gamma - 1) u

Usage:
  eos_tables.py --eos ideal_gas --format swift -o table.txt
  eos_tables.py --format rho_T --rho 100 20000 --T 10 1e5 --n 32 48 -o t.txt
  eos_tables.py --format miluphcuda --rho 1 1e4 --u 1e4 1e8 --n 40 50 -o aneos.table
  eos_tables.py --format miluphcuda --spacing linear --rho 1e3 1e4 --u 1e6 1e7 -o lin.table
As a module: ideal_gas(rho, u), evaluate(...), axis(...), write_swift(...),
write_rho_T(...), write_miluphcuda(...)."""
import argparse
import sys

import numpy as np

def ideal_gas(rho, u, gamma=5.0 / 3.0):
    """Pressure and sound speed of the ideal gas."""
    rho, u = np.asarray(rho, float), np.asarray(u, float)
    return (gamma - 1.0) * rho * u, np.sqrt(gamma * (gamma - 1.0) * np.maximum(u, 0.0))


def evaluate(eos, rho, T, gamma=5.0 / 3.0, cv=None):
    """u, P, c on the (rho, T) nodes (arrays of shape (n_rho, n_T))."""
    R, TT = np.meshgrid(rho, T, indexing="ij")
    if eos != "ideal_gas":
        raise ValueError("unknown EOS %r" % eos)
    cv = 1000.0 if cv is None else cv
    U = cv * TT
    P, c = ideal_gas(R, U, gamma)
    s = cv * np.log(np.maximum(TT, 1e-300))  # an entropy-like column (not read by Bolide)
    return R, TT, U, P, c, s


def axis(lo, hi, n, spacing="log", seed=1):
    """n strictly increasing nodes from lo to hi: log-spaced, linearly
    spaced, or irregular (log-spaced with the interior nodes moved by up to
    30% of the spacing in ln, from a seeded generator)."""
    if spacing == "linear":
        return np.linspace(lo, hi, n)
    x = np.geomspace(lo, hi, n)
    if spacing == "irregular" and n > 2:
        h = np.log(hi / lo) / (n - 1)
        rng = np.random.default_rng(seed)
        x[1:-1] = np.exp(np.log(x[1:-1]) + rng.uniform(-0.3, 0.3, n - 2) * h)
    elif spacing != "log":
        raise ValueError("unknown spacing %r" % spacing)
    return x


def write_swift(path, rho, T, U, P, c, s, title="analytic EOS"):
    """SWIFT's planetary table layout (see the module docstring)."""
    with open(path, "w") as f:
        header = ["# Bolide tools/eos_tables.py: %s, in the layout of SWIFT's planetary tables" % title,
                  "# (SESAME-like; written from a formula, for tests: not a real material table)",
                  "# version_date", "# num_rho  num_T", "# rho[0] ... rho[num_rho-1]  (kg/m^3)",
                  "# T[0] ... T[num_T-1]  (K)", "# u  P  c  s  for every (rho, T), rho fastest",
                  "#   (J/kg, Pa, m/s, J/K/kg)", "#", "#", "#", "#"]
        assert len(header) == 12
        f.write("\n".join(header) + "\n")
        f.write("20220714\n%d %d\n" % (len(rho), len(T)))
        f.write(" ".join("%.9e" % x for x in rho) + "\n")
        f.write(" ".join("%.9e" % x for x in T) + "\n")
        for j in range(len(T)):
            for i in range(len(rho)):
                f.write("%.9e %.9e %.9e %.9e\n" % (U[i, j], P[i, j], c[i, j], s[i, j]))


def write_rho_T(path, rho, T, U, P, c):
    """Bolide's rho_T layout: N_RHO N_T, then rows rho T u P c."""
    with open(path, "w") as f:
        f.write("%d %d\n" % (len(rho), len(T)))
        for i in range(len(rho)):
            for j in range(len(T)):
                f.write("%.12e %.12e %.12e %.12e %.12e\n" % (rho[i], T[j], U[i, j], P[i, j], c[i, j]))


def write_miluphcuda(path, rho, e, gamma=5.0 / 3.0, cv=None, title="ideal_gas"):
    """miluphcuda's ANEOS table layout (see the module docstring) of the
    ideal gas on the (rho, e) nodes; the phase flag is 1 (one phase)."""
    cv = 1000.0 if cv is None else cv
    with open(path, "w") as f:
        f.write("# Bolide tools/eos_tables.py: %s, in the layout of miluphcuda's ANEOS tables "
                "(written from a formula, for tests: not a real material table)\n" % title)
        f.write("# n_rho = %d  n_e = %d  (rows: rho slowest, e fastest)\n" % (len(rho), len(e)))
        f.write("# rho [kg/m^3]  e [J/kg]  P [Pa]  T [K]  cs [m/s]  s [J/kg/K]  phase_flag\n")
        for r in rho:
            P, c = ideal_gas(r, e, gamma)
            T = e / cv
            s = cv * np.log(np.maximum(T, 1e-300))
            for j in range(len(e)):
                f.write("%.9e %.9e %.9e %.9e %.9e %.9e %d\n" % (r, e[j], P[j], T[j], c[j], s[j], 1))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--eos", choices=["ideal_gas"], default="ideal_gas")
    ap.add_argument("--format", choices=["swift", "rho_T", "miluphcuda"], default="swift")
    ap.add_argument("--rho", nargs=2, type=float, default=[1.0, 1e4], metavar=("MIN", "MAX"),
                    help="density range, kg/m^3 (log-spaced)")
    ap.add_argument("--T", nargs=2, type=float, default=[10.0, 1e5], metavar=("MIN", "MAX"),
                    help="temperature range, K (log-spaced)")
    ap.add_argument("--u", nargs=2, type=float, default=[1e4, 1e8], metavar=("MIN", "MAX"),
                    help="specific energy range of format miluphcuda, J/kg (log-spaced)")
    ap.add_argument("--n", nargs=2, type=int, default=[64, 64], metavar=("N_RHO", "N_T"),
                    help="node counts (N_RHO N_E for format miluphcuda)")
    ap.add_argument("--spacing", choices=["log", "linear", "irregular"], default="log",
                    help="node spacing of both axes of format miluphcuda (default log)")
    ap.add_argument("--seed", type=int, default=1, help="seed of --spacing irregular")
    ap.add_argument("--gamma", type=float, default=5.0 / 3.0, help="ideal gas gamma")
    ap.add_argument("--cv", type=float, default=None, help="c_v, J/kg/K")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args(argv)
    if min(a.n) < 2 or a.rho[0] <= 0 or a.T[0] <= 0 or a.rho[1] <= a.rho[0] or a.T[1] <= a.T[0]:
        sys.exit("eos_tables.py: error: ranges must be positive and increasing, at least 2 nodes")
    if a.spacing != "log" and a.format != "miluphcuda":
        sys.exit("eos_tables.py: error: --spacing %s: only format miluphcuda takes axes that "
                 "are not log-spaced" % a.spacing)
    rho = axis(a.rho[0], a.rho[1], a.n[0], a.spacing, a.seed)
    if a.format == "miluphcuda":
        if a.u[0] <= 0 or a.u[1] <= a.u[0]:
            sys.exit("eos_tables.py: error: the energy range must be positive and increasing")
        e = axis(a.u[0], a.u[1], a.n[1], a.spacing, a.seed + 1)
        write_miluphcuda(a.output, rho, e, a.gamma, a.cv, a.eos)
        return
    T = np.geomspace(a.T[0], a.T[1], a.n[1])
    R, TT, U, P, c, s = evaluate(a.eos, rho, T, a.gamma, a.cv)
    if a.format == "swift":
        write_swift(a.output, rho, T, U, P, c, s, a.eos)
    else:
        write_rho_T(a.output, rho, T, U, P, c)


if __name__ == "__main__":
    main()
