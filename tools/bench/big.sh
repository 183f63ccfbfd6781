#!/usr/bin/env bash
# The planetary reference impact at the size that fills one GPU (issue 21
# item 6: 1.1e8 particles on one H200), in two parts that fit the device
# host's calls of 600 s: the IC made once into a folder that the host keeps
# while it stays warm, then a run of a few steps on the GPU with the step's
# time and the memory per particle of the host (peak resident set) and of
# the device (the run's own report).  The problem is tools/bench/gpu.sh's
# "gravity" (hydrodynamics and self-gravity, the suggested softening, 16^3
# top-level cells, every particle active), without snapshots
# (Snapshots:enabled: false: two snapshots of 1.1e8 particles would be
# 45 GB).
#
# Usage: tools/bench/big.sh gen N DIR        make_impact_ic.py N*10/11 N/11 DIR/ic.hdf5
#                                            (nothing if DIR/ic.hdf5 is there)
#        tools/bench/big.sh run N DIR [STEPS] [BOLIDE ARGS...]
#                                            STEPS steps (default 2), the log DIR/run.log
# Env:   BOLIDE_BUILD (build folder), BOLIDE_BENCH_IC (make_impact_ic.py),
#        PYTHON (with numpy and h5py), BIG_LIMIT (seconds: the run is killed
#        after them and its log still printed; 0, the default: no limit)
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-python3}
what=${1:?"usage: big.sh gen|run N DIR [STEPS] [BOLIDE ARGS...]"}
n=${2:?"usage: big.sh gen|run N DIR"}
dir=${3:?"usage: big.sh gen|run N DIR"}
mkdir -p "$dir"
case $what in
  gen)
    gen=${BOLIDE_BENCH_IC:?"set BOLIDE_BENCH_IC to make_impact_ic.py"}
    [ -f "$dir/ic.hdf5" ] && { echo "big.sh: $dir/ic.hdf5 is there"; exit 0; }
    nt=$(awk -v n="$n" 'BEGIN {printf "%d", n * 10 / 11}'); ni=$(awk -v n="$n" 'BEGIN {printf "%d", n / 11}')
    /usr/bin/time -v "$python" "$gen" "$nt" "$ni" "$dir/ic.tmp.hdf5" >"$dir/ic.log" 2>"$dir/ic.time"
    mv "$dir/ic.tmp.hdf5" "$dir/ic.hdf5"
    grep -E "Elapsed|Maximum resident" "$dir/ic.time"
    cat "$dir/ic.log" ;;
  run)
    steps=${4:-2}
    shift $(($# < 4 ? $# : 4))
    [ -f "$dir/ic.hdf5" ] || { echo "big.sh: no $dir/ic.hdf5: run big.sh gen first" >&2; exit 1; }
    soft=${BENCH_SOFTENING:-$(awk '/suggested softening/ {print $NF * 1e6}' "$dir/ic.log")}
    cat >"$dir/p.yml" <<YML
InitialConditions:
  file_name: $dir/ic.hdf5
  periodic: false
TimeIntegration:
  time_end: 1e30
  dt_min: 1e-30
Snapshots:
  subdir: $dir/out
  enabled: false
Statistics:
  delta_time: 1e30
Materials:
  101: {}
Gravity:
  enabled: true
  softening: $soft
SPH:
  resolution_eta: 1.2348
  CFL_condition: 0.2
  viscosity_alpha: 1.5
Scheduler:
  max_top_level_cells: 16
YML
    rc=0
    lim=()
    [ "${BIG_LIMIT:-0}" = 0 ] || lim=(timeout -s KILL "$BIG_LIMIT")
    "${lim[@]}" /usr/bin/time -v "$build/bolide" --gpu -P Scheduler:gpu:all -v -n "$steps" -t "$(nproc)" "$@" \
      "$dir/p.yml" >"$dir/run.log" 2>&1 || rc=$?
    grep -v "^\s" "$dir/run.log" | grep -E "^\[|^GPU|^ *[0-9]+ |error" | cut -c1-400
    grep -E "Elapsed|Maximum resident|Exit status" "$dir/run.log"
    awk -v n="$n" '/Maximum resident/ {printf "host: %.0f bytes per particle at the peak (resident set)\n", $NF * 1024 / n}' \
      "$dir/run.log"
    nvidia-smi --query-gpu=name,memory.total --format=csv,noheader 2>/dev/null || true
    exit $rc ;;
  *) echo "big.sh: unknown part '$what' (gen or run)" >&2; exit 2 ;;
esac
