#!/usr/bin/env bash
# NakamuraBasalt: initial conditions, run, fragments and intact core.
# Usage: ./run.sh [N] [THREADS]   (N: target particles, default 20000, about
# ten minutes on 2 cores; the bullet gets particles of the same spacing)
# BOLIDE_ARGS (optional): more bolide options, e.g. the 1e6 run of README.md:
#   BOLIDE_ARGS="-P Damage:max_change:1 -P SPH:continuity_min_density_ratio:0.5 -P SPH:h_max:0.0012" ./run.sh 1000000 2
# WEIBULL_K, WEIBULL_M (optional) replace the target's Weibull k and m of
# params.yml (e.g. WEIBULL_M=8.5, the value of miluphcuda's Nakamura test
# case, README.md); the run folder is then run_N_m<M>_k<K>.
# IC_ONLY=1: write the initial conditions and params.yml, run nothing.
# Writes, in run_N/: the snapshots, fragments_*.txt (bolide-fof tables),
# core.txt (intact-core fraction against time), spectrum.png.
set -euo pipefail
cd "$(dirname "$0")"
top=${TOP:-../..}
build=$(cd "${BOLIDE_BUILD:-$top/_build}" && pwd)
python=${PYTHON:-$build/.venv/bin/python}
n=${1:-20000}
threads=${2:-2}
# bullet: 0.2 g of lucite (1186 kg/m^3) against 0.30536 kg of basalt (2700
# kg/m^3): equal spacing gives it N x 1.49e-3 particles
ni=$(( (n * 149 + 50000) / 100000 ))
[ "$ni" -ge 8 ] || ni=8
dir=run_$n
[ -z "${WEIBULL_M:-}${WEIBULL_K:-}" ] || dir=run_${n}_m${WEIBULL_M:-8}_k${WEIBULL_K:-5e34}
mkdir -p "$dir"
# start 1 us before contact (3.2 mm apart); 30 degrees between the velocity
# and the line of centres at contact
"$build/bolide-ic" impact \
  --target "sphere,material=basalt,radius=0.03,n=$n" \
  --impactor "sphere,material=lucite,mass=2e-4,n=$ni" \
  --v-contact 3200 --angle 30 --time 1e-6 -o "$dir/nakamura_ic.hdf5"
sed -e "s/weibull_k: 5e34/weibull_k: ${WEIBULL_K:-5e34}/" -e "s/weibull_m: 8}/weibull_m: ${WEIBULL_M:-8}}/" \
  params.yml >"$dir/params.yml"
grep -q "weibull_k: ${WEIBULL_K:-5e34}, weibull_m: ${WEIBULL_M:-8}}" "$dir/params.yml" \
  || { echo "run.sh: could not set the Weibull parameters in $dir/params.yml"; exit 1; }
# IC_ONLY=1: stop here (initial conditions and params.yml written; device_2e6.sh)
[ -z "${IC_ONLY:-}" ] || exit 0
t0=$(date +%s)
# shellcheck disable=SC2086
( cd "$dir" && "$build/bolide" -t "$threads" ${BOLIDE_ARGS:-} params.yml >bolide.log 2>&1 ) \
  || { tail -5 "$dir/bolide.log"; exit 1; }
echo "run: $(( $(date +%s) - t0 )) s wall on $threads threads ($(nproc) cores here)" | tee "$dir/wall.txt"
grep -E "Weibull flaws|done:" "$dir/bolide.log"
BOLIDE_BUILD=$build "$python" analyse.py "$dir"
last=$(ls "$dir"/nakamura_[0-9]*.hdf5 | tail -1)
"$python" $top/tools/plot_snapshot.py "$last" --colour damage --out "$dir/damage.png"
