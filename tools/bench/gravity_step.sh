#!/usr/bin/env bash
# Seconds per step of the reference impact (theory/validation.md, "Benchmarks") with and without
# self-gravity, every particle active, at given Gravity:epsilon_fmm and
# multipole_order: the step's gravity time is the difference (issue 25,
# item 4: against SWIFT's 2.79 s hydro + gravity, 0.385 s hydro, per step at
# 1.1e6 on the 16-core H200 host, epsilon_fmm 1e-3, theta 0.5).  Median of
# steps 2..S of one run each (the first step includes the set-up).  A GPU
# run's row is followed by its gravity stages (ms per evaluation) as a
# comment.
#
# Usage: tools/bench/gravity_step.sh [-n "1.1e5 1.1e6"] [-m "cpu gpu"] [-t THREADS]
#          [-s STEPS] [-c "5e-5,5 1e-3,4"]
#   -c  the gravity settings "EPS_FMM,ORDER ..." (theta_cr 0.5); "off": no gravity
# Environment: BOLIDE_BUILD (default _build), PYTHON, BOLIDE_BENCH_IC.
# On the GPU host: tools/bench/device.sh 'cmd:tools/bench/gravity_step.sh -n 1.1e6 -t 16'
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
gen=${BOLIDE_BENCH_IC:?"set BOLIDE_BENCH_IC to the reference impact IC generator of the benchmark set (make_impact_ic.py; theory/validation.md, Benchmarks)"}
sizes="1.1e5"; modes="cpu"; threads=$(nproc); steps=6; cfgs="off 1e-3,4 5e-5,5"
while getopts "n:m:t:s:c:" o; do
  case $o in n) sizes=$OPTARG ;; m) modes=$OPTARG ;; t) threads=$OPTARG ;; s) steps=$OPTARG ;;
             c) cfgs=$OPTARG ;; *) exit 2 ;; esac
done
[ -f "$gen" ] || { echo "gravity_step.sh: error: $gen not found (set BOLIDE_BENCH_IC)" >&2; exit 1; }
work=$(mktemp -d); trap '[ -n "${GS_KEEP:-}" ] || rm -rf "$work"' EXIT
cd "$work"
printf "# %s on %s (%s), %s threads, commit %s\n" "$("$build/bolide" --version | head -1)" "$(uname -n)" \
  "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" "$threads" \
  "$(git -C "$top" rev-parse --short HEAD 2>/dev/null || echo unknown)"
printf "%-8s %-4s %-10s %12s\n" N mode gravity s_per_step
for n in $sizes; do
  nt=$(awk -v n=$n 'BEGIN {printf "%d", n * 10 / 11}'); ni=$(awk -v n=$n 'BEGIN {printf "%d", n / 11}')
  "$python" "$gen" "$nt" "$ni" impact.hdf5 >ic.log
  soft=$(awk '/suggested softening/ {print $NF * 1e6}' ic.log)
  N=$(awk '/N_target=/ {sub(/.*N=/, ""); print}' ic.log)
  for m in $modes; do
    gpu="--no-gpu"; [ "$m" = gpu ] && gpu=""
    for c in $cfgs; do
      en=true; e=${c%,*}; p=${c#*,}
      [ "$c" = off ] && { en=false; e=5e-5; p=5; }
      cat >p.yml <<YML
InitialConditions:
  file_name: impact.hdf5
TimeIntegration:
  time_end: 4000
Snapshots:
  subdir: out
  delta_time: 1e30
Statistics:
  delta_time: 1e30
Materials:
  101: {}
SPH:
  resolution_eta: 1.2348
  CFL_condition: 0.2
  viscosity_alpha: 1.5
Gravity:
  enabled: $en
  theta_cr: 0.5
  softening: $soft
  epsilon_fmm: $e
  multipole_order: $p
Scheduler:
  max_top_level_cells: 16
YML
      "$build/bolide" $gpu -t "$threads" --steps "$steps" p.yml >run.log 2>&1 || { tail -3 run.log >&2; exit 1; }
      t=$(awk '/^ *[0-9]+ +[0-9.e+-]+ +[0-9.e+-]+ +[0-9]+ +[0-9.]+/ && NF >= 6 && $1 >= 2 {print $5}' run.log | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : 0.5 * (v[NR / 2] + v[NR / 2 + 1])}')
      [ "$t" != 0 ] || { echo "gravity_step.sh: error: no step lines in the run's log; its end:" >&2; tail -15 run.log >&2; }
      label=$c; [ "$c" = off ] || label="$e,p$p"
      printf "%-8s %-4s %-10s %12s\n" "$N" "$m" "$label" "$t"
      # the GPU's gravity stages (ms per evaluation), under the row
      grep -m1 '^GPU gravity' run.log | sed 's/^/# /' || true
    done
  done
done
