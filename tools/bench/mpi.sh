#!/usr/bin/env bash
# Multi-rank runs against threads (issue 22, theory/mpi.md "Multi-rank
# runs"): the planetary reference impact (make_impact_ic.py of the benchmark
# set; hydrodynamics only, with -g hydrodynamics and self-gravity) for
# STEPS steps, every particle active, in each layout RxT of -c (R MPI ranks
# of T threads each: mpirun -n R bolide -t T), the layouts alternating
# within each of REPEAT rounds so that the load of a shared machine falls on
# all alike (mpirun --bind-to none: OpenMPI binds a rank to one core by
# default, which would leave a rank of T threads one core).  Prints, per layout, the median wall seconds per step (the steps
# after the first of rank 0's step lines) and the ratio to the first layout.
# With -w the weak scaling: N particles per rank (R x N in all).
#
# With -S DIR, SWIFT too (DIR: a SWIFT build configured with --enable-mpi
# --with-hydro=planetary --with-equation-of-state=planetary
# --with-kernel=cubic-spline, holding swift_mpi): the same IC and layouts,
# SWIFT's settings of the benchmark set (eta 1.2348, CFL 0.2, alpha 1.5;
# with -g FMM gravity, adaptive MAC epsilon_fmm 1e-3, theta_cr 0.5, softening
# the lattice spacing), dt_max 1 s so that every step updates every
# particle, the mean of its step lines' wall-clock column over the same
# steps; printed beside Bolide's as the ratio Bolide / SWIFT.  Bolide then
# runs with dt_max 1 s too (the h iteration's work depends on the step),
# and with -g at SWIFT's accuracy (the benchmark set's measurement: Bolide's
# epsilon_fmm 2.5e-5 gives SWIFT's median and 99th-percentile force errors
# at its 1e-3), theta_cr 0.5 and the same softening.
#
# With -G every rank runs its FORCE phases on a GPU (--gpu; a build with
# --with-mpi --with-cuda): rank k of a node on its device k modulo the
# node's GPUs (theory/mpi.md, "GPUs on several ranks"). With -g too, each
# rank computes self-gravity on its GPU before the GPU's hydrodynamics (the
# upward pass, the walks and the interactions; the walks with the other
# ranks' records on its CPU workers), each layout as a user gets it.
#
# Usage: BOLIDE_BENCH_IC=.../make_impact_ic.py BOLIDE_BUILD=_build_mpi \
#          tools/bench/mpi.sh [-n 1.1e5] [-c "1x2 2x1"] [-s 5] [-r 3] [-m 16] [-w] [-g] [-G] [-S DIR]
#   -m: Scheduler:max_top_level_cells (the decomposition's grid)
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build_mpi}
python=${PYTHON:-$top/_build/.venv/bin/python}
gen=${BOLIDE_BENCH_IC:?"set BOLIDE_BENCH_IC to the reference impact IC generator of the benchmark set (make_impact_ic.py; theory/validation.md, Benchmarks)"}
n=1.1e5; layouts="1x2 2x1"; steps=5; repeat=3; cells=16; weak=0; gravity=false; swift=""; gpu=--no-gpu
while getopts "n:c:s:r:m:wgGS:" o; do
  case $o in n) n=$OPTARG ;; c) layouts=$OPTARG ;; s) steps=$OPTARG ;; r) repeat=$OPTARG ;;
             m) cells=$OPTARG ;; w) weak=1 ;; g) gravity=true ;; G) gpu=--gpu ;; S) swift=$OPTARG ;;
             *) exit 2 ;; esac
done
if [ -n "$swift" ]; then
  swift=$(cd "$swift" && pwd)
  [ -x "$swift/swift_mpi" ] || { echo "mpi.sh: no swift_mpi in $swift (-S)" >&2; exit 1; }
fi
build=$(cd "$build" && pwd)
grep -q '^#define HAVE_MPI 1' "$build/config.h" ||
  { echo "mpi.sh: $build is not built with --with-mpi" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export BOLIDE_SRCDIR=${BOLIDE_SRCDIR:-$top}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
ic() { # ic N FILE
  local nt ni
  nt=$(awk -v n="$1" 'BEGIN {printf "%d", n * 10 / 11}'); ni=$(awk -v n="$1" 'BEGIN {printf "%d", n / 11}')
  [ -f "$2" ] || "$python" "$gen" "$nt" "$ni" "$2" >/dev/null
}
# SWIFT's parameters for IC (the units of make_impact_ic.py's file: 1e24 kg,
# 1e6 m, 1 s; softening the lattice spacing of its target, 3.4729e4 m at
# 1e5 target particles, scaled by N^(-1/3))
swift_eps() { # [m]
  awk -v n="$n" 'BEGIN {printf "%.6g", 3.4729e4 * (1e5 / (n * 10 / 11)) ^ (1 / 3)}'
}
# shellcheck source=tools/bench/swift_params.sh
. "$top/tools/bench/swift_params.sh"
printf "# %s on %s (%s, %s cores), %s, %s, median of %d rounds of %d steps, every particle active\n" \
  "checkout $(git -C "$top" rev-parse --short HEAD), build $("$build/bolide" --version 2>/dev/null |
    sed -n 's/.*(git \([^)]*\)).*/\1/p;q') (the git version configure recorded)" "$(uname -n)" \
  "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" "$(nproc)" \
  "$([ $weak = 1 ] && echo "weak scaling, $n particles per rank" || echo "$n particles")" \
  "$([ $gravity = true ] && echo "hydrodynamics and self-gravity" || echo "hydrodynamics only")$([ $gpu = --gpu ] &&
    echo ", a GPU per rank ($(nvidia-smi --query-gpu=name --format=csv,noheader 2>/dev/null | sort | uniq -c |
      sed 's/^ *//' | paste -sd, -))")" \
  "$repeat" "$steps"
