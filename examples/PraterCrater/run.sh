#!/usr/bin/env bash
# Prater crater: initial conditions, run, crater depth and diameter over
# time, picture crater.png.
# Usage: ./run.sh [DX] [THREADS]  (lattice spacing in m, default 0.00127:
# r/dx = 2.5 for the 6.35 mm diameter projectile, a 6 x 6 x 4 cm block,
# 74,512 particles, to 50 us)
# PARAMS (optional): another parameter file (a material variant, README.md);
# BOLIDE_ARGS (optional): more bolide options.
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
dx=${1:-0.00127}
threads=${2:-2}
"$python" make_ic.py --dx "$dx" --half-width 0.03 --depth 0.04 -o crater.hdf5
# shellcheck disable=SC2086
"$build/bolide" -t "$threads" ${BOLIDE_ARGS:-} "${PARAMS:-params.yml}"
"$python" crater.py --dx "$dx" --out crater.png output
