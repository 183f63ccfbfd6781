#!/usr/bin/env bash
# CeresHitAndRun: initial conditions, run, survivors (bolide-fof) next to the
# paper's, pictures.
# Usage: ./run.sh [N [bolide options...]]
#   N: total particles (default 10000), half per body (equal masses)
#   bolide options are passed on, e.g. -t 2 or -P TimeIntegration:time_end:20000
set -euo pipefail
cd "$(dirname "$0")"
top=${TOP:-../..}
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
n=${1:-10000}
shift || true
read -r na nb eps < <("$python" -c "
n = int(float('$n')); print(n // 2, n - n // 2, 5.0e3 * (2e4 / n) ** (1 / 3))")
# Body A: basalt core with a 30 wt-% water ice mantle, 9.43e20 kg (R = 509 km
# uncompressed); body B: pure basalt, 9.43e20 kg (R = 437 km).  Start 11369 km
# apart at 744 m/s with impact parameter 819 km (theory/validation.md).
"$build/bolide-ic" impact \
  --target "planet,materials=basalt:ice,mass-fractions=0.7:0.3,mass=9.43e20,T-surface=0,mat-ids=1:2,n=$na" \
  --impactor "planet,materials=basalt,mass=9.43e20,T-surface=0,mat-ids=3,n=$nb,seed=2" \
  --v-start 744 --b-start 819e3 --separation 11369e3 \
  -o ceres_impact.hdf5 | tee ic.log
rm -f ceres_0*.hdf5 ceres_0*.xmf statistics.txt
"$build/bolide" -P Gravity:softening:"$eps" "$@" params.yml
last=$(ls ceres_0*.hdf5 | tail -1)
"$build/bolide-fof" "$last" --link-h 2 --min-count 10 -o fragments.txt
"$python" survivors.py fragments.txt "$last" | tee survivors.txt
./plot.sh
echo "survivors: $(pwd)/survivors.txt"
