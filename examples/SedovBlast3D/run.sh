#!/usr/bin/env bash
# Sedov-Taylor blast: initial conditions, run, plot against the similarity solution.
# Usage: ./run.sh [N]   (N: lattice cells along a side; default 32, 32768 particles)
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
n=${1:-32}
"$build/bolide-ic" sedov --n "$n" --energy 1 --rho 1 -o sedov.hdf5
"$build/bolide" params.yml
./plot.sh sedov_0002.hdf5
