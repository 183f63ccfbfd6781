#!/usr/bin/env bash
# DemoImpact: initial conditions, run, picture of the collision.
# Usage: ./run.sh [N]   (N: target particles, default 16000; impactor N/8)
set -euo pipefail
cd "$(dirname "$0")"
top=${TOP:-../..}
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
n=${1:-16000}
# centres 1.6 km apart at the start: contact after ~0.02 s
"$build/bolide-ic" impact \
  --target "sphere,material=granite,radius=1000,n=$n" \
  --impactor "sphere,material=granite,radius=500,n=$((n / 8))" \
  --v-contact 5000 --angle 45 --separation 1600 --impactor-mat-offset 1000 \
  -o demo_impact.hdf5
"$build/bolide" params.yml
./plot.sh
