#!/usr/bin/env bash
# The domain decomposition of the planetary reference impact (issue 22,
# theory/mpi.md): bolide --partition over 2, 4, 8 ... ranks with every
# method (METIS, Morton ranges, slabs), for several top-level grids, with the
# estimated costs and (with -m) the costs measured over STEPS steps.  Prints
# the partition lines of bolide (imbalance, edge cut, halo, pieces).
#
# Usage: BOLIDE_BENCH_IC=.../make_impact_ic.py tools/bench/decomp.sh
#          [-n 1e5] [-r "2 4 8"] [-c "16 64"] [-m STEPS] [-t THREADS]
#
# With -a (scaling on paper, theory/mpi.md): no IC file and no run; the
# per-cell counts of the impact of -n particles come from the generator's
# analytic layout (tools/bench/impact_counts.py), METIS partitions them over
# each rank count of -r (bolide --partition-counts), and
# tools/bench/decomp_model.py prints the table of imbalance, halo, bytes and
# estimated step time and draws decomp_scaling.png (in -o DIR, default .):
#   tools/bench/decomp.sh -a -n 1e8 -c 640 -r "2 4 8 16 32 64 128 256 512 1024"
# (about 10 minutes and 2 GB on 2 cores; -x "ARGS": more decomp_model.py options)
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
size=1e5; ranks="2 4 8"; cells="16 64"; steps=0; threads=$(nproc); counts=0; outdir=.; extra=""
while getopts "n:r:c:m:t:ao:x:" o; do
  case $o in n) size=$OPTARG ;; r) ranks=$OPTARG ;; c) cells=$OPTARG ;; m) steps=$OPTARG ;;
             t) threads=$OPTARG ;; a) counts=1 ;; o) outdir=$OPTARG ;; x) extra=$OPTARG ;;
             *) exit 2 ;; esac
done
nt=$(awk -v n="$size" 'BEGIN {printf "%d", n}'); ni=$(awk -v n="$size" 'BEGIN {printf "%d", n / 10}')
if [ $counts = 1 ]; then
  # scaling on paper: -n is the target's particles, the impactor has a tenth
  mkdir -p "$outdir"
  printf "# %s on %s, counts of make_impact_ic.py %s %s (analytic layout)\n" \
    "$("$build/bolide" --version | head -1)" "$(uname -n)" "$nt" "$ni"
  for c in $cells; do
    d="$outdir/cells$c"
    mkdir -p "$d"
    "$python" "$top/tools/bench/impact_counts.py" --cells "$c" "$nt" "$ni" "$d/counts.txt"
    for r in $ranks; do
      "$build/bolide" --partition "$r" --partition-counts "$d/counts.txt" \
        --partition-method metis >"$d/ranks_$r.txt"
      grep -E '^(partition: method|exchange:)' "$d/ranks_$r.txt"
    done
    # shellcheck disable=SC2086
    "$python" "$top/tools/bench/decomp_model.py" "$d" --plot "$d/decomp_scaling.png" $extra
  done
  exit 0
fi
gen=${BOLIDE_BENCH_IC:?"set BOLIDE_BENCH_IC to the reference impact IC generator (make_impact_ic.py)"}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
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