for r in $(seq "$repeat"); do
  for l in $layouts; do
    R=${l%x*}; T=${l#*x}
    N=$n; [ $weak = 1 ] && N=$(awk -v n="$n" -v r="$R" 'BEGIN {printf "%g", n * r}')
    ic "$N" "impact_$N.hdf5"
    cat >p.yml <<YML
InitialConditions:
  file_name: impact_$N.hdf5
TimeIntegration:
  time_end: 1e30$([ -n "$swift" ] && printf '\n  dt_max: 1')
Snapshots:
  subdir: out_$l
  delta_time: 1e30
Materials:
  101: {}
Gravity:
  enabled: $gravity$([ -n "$swift" ] && printf '\n  theta_cr: 0.5\n  epsilon_fmm: 2.5e-5\n  softening: %s' "$(swift_eps)")
SPH:
  resolution_eta: 1.2348
Scheduler:
  max_top_level_cells: $cells
YML
    mpirun --bind-to none -n "$R" "$build/bolide" "$gpu" -n $((steps + 1)) -t "$T" p.yml >run.log 2>&1 ||
      { tail -5 run.log >&2; echo "mpi.sh: bolide failed in layout $l (log above)" >&2; exit 1; }
    awk -v l="$l" '$1 ~ /^[0-9]+$/ && NF == 6 && $1 > 1 {s += $5; c++} END {printf "%s %.6f\n", l, s / c}' \
      run.log >>times
    [ -n "$swift" ] || continue
    swift_params "impact_$N.hdf5" 1e5 1 1e10 "$(awk -v e="$(swift_eps)" 'BEGIN {printf "%.6g", e / 1e6}')" "$cells" >swift.yml
    # (SWIFT's step 0 is its initial force computation; -n S runs steps 1 .. S + 1)
    mpirun --bind-to none -n "$R" "$swift/swift_mpi" --hydro $([ $gravity = true ] && echo --self-gravity) \
      --threads="$T" -n "$steps" swift.yml >swift.log 2>&1 ||
      { tail -5 swift.log >&2; echo "mpi.sh: SWIFT failed in layout $l (log above)" >&2; exit 1; }
    awk -v l="swift:$l" '$1 ~ /^[0-9]+$/ && NF >= 15 && $1 > 1 {s += $13 / 1000; c++}
      END {printf "%s %.6f\n", l, s / c}' swift.log >>times
  done
done
first=""
[ -z "$swift" ] || printf "# Bolide: %s; SWIFT: %s (%s)\n" "$build/bolide" "$swift/swift_mpi" \
  "$("$swift/swift_mpi" --version 2>/dev/null | grep -m1 -i 'revision\|git' | sed 's/^ *//')"
for l in $layouts; do
  med=$(awk -v l="$l" '$1 == l {print $2}' times | sort -g | awk '{x[NR] = $1} END {print x[int((NR + 1) / 2)]}')
  all=$(awk -v l="$l" '$1 == l {printf "%s ", $2}' times)
  [ -n "$first" ] || first=$med
  printf "%-6s ranks x threads  %10.4f s/step  ratio to %s %.3f   (runs: %s)\n" "$l" "$med" \
    "${layouts%% *}" "$(awk -v a="$med" -v b="$first" 'BEGIN {print a / b}')" "$all"
done
[ -n "$swift" ] || exit 0
first=""
for l in $layouts; do
  med=$(awk -v l="swift:$l" '$1 == l {print $2}' times | sort -g | awk '{x[NR] = $1} END {print x[int((NR + 1) / 2)]}')
  bol=$(awk -v l="$l" '$1 == l {print $2}' times | sort -g | awk '{x[NR] = $1} END {print x[int((NR + 1) / 2)]}')
  all=$(awk -v l="swift:$l" '$1 == l {printf "%s ", $2}' times)
  [ -n "$first" ] || first=$med
  printf "SWIFT %-6s ranks x threads  %10.4f s/step  ratio to %s %.3f   Bolide / SWIFT %.3f   (runs: %s)\n" \
    "$l" "$med" "${layouts%% *}" "$(awk -v a="$med" -v b="$first" 'BEGIN {print a / b}')" \
    "$(awk -v a="$bol" -v b="$med" 'BEGIN {print a / b}')" "$all"
done
