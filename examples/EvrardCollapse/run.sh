#!/usr/bin/env bash
# Evrard collapse: initial conditions, run to t = 3, energy curves.
# Usage: ./run.sh [N_ACROSS]   (default 40: about 33,500 particles)
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
"$python" make_ic.py "${1:-40}" evrard.hdf5
"$build/bolide" params.yml
./plot.sh
