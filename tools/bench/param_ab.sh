#!/usr/bin/env bash
# One parameter's values against each other on the planetary reference
# impact (hydro only, impact.sh's IC and parameter file, `impact.sh -w`),
# alternating value by value within each round so that a machine's drift
# shows in every value alike.  Prints, per run, the mean seconds per step
# over all steps (impact.sh's figure) and over steps 2..n.
#
# Usage: tools/bench/param_ab.sh [-k SPH:h_taylor] [-v "true false"] [-n 1e6]
#                               [-t 16] [-m "cpu gpu"] [-r 3] [-s 3]
#   -m  cpu: bolide --no-gpu; gpu: the GPU runner (CUDA builds); gpu runs take one step more
# BOLIDE_BUILD (default _build), PYTHON, BOLIDE_BENCH_IC as for impact.sh.
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
key=SPH:h_taylor; values="true false"; n=1e6; threads=$(nproc); modes=cpu; rounds=3; steps=3
while getopts "k:v:n:t:m:r:s:" o; do
  case $o in k) key=$OPTARG ;; v) values=$OPTARG ;; n) n=$OPTARG ;; t) threads=$OPTARG ;;
             m) modes=$OPTARG ;; r) rounds=$OPTARG ;; s) steps=$OPTARG ;; *) exit 2 ;; esac
done
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
"$top/tools/bench/impact.sh" -n "$n" -w "$work"   # the IC and impact.sh's hydro p.yml
cd "$work"
printf "# %s, %s threads, %s = %s, %d rounds\n" "$("$build/bolide" --version | head -1)" "$threads" "$key" "$values" "$rounds"
for r in $(seq "$rounds"); do
  for v in $values; do
    for m in $modes; do
      flag=""; ns=$((steps + 1)); [ "$m" = cpu ] && { flag=--no-gpu; ns=$steps; }
      "$build/bolide" $flag -n "$ns" -t "$threads" -P "$key:$v" p.yml >run.log 2>&1 || { tail -3 run.log >&2; exit 1; }
      awk -v tag="round $r $key $v $m" '$1 ~ /^[0-9]+$/ && NF == 6 {s += $5; n++; if ($1 > 1) {s2 += $5; n2++}}
        END {printf "%s: all %.4f  from2 %.4f s/step\n", tag, s / n, (n2 ? s2 / n2 : 0)}' run.log
    done
  done
done
