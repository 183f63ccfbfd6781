#!/usr/bin/env bash
# Graded plate impact (issue 24 item 6): an Al sphere at 1000 m/s into a
# steel 4340 plate, once with uniform particles and once with graded ones
# (fine within 1.65 cm of the axis, twice as coarse outside: a third of the
# particles), each through a node file and bolide-ic import-mesh; then the
# deformation of both compared and the wall- and CPU-time ratios printed
# (results/compare.txt, deformation.png).
# Usage: ./run.sh [DX] [THREADS]  (fine spacing in m, default 0.001: 6 layers
# through the plate, 22,152 / 7,620 particles, to 20 us: 4 to 8 minutes on
# 2 cores; 0.0005 for a real run, 12 layers, 177,024 / 61,440 particles)
# BOLIDE_ARGS (optional): more bolide options, e.g. BOLIDE_ARGS="-P Scheduler:gpu:all".
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=$(cd "${BOLIDE_BUILD:-$top/_build}" && pwd)
python=${PYTHON:-$build/.venv/bin/python}
dx=${1:-0.001}
threads=${2:-2}
read -r -a extra <<<"${BOLIDE_ARGS:-}"
mkdir -p results
for kind in uniform graded; do
  mkdir -p "run_$kind"
  "$python" make_ic.py "$kind" --dx "$dx" --bolide-ic "$build/bolide-ic" -o "run_$kind/plate.hdf5"
  echo "running the $kind plate (log: run_$kind/log.txt)"
  cp params.yml "run_$kind/"
  # wall, user and system seconds of the run (time.txt): the VM may be shared,
  # and the CPU time is the steadier measure of the work there
  TIMEFORMAT="%R %U %S"
  { time (cd "run_$kind" && "$build/bolide" -t "$threads" ${extra[@]+"${extra[@]}"} params.yml >log.txt); } 2>"run_$kind/time.txt"
  grep -h "done:" "run_$kind/log.txt"
done
"$python" analyse.py --dx "$dx" --out deformation.png run_uniform run_graded | tee results/compare.txt
