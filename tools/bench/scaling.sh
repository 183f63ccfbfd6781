#!/usr/bin/env bash
# Strong and weak scaling in threads for a planetary impact: the EarthImpact
# set-up (proto-Earth 0.887 M_E and Theia 0.133 M_E, iron core / granite
# mantle, v_esc at 45 degrees; examples/EarthImpact) built by bolide-ic impact
# ten minutes before contact, hydrodynamics + self-gravity, every particle
# active.  Each figure is the median over REPEAT runs of the mean wall time
# per step of `bolide -n STEPS` (the step lines; the start-up force
# computation is not a step and is left out).
#
#   strong: the same N on every thread count; speed-up t(1)/t(T), efficiency
#           t(1)/(T t(T)).
#   weak:   N = N_PER_THREAD x T; efficiency t(1)/t(T).
#
# Usage: tools/bench/scaling.sh strong [-n N] [-t "1 2 ..."] [-r REPEAT] [-s STEPS] [-o PREFIX]
#        tools/bench/scaling.sh weak [-n N_PER_THREAD] [-t "1 2 ..."] [-r REPEAT] [-s STEPS] [-o PREFIX]
# Defaults: N 1e5 (strong), 2.5e4 per thread (weak); threads 1 .. nproc in
# powers of two; REPEAT 3; STEPS 3; PREFIX scaling_strong / scaling_weak.
# Writes PREFIX.txt (the table, also printed) and PREFIX.png.
# Environment: BOLIDE_BUILD (default: _build), PYTHON (default: the build's venv).
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
usage() { echo "usage: $0 strong|weak [-n N] [-t THREADS] [-r REPEAT] [-s STEPS] [-o PREFIX]" >&2; exit 2; }
[ $# -ge 1 ] || usage
mode=$1; shift
case $mode in strong) n=1e5 ;; weak) n=2.5e4 ;; *) usage ;; esac
threads=""; t=1
while [ "$t" -le "$(nproc)" ]; do threads="$threads $t"; t=$((2 * t)); done
[ "$(nproc)" -eq $((t / 2)) ] || threads="$threads $(nproc)"
repeat=3; steps=3; prefix="scaling_$mode"
while getopts "n:t:r:s:o:" o; do
  case $o in n) n=$OPTARG ;; t) threads=$OPTARG ;; r) repeat=$OPTARG ;; s) steps=$OPTARG ;;
             o) prefix=$OPTARG ;; *) usage ;; esac
done
for v in "$repeat" "$steps"; do [[ "$v" =~ ^[1-9][0-9]*$ ]] || { echo "scaling.sh: error: -r and -s take positive integers" >&2; exit 2; }; done
out="$(pwd)/$prefix"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"

make_ic() { # make_ic N FILE: the EarthImpact bodies, 10 minutes before contact
  local nt ni
  nt=$(awk -v n="$1" 'BEGIN {printf "%d", n * 0.887 / 1.02 + 0.5}')
  ni=$(awk -v n="$1" -v t="$nt" 'BEGIN {printf "%d", n - t}')
  local layers="materials=iron:granite,mass-fractions=0.3:0.7,T-rho=adiabatic,T-surface=2000"
  "$build/bolide-ic" impact --target "planet,$layers,mass=5.297e24,n=$nt" \
    --impactor "planet,$layers,mass=7.943e23,n=$ni,seed=2" --v-over-vesc 1 --angle 45 \
    --time 600 --impactor-mat-offset 1000 -o "$2" >/dev/null
  local eps
  eps=$(awk -v n="$1" 'BEGIN {printf "%.6g", 6e4 * (1e5 / n) ^ (1 / 3)}')
  cat >"${2%.hdf5}.yml" <<YML
InitialConditions:
  file_name: $2
  periodic: false
TimeIntegration:
  time_end: 1e30
Snapshots:
  subdir: out
  delta_time: 1e30
SPH:
  resolution_eta: 1.2348
  CFL_condition: 0.2
Gravity:
  enabled: true
  theta_cr: 0.5
  softening: $eps
Materials:
  100: {name: iron, P_min: 0}
  101: {name: granite, P_min: 0}
  1100: {name: iron, P_min: 0}
  1101: {name: granite, P_min: 0}
YML
}

time_per_step() { # time_per_step PARAMS THREADS: median over REPEAT of the mean s/step
  for r in $(seq "$repeat"); do
    "$build/bolide" -n "$steps" -t "$2" "$1" >run.log 2>&1 || { tail -3 run.log >&2; exit 1; }
    awk '$1 ~ /^[0-9]+$/ && NF == 6 {s += $5; k++} END {printf "%.6f\n", s / k}' run.log
  done | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'
}

{
  printf "# %s scaling in threads, planetary impact (EarthImpact set-up, hydro + gravity)\n" "$mode"
  printf "# %s on %s (%s, %s cores); commit %s\n" "$("$build/bolide" --version | head -1)" \
    "$(uname -n)" "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" "$(nproc)" \
    "$(git -C "$top" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  printf "# median of %d runs of the mean wall time of %d steps\n" "$repeat" "$steps"
  printf "%8s %10s %12s %10s %10s\n" threads N s/step speedup efficiency
} | tee "$out.txt"
t1=""
for t in $threads; do
  if [ "$mode" = strong ]; then nn=$n; else nn=$(awk -v n="$n" -v t="$t" 'BEGIN {printf "%d", n * t}'); fi
  [ -f "ic_$nn.hdf5" ] || make_ic "$nn" "ic_$nn.hdf5"
  s=$(time_per_step "ic_$nn.yml" "$t")
  [ -n "$t1" ] || t1=$s
  if [ "$mode" = strong ]; then
    awk -v t="$t" -v n="$nn" -v s="$s" -v t1="$t1" \
      'BEGIN {printf "%8d %10d %12.4f %10.3f %10.3f\n", t, n, s, t1 / s, t1 / (t * s)}'
  else
    awk -v t="$t" -v n="$nn" -v s="$s" -v t1="$t1" \
      'BEGIN {printf "%8d %10d %12.4f %10s %10.3f\n", t, n, s, "-", t1 / s}'
  fi
done | tee -a "$out.txt"

MPLBACKEND=Agg "$python" - "$out.txt" "$out.png" "$mode" <<'PY'
import sys
import numpy as np
import matplotlib.pyplot as plt
table, png, mode = sys.argv[1:4]
d = np.loadtxt(table, comments="#", skiprows=4, ndmin=2, usecols=(0, 1, 2, 4))
t, n, s, eff = d.T
fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.8))
if mode == "strong":
    a1.plot(t, s[0] / s, "o-", label="measured")
    a1.plot(t, t, "k--", label="ideal")
    a1.set_ylabel("speed-up t(1)/t(T)")
    a1.set_title("strong scaling, N = %d" % n[0])
else:
    a1.plot(t, s, "o-")
    a1.set_ylabel("wall time per step [s]")
    a1.set_title("weak scaling, %d particles per thread" % (n[0]))
a2.plot(t, eff, "o-")
a2.axhline(1, color="k", ls="--")
a2.set_ylim(0, 1.1)
a2.set_ylabel("parallel efficiency")
for a in (a1, a2):
    a.set_xlabel("threads")
    a.grid(alpha=0.3)
a1.legend() if mode == "strong" else None
fig.tight_layout()
fig.savefig(png, dpi=110)
PY
echo "# table: $out.txt, plot: $out.png"
