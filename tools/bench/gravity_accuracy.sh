#!/usr/bin/env bash
# Gravity's accuracy against its cost on the planetary reference impact of
# theory/validation.md, "Benchmarks" (issue 25): for each Gravity:epsilon_fmm, theta_cr and
# multipole_order, the median, 90th and 99th percentile and largest relative
# acceleration error |a - a_direct| / |a_direct| at the first evaluation (a
# run's first step: no previous acceleration) and at the second (the
# adaptive criterion on the first's |a|), and the time of each evaluation
# (tests/helpers/bench_gravity_accuracy: the CPU's serial tree, or with -m gpu the
# upward pass, walks and interactions on the GPU).  The direct sum is
# computed once per size and kept in the output directory.  SWIFT's figures
# on these ICs (theory/validation.md, "Benchmarks"): median 3.3e-5, p90 8.2e-5, p99
# 1.7e-4, max 7.4e-4 at every step (epsilon_fmm 1e-3, theta 0.5, 1 in 10).
#
# Usage: tools/bench/gravity_accuracy.sh [-n "2.2e4 1.1e5"] [-m "cpu gpu"]
#          [-E "1e-3 1e-4 1e-5 1e-6"] [-T "0.5"] [-P "4"] [-k STRIDE] [-t THREADS]
#          [-o OUTDIR] [-x EXTRA]
#   -n  sizes (make_impact_ic.py N*10/11 N/11)
#   -m  cpu and/or gpu (a CUDA build on a GPU host)
#   -E, -T, -P  the epsilon_fmm, theta_cr and order values (every combination;
#       epsilon_fmm 0 is the geometric criterion alone)
#   -k  the reference for 1 particle in STRIDE (default 1 up to 2e5, else 10)
#   -t  threads of the direct summation (default nproc)
#   -o  where the tables go (default gravity_accuracy.out): acc_N_MODE.txt
#   -x  extra configurations "E,T,P ..." added as they are
# Environment: BOLIDE_BUILD (default _build), PYTHON, BOLIDE_BENCH_IC.
# Plot: tools/bench/plot_gravity_accuracy.py OUTDIR/acc_*.txt -o acc.png
# On the GPU host (tools/bench/device.sh builds in _dbuild):
#   tools/bench/device.sh 'cmd:tools/bench/gravity_accuracy.sh -n "1.1e5 1.1e6" -m "gpu cpu" -o /tmp/dout/gacc'
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
gen=${BOLIDE_BENCH_IC:?"set BOLIDE_BENCH_IC to the reference impact IC generator of the benchmark set (make_impact_ic.py; theory/validation.md, Benchmarks)"}
sizes="2.2e4"; modes="cpu"; epss="1e-3 1e-4 1e-5 1e-6"; thetas="0.5"; orders="4"
stride=""; threads=$(nproc); out=gravity_accuracy.out; extra=""
while getopts "n:m:E:T:P:k:t:o:x:" o; do
  case $o in n) sizes=$OPTARG ;; m) modes=$OPTARG ;; E) epss=$OPTARG ;; T) thetas=$OPTARG ;;
             P) orders=$OPTARG ;; k) stride=$OPTARG ;; t) threads=$OPTARG ;; o) out=$OPTARG ;;
             x) extra=$OPTARG ;; *) exit 2 ;; esac
done
bench=$build/tests/helpers/bench_gravity_accuracy
[ -x "$bench" ] || (cd "$build" && make tests/helpers/bench_gravity_accuracy >/dev/null) || {
  echo "gravity_accuracy.sh: error: cannot build $bench" >&2; exit 1; }
[ -f "$gen" ] || { echo "gravity_accuracy.sh: error: $gen not found (set BOLIDE_BENCH_IC)" >&2; exit 1; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cfgs=""
for e in $epss; do for t in $thetas; do for p in $orders; do cfgs="$cfgs -c $e,$t,$p"; done; done; done
for x in $extra; do cfgs="$cfgs -c $x"; done
for n in $sizes; do
  nt=$(awk -v n=$n 'BEGIN {printf "%d", n * 10 / 11}'); ni=$(awk -v n=$n 'BEGIN {printf "%d", n / 11}')
  ic=$out/impact_$n.hdf5
  [ -f "$ic" ] || "$python" "$gen" "$nt" "$ni" "$ic" >"$out/ic_$n.log"
  soft=$(awk '/suggested softening/ {print $NF}' "$out/ic_$n.log")
  N=$(awk '/N_target=/ {sub(/.*N=/, ""); print}' "$out/ic_$n.log")
  k=$stride
  [ -n "$k" ] || k=$(awk -v n=$N 'BEGIN {print (n > 2e5) ? 10 : 1}')
  for m in $modes; do
    g=""; [ "$m" = gpu ] && g="-g"
    f=$out/acc_${N}_$m.txt
    {
      printf "# %s on %s (%s), commit %s\n" "$("$build/bolide" --version 2>/dev/null | head -1)" \
        "$(uname -n)" "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" \
        "$(git -C "$top" rev-parse --short HEAD 2>/dev/null || echo unknown)"
      # shellcheck disable=SC2086
      "$bench" -s "$soft" -k "$k" -t "$threads" -r "$out/ref_${N}_k$k.bin" $g $cfgs "$ic"
    } | tee "$f"
  done
done
