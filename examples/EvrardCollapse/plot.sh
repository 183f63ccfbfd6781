#!/usr/bin/env bash
# Evrard collapse: kinetic, thermal, potential and total energy against time
# from statistics.txt (tools/plot_stats.py), to set beside Evrard (1988).
# Usage: ./plot.sh   (run.sh first)
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
"$python" $top/tools/plot_stats.py statistics.txt --out energies.png
echo "plot: $(pwd)/energies.png"
