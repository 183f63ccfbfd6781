#!/usr/bin/env bash
# Sod shock tube: initial conditions, run, plot against the exact solution.
# Usage: ./run.sh [NX]   (NX: particles along x in the dense half; default 64, 18432 particles)
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
nx=${1:-64}
"$build/bolide-ic" sod --nx "$nx" --size 2,0.25,0.25 -o sod.hdf5
"$build/bolide" params.yml
./plot.sh sod_0002.hdf5
