#!/usr/bin/env bash
# Water jet on a thin plate (issue 24 item 6): initial conditions, run,
# the fluid-solid gap, penetration and plate deflection against time
# (results/*.txt) and the picture interface.png.
# Usage: ./run.sh [DX] [THREADS]  (lattice spacing in m, default 0.0005: 4
# layers through the plate, 10,048 particles, to 20 us: about 4 minutes on
# 2 cores; 0.00025 for 8 layers, 80,000 particles)
# PARAMS (optional): another parameter file, e.g. PARAMS=variants/no_interface.yml;
# each parameter file runs in its own folder run_NAME/ (run_params/ for
# params.yml), and the picture shows every run_*/ folder there is.
# BOLIDE_ARGS (optional): more bolide options, e.g. BOLIDE_ARGS="-P Scheduler:gpu:all".
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=$(cd "${BOLIDE_BUILD:-$top/_build}" && pwd)
python=${PYTHON:-$build/.venv/bin/python}
dx=${1:-0.0005}
threads=${2:-2}
read -r -a extra <<<"${BOLIDE_ARGS:-}"
params=${PARAMS:-params.yml}
run=run_$(basename "$params" .yml)
mkdir -p "$run" results
"$python" make_ic.py --dx "$dx" -o "$run/jet.hdf5"
cp "$params" "$run/params.yml"
(cd "$run" && "$build/bolide" -t "$threads" ${extra[@]+"${extra[@]}"} params.yml >log.txt)
grep -h "done:\|conservation budget" "$run/log.txt"
runs=""
for d in run_params run_*/; do
  d=${d%/}
  [ -d "$d/output" ] || continue
  case " $runs " in *" $d "*) ;; *) runs="$runs $d" ;; esac
done
# shellcheck disable=SC2086
"$python" analyse.py --dx "$dx" --out interface.png $runs | tee "results/$run.txt"
