#!/usr/bin/env bash
# The domain decomposition of the planetary reference impact (issue 22,
# theory/mpi.md): bolide --partition over 2, 4, 8 ... ranks with every
# method (METIS, Morton ranges, slabs), for several top-level grids, with the
# estimated costs and (with -m) the costs measured over STEPS steps.  Prints
# the partition lines of bolide (imbalance, edge cut, halo, pieces).
#
# Usage: BOLIDE_BENCH_IC=.../make_impact_ic.py tools/bench/decomp.sh
#          [-n 1e5] [-r "2 4 8"] [-c "16 64"] [-m STEPS] [-t THREADS]
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
gen=${BOLIDE_BENCH_IC:?"set BOLIDE_BENCH_IC to the reference impact IC generator (make_impact_ic.py)"}
size=1e5; ranks="2 4 8"; cells="16 64"; steps=0; threads=$(nproc)
while getopts "n:r:c:m:t:" o; do
  case $o in n) size=$OPTARG ;; r) ranks=$OPTARG ;; c) cells=$OPTARG ;; m) steps=$OPTARG ;;
             t) threads=$OPTARG ;; *) exit 2 ;; esac
done
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
nt=$(awk -v n=$size 'BEGIN {printf "%d", n}'); ni=$(awk -v n=$size 'BEGIN {printf "%d", n / 10}')
"$python" "$gen" "$nt" "$ni" impact.hdf5 >/dev/null
cat >p.yml <<YML
InitialConditions:
  file_name: impact.hdf5
TimeIntegration:
  time_end: 1e30
Snapshots:
  subdir: out
  delta_time: 1e30
Materials:
  101: {}
SPH:
  resolution_eta: 1.2348
  CFL_condition: 0.2
  viscosity_alpha: 1.5
YML
printf "# %s on %s (%s), %s steps measured (0: estimated costs), %s threads\n" \
  "$("$build/bolide" --version | head -1)" "$(uname -n)" \
  "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" "$steps" "$threads"
for c in $cells; do
  for r in $ranks; do
    echo "# top-level cells per side: $c, ranks: $r"
    "$build/bolide" --partition "$r" --partition-method all -t "$threads" -n "$steps" \
      -P Scheduler:max_top_level_cells:"$c" p.yml 2>/dev/null | grep '^partition'
  done
done
