#!/usr/bin/env bash
# EarthImpact: pictures of the collision, bound mass and energy budget from
# the snapshots and statistics.txt (tools/plot_impact.py); the bound-mass
# table goes to bound_mass.txt.
# Usage: ./plot.sh   (run.sh first)
set -euo pipefail
cd "$(dirname "$0")"
top=${TOP:-../..}
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
"$python" $top/tools/plot_impact.py --stats statistics.txt earth_0*.hdf5 | tee bound_mass.txt
