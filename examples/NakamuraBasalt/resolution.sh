#!/usr/bin/env bash
# The intact core against resolution: several NakamuraBasalt runs at once.
# Usage: ./resolution.sh N:THREADS [N:THREADS ...]
#   e.g. ./resolution.sh 20000:2 40000:2 100000:10   (a 16-core host)
# LIMIT (seconds, default none) stops a run that takes longer; its last
# snapshot is analysed then.  Writes run_N/ for each and core_resolution.png.
set -uo pipefail
cd "$(dirname "$0")"
top=${TOP:-../..}
build=$(cd "${BOLIDE_BUILD:-$top/_build}" && pwd)
python=${PYTHON:-$build/.venv/bin/python}
limit=${LIMIT:-0}
runs=()
for spec in "$@"; do
  n=${spec%%:*}; threads=${spec##*:}
  ni=$(( (n * 149 + 50000) / 100000 )); [ "$ni" -ge 8 ] || ni=8
  dir=run_$n; mkdir -p "$dir"; runs+=("$dir")
  "$build/bolide-ic" impact --target "sphere,material=basalt,radius=0.03,n=$n" \
    --impactor "sphere,material=lucite,mass=2e-4,n=$ni" \
    --v-contact 3200 --angle 30 --time 1e-6 -o "$dir/nakamura_ic.hdf5" >"$dir/ic.log" || exit 1
  cp params.yml "$dir/params.yml"
  ( cd "$dir" && t0=$(date +%s) && timeout "$limit" "$build/bolide" -t "$threads" params.yml >bolide.log 2>&1
    echo "exit $? after $(( $(date +%s) - t0 )) s wall on $threads threads ($(nproc) cores here)" >wall.txt ) &
done
wait
for d in "${runs[@]}"; do echo "$d: $(cat "$d/wall.txt"); $(grep -E "done:" "$d/bolide.log")"; done
BOLIDE_BUILD=$build "$python" analyse.py "${runs[@]}"
