#!/usr/bin/env bash
# Prater crater: initial conditions, run, crater depth and diameter over
# time, picture crater.png.
# Usage: ./run.sh [DX] [THREADS]  (lattice spacing in m, default 0.0025:
# a 12 x 12 x 8 cm block and a projectile of 81 particles, 76,913 particles,
# about 10 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
dx=${1:-0.0025}
threads=${2:-2}
"$python" make_ic.py --dx "$dx" --half-width 0.06 --depth 0.08 -o crater.hdf5
"$build/bolide" -t "$threads" params.yml
"$python" crater.py --dx "$dx" --out crater.png output
