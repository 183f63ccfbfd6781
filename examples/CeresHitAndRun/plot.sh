#!/usr/bin/env bash
# CeresHitAndRun: pictures of the collision and of the energy budget, and the
# bound mass against time (tools/plot_impact.py, lengths in km; the impactor's
# material ids are offset by 3), from the snapshots and statistics.txt.
# Usage: ./plot.sh   (run.sh first)
set -euo pipefail
cd "$(dirname "$0")"
top=${TOP:-../..}
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
"$python" $top/tools/plot_impact.py --stats statistics.txt \
  --length-unit 1e3 --length-name km --impactor-offset 3 ceres_0*.hdf5 > bound_mass.txt
echo "pictures: $(pwd)/collision.png $(pwd)/energy.png; bound mass: $(pwd)/bound_mass.txt"
