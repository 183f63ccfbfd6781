#!/usr/bin/env bash
# Colliding rubber rings (Gray, Monaghan & Swift 2001): with and without
# artificial stress.  Usage: ./run.sh [DX] [open]  (lattice spacing in m;
# default 0.0025).  Default: plane strain, the 2D problem of the paper (rings
# 2 cm = 8 layers tall in a box periodic in z; 5696 particles, about 2
# minutes per run on 2 idle cores).  `open`: short tubes 1 cm thick with free
# faces in z (2848 particles), which do not fracture (README.md).
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
dx=${1:-0.0025}
if [ "${2:-}" = open ]; then
  "$python" make_ic.py --dx "$dx" --thickness 0.01 -o rings.hdf5
else
  "$python" make_ic.py --dx "$dx" --thickness 0.02 --periodic-z -o rings.hdf5
fi
"$build/bolide" params.yml
"$build/bolide" params_no_as.yml
"$python" plot_rings.py --dx "$dx" --out rings.png with_as no_as
