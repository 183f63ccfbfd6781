#!/usr/bin/env bash
# CPU-only (every host core) against the GPU runner, seconds per step with
# every particle active, for a uniform periodic box, a Sedov blast, the
# planetary reference impact of shared/bench (make_impact_ic.py, Tillotson
# granite, hydro only) and the same initial conditions as solids ("solid":
# Tillotson basalt with Collins strength and Grady-Kipp damage with Weibull
# flaws; no self-gravity) and with self-gravity ("gravity": granite, hydro +
# tree gravity, softening 30 km; on the GPU runner the multipoles and the walks
# stay on the CPU, which record the interactions, and M2L, L2L, L2P, M2P and
# P2P run on the GPU), at each size; median over REPEAT runs of STEPS steps
# (each run's mean step).  Prints one table (markdown) and the GPU's stage
# times of the last GPU run of each case.
#
# Usage: tools/bench/gpu.sh [-n "1e5 1e6"] [-p "box sedov impact solid gravity"] [-r 3] [-s 4] [-g "GPU ARGS"]
#   -g  extra bolide arguments for the GPU runs only, e.g.
#       "-P Scheduler:cell_split_size:64" (smaller leaves: shorter GPU loops)
# Env:   BOLIDE_BUILD (build folder), BOLIDE_BENCH_IC (make_impact_ic.py),
#        PYTHON (with numpy and h5py, for the impact IC)
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-python3}
gen=${BOLIDE_BENCH_IC:-$top/../shared/bench/make_impact_ic.py}
sizes="1e5 1e6"; problems="box sedov impact"; repeat=3; steps=4; gpu_args=""
while getopts "n:p:r:s:g:" o; do
  case $o in n) sizes=$OPTARG ;; p) problems=$OPTARG ;; r) repeat=$OPTARG ;; s) steps=$OPTARG ;;
             g) gpu_args=$OPTARG ;; *) exit 2 ;; esac
done
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
ncpu=$(nproc)
printf "# %s on %s (%s, %d cores); GPU: %s\n" "$("$build/bolide" --version | head -1)" "$(uname -n)" \
  "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" "$ncpu" \
  "$(nvidia-smi --query-gpu=name --format=csv,noheader 2>/dev/null | head -1)"
printf "# median of %d runs of %d steps, every particle active\n" "$repeat" "$steps"
printf "| problem | N | CPU %d threads s/step | GPU %s s/step | speed-up |\n|---|---|---|---|---|\n" "$ncpu" "$gpu_args"
stages=""

# run FLAG: median over the repeats of the mean wall time per step
run() {
  for r in $(seq "$repeat"); do
    "$build/bolide" -n "$steps" -t "$ncpu" $1 p.yml >run.log 2>&1 || { tail -3 run.log >&2; exit 1; }
    awk '$1 ~ /^[0-9]+$/ && NF == 6 {s += $5; n++} END {printf "%.6f\n", s / n}' run.log
  done | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'
}

for prob in $problems; do
  for n in $sizes; do
    side=$(awk -v n=$n 'BEGIN {printf "%d", n ^ (1 / 3) + 0.5}')
    case $prob in
      box)
        "$build/bolide-ic" box --n "$side" --perturb 0.1 -o ic.hdf5 >/dev/null
        extra="  periodic: true" ;;
      sedov)
        "$build/bolide-ic" sedov --n "$side" --energy 1 --rho 1 -o ic.hdf5 >/dev/null
        extra="  periodic: true" ;;
      impact|solid|gravity)
        nt=$(awk -v n=$n 'BEGIN {printf "%d", n * 10 / 11}'); ni=$(awk -v n=$n 'BEGIN {printf "%d", n / 11}')
        "$python" "$gen" "$nt" "$ni" ic.hdf5 >/dev/null
        extra="  periodic: false" ;;
    esac
    mats=""; [ $prob = impact ] && mats=$'Materials:\n  101: {}'
    [ $prob = gravity ] && mats=$'Materials:\n  101: {}\nGravity:\n  enabled: true\n  softening: 3e4'
    [ $prob = solid ] && mats=$'Materials:\n  101: {name: basalt, strength: collins, yield_stress: 1e7, yield_stress_max: 3.5e9, friction_intact: 1.2, cohesion_damaged: 1e5, friction_damaged: 0.6, weibull_k: 1e61, weibull_m: 16}\nDamage:\n  seed: 1'
    cat >p.yml <<YML
InitialConditions:
  file_name: ic.hdf5
$extra
TimeIntegration:
  time_end: 1e30
  dt_min: 1e-30
Snapshots:
  subdir: out
  delta_time: 1e30
Statistics:
  delta_time: 1e30
$mats
SPH:
  resolution_eta: 1.2348
  CFL_condition: 0.2
  viscosity_alpha: 1.5
Scheduler:
  max_top_level_cells: 16
YML
    N=$(awk '/read [0-9]+ particles/ {for (k = 1; k <= NF; k++) if ($k == "read") print $(k + 1)}' \
        <("$build/bolide" --check p.yml 2>&1 || true) | head -1)
    cpu=$(run --no-gpu)
    gpu=$(run "--gpu $gpu_args")
    stages="$stages$prob $N: $(grep '^GPU (' run.log | sed 's/^GPU ([^)]*), //' | tr '\n' ' '); $(grep '^GPU host\|^GPU gravity' run.log | tr '\n' ' ')"$'\n'
    printf "| %s | %s | %.4f | %.4f | %.1f |\n" "$prob" "$N" "$cpu" "$gpu" "$(awk -v a=$cpu -v b=$gpu 'BEGIN {print a / b}')"
  done
done
printf "\nGPU stage times of the last run of each case:\n%s" "$stages"
