#!/usr/bin/env bash
# EarthImpact: initial conditions, run, pictures of the collision, bound mass
# and energy budget.
# Usage: ./run.sh [N [bolide options...]]
#   N: total particles (default 1e5), shared by mass (proto-Earth 87%, Theia 13%)
#   bolide options are passed on, e.g. a short test run:
#     ./run.sh 5000 -P TimeIntegration:time_end:7200 -P Snapshots:delta_time:1800
set -euo pipefail
cd "$(dirname "$0")"
top=${TOP:-../..}
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
n=${1:-100000}
shift || true
M_E=5.972e24
read -r nt ni mt mi eps < <("$python" -c "
n = int(float('$n')); me = $M_E
mt, mi = 0.887 * me, 0.133 * me
nt = round(n * mt / (mt + mi))
print(nt, n - nt, mt, mi, 6.0e4 * (1e5 / n) ** (1 / 3))")
layers="materials=iron:granite,mass-fractions=0.3:0.7,T-rho=adiabatic,T-surface=2000"
# contact at v = v_esc, 45 degrees, one hour after the start
"$build/bolide-ic" impact \
  --target "planet,$layers,mass=$mt,n=$nt" \
  --impactor "planet,$layers,mass=$mi,n=$ni,seed=2" \
  --v-over-vesc 1 --angle 45 --time 3600 --impactor-mat-offset 1000 \
  -o earth_impact.hdf5
rm -f earth_0*.hdf5 earth_0*.xmf statistics.txt
"$build/bolide" -P Gravity:softening:"$eps" "$@" params.yml
./plot.sh
