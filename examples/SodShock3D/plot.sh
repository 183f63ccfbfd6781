#!/usr/bin/env bash
# Sod shock tube: the last snapshot against the exact Riemann solution
# (tools/plot_sod.py); prints the L1 errors and the star state.
# Usage: ./plot.sh [SNAPSHOT]   (default sod_0002.hdf5, t = 0.2; run.sh first)
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
"$python" $top/tools/plot_sod.py "${1:-sod_0002.hdf5}" --out sod.png
echo "plot: $(pwd)/sod.png"
