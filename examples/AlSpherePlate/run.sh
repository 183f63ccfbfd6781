#!/usr/bin/env bash
# Aluminium sphere on a plate (Hiermaier et al. 1997): initial conditions,
# run, hole diameter and debris-cloud length/width, picture plate.png.
# Usage: ./run.sh [DX] [THREADS]  (lattice spacing in m, default 0.0008:
# 5 layers through the plate, 52,069 particles, to 20 us: about 6 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
dx=${1:-0.0008}
threads=${2:-2}
"$python" make_ic.py --dx "$dx" -o plate.hdf5
"$build/bolide" -t "$threads" params.yml
"$python" analyse.py --dx "$dx" --out plate.png output
