#!/usr/bin/env bash
# Sedov-Taylor blast: density against radius beside the similarity solution
# (tools/plot_sedov.py, which prints the shock radius and its error) and the
# energy budget of statistics.txt (tools/plot_stats.py).
# Usage: ./plot.sh [SNAPSHOT]   (default sedov_0002.hdf5; run.sh first)
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
initial=""; [ -f sedov.hdf5 ] && initial="--initial sedov.hdf5"  # the moment estimate of the radius
# shellcheck disable=SC2086
"$python" $top/tools/plot_sedov.py "${1:-sedov_0002.hdf5}" --E 1 --rho0 1 $initial --out sedov.png
"$python" $top/tools/plot_stats.py statistics.txt --out statistics.png
echo "plots: $(pwd)/sedov.png $(pwd)/statistics.png"
