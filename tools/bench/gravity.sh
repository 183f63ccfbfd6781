#!/bin/bash
# Gravity tree: wall time of one force pass against N, and the fitted
# exponent of t ~ N^k (least squares in log-log).  theory/validation.md asks for
# cost growing no faster than N log N (k close to 1; N log N over this range
# fits k ~ 1.1).  One thread; keep the sizes small on a small machine.
#   tools/bench/gravity.sh [BUILDDIR] [SET] [N...]
# BUILDDIR: where `make tests/helpers/bench_gravity` was run (default .);
# SET: plummer (default) or uniform; N: sizes (default 5000 10000 20000 40000).
set -eu
builddir=${1:-.}
set_name=${2:-plummer}
shift $(( $# > 2 ? 2 : $# ))
sizes=${*:-5000 10000 20000 40000}
bench="$builddir/tests/helpers/bench_gravity"
if [ ! -x "$bench" ]; then
  echo "gravity.sh: error: $bench not found (run make tests/helpers/bench_gravity in $builddir)" >&2
  exit 1
fi
echo "# N seconds ($set_name sphere, theta 0.5, the default order and epsilon_fmm)"
results=$(for n in $sizes; do "$bench" "$n" "$set_name"; done)
echo "$results"
echo "$results" | awk '
  { x = log($1); y = log($2); sx += x; sy += y; sxx += x * x; sxy += x * y; k++ }
  END { if (k > 1) printf "# fitted exponent: t ~ N^%.2f\n", (k * sxy - sx * sy) / (k * sxx - sx * sx) }'
