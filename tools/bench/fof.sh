#!/usr/bin/env bash
# bolide-fof speed and memory: the basalt reference impact of
# tools/bench/basalt_ic.py (two lattice spheres) at each size, linking
# length one median h, every particle kept; median wall time of REPEAT runs
# and the peak memory of the last.
# Usage: tools/bench/fof.sh [-n "1e5 1e6 1e7"] [-r 3]
# Env: BOLIDE_BUILD (build folder), PYTHON (with numpy and h5py)
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
sizes="1e5 1e6 1e7"; repeat=3
while getopts "n:r:" o; do
  case $o in n) sizes=$OPTARG ;; r) repeat=$OPTARG ;; *) exit 2 ;; esac
done
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
printf "# %s on %s (%d cores); median of %d runs\n" "$("$build/bolide-fof" --version | head -1)" "$(uname -n)" "$(nproc)" "$repeat"
printf "| N | wall s | peak MiB | groups |\n|---|---|---|---|\n"
for n in $sizes; do
  "$python" "$top/tools/bench/basalt_ic.py" "$n" "$work/s.hdf5" >/dev/null
  N=$("$python" -c "import h5py; print(h5py.File('$work/s.hdf5')['PartType0/Masses'].shape[0])")
  for r in $(seq "$repeat"); do
    /usr/bin/time -f "%e %M" -o "$work/t" "$build/bolide-fof" "$work/s.hdf5" -v -o /dev/null >"$work/log" 2>&1
    cat "$work/t"
  done | sort -g >"$work/times"
  g=$(awk '/groups/ {print $(NF - 1)}' "$work/log")
  awk -v N="$N" -v g="$g" '{w[NR] = $1; m = $2} END {printf "| %d | %.2f | %.0f | %s |\n", N, w[int((NR + 1) / 2)], m / 1024, g}' "$work/times"
done
