#!/usr/bin/env bash
# Boss-Bodenheimer collapse: initial conditions, run to 1.2 t_ff, maximum
# density against t/t_ff.  Usage: ./run.sh [N_ACROSS]  (default 40)
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
"$python" make_ic.py "${1:-40}" cloud.hdf5
"$build/bolide" params.yml
"$python" plot_density.py "cloud_*.hdf5" --out max_density.png
