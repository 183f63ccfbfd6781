#!/usr/bin/env bash
# Colliding rubber rings (Gray, Monaghan & Swift 2001): with and without
# artificial stress.  Usage: ./run.sh [DX]  (lattice spacing in m; default
# 0.0025: 2848 particles, about 5 minutes per run on 2 cores)
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
dx=${1:-0.0025}
"$python" make_ic.py --dx "$dx" -o rings.hdf5
"$build/bolide" params.yml
"$build/bolide" params_no_as.yml
"$python" plot_rings.py --dx "$dx" --out rings.png with_as no_as
