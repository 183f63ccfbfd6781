#!/usr/bin/env bash
# The planetary reference impact of theory/validation.md (Tillotson granite spheres,
# 2 km/s, 45 degrees; the IC generator is make_impact_ic.py):
# seconds per step with every particle active, hydro only and (when the
# build has self-gravity) hydro + gravity, at each thread count; median of
# REPEAT runs of STEPS steps.  Compare with SWIFT's figures in
# theory/validation.md as ratios measured on the same machine.
#
# Usage: tools/bench/impact.sh [-n "1e5 1e6"] [-t "1 2"] [-r 3] [-s 3] [-g] [-w DIR]
#   -g  also hydro + gravity
#   -w  write the IC of the first size and its hydro p.yml into DIR and stop
#       (the set-up that tools/bench/param_ab.sh times)
# BOLIDE_RUN_FLAGS adds options to each run (--no-gpu: the CPU path of a
# build with CUDA).
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
gen=${BOLIDE_BENCH_IC:?"set BOLIDE_BENCH_IC to the reference impact IC generator of the benchmark set (make_impact_ic.py; theory/validation.md, Benchmarks)"}
sizes="1e5"; threads="1 $(nproc)"; repeat=3; steps=3; gravity=0; writeto=""
while getopts "n:t:r:s:gw:" o; do
  case $o in n) sizes=$OPTARG ;; t) threads=$OPTARG ;; r) repeat=$OPTARG ;; s) steps=$OPTARG ;;
             g) gravity=1 ;; w) writeto=$OPTARG ;; *) exit 2 ;; esac
done
[ -f "$gen" ] || { echo "impact.sh: error: $gen not found (set BOLIDE_BENCH_IC)" >&2; exit 1; }
if [ -n "$writeto" ]; then
  mkdir -p "$writeto" && cd "$writeto"
else
  work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
  cd "$work"
fi
[ -n "$writeto" ] || printf "# %s on %s (%s)\n" "$("$build/bolide" --version | head -1)" "$(uname -n)" \
  "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
if [ -z "$writeto" ]; then
  printf "# median of %d runs of %d steps, every particle active\n" "$repeat" "$steps"
  printf "%-10s %-16s %8s %12s %16s\n" N physics threads s/step updates/s/core
fi
for n in $sizes; do
  nt=$(awk -v n=$n 'BEGIN {printf "%d", n * 10 / 11}'); ni=$(awk -v n=$n 'BEGIN {printf "%d", n / 11}')
  "$python" "$gen" "$nt" "$ni" impact.hdf5 >/dev/null
  N=$("$python" -c "import h5py; print(len(h5py.File('impact.hdf5', 'r')['PartType0/Masses']))")
  variants="hydro"; [ $gravity = 1 ] && variants="hydro hydro+gravity"
  for v in $variants; do
    grav=false; [ "$v" = hydro+gravity ] && grav=true
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
Gravity:
  enabled: $grav
  theta_cr: 0.5
Scheduler:
  max_top_level_cells: 16
YML
    [ -n "$writeto" ] && exit 0
    for t in $threads; do
      s=$(for r in $(seq "$repeat"); do
            "$build/bolide" ${BOLIDE_RUN_FLAGS:-} -n "$steps" -t "$t" p.yml >run.log 2>&1 || { tail -3 run.log >&2; exit 1; }
            awk '$1 ~ /^[0-9]+$/ && NF == 6 {s += $5; n++} END {printf "%.6f\n", s / n}' run.log
          done | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
      printf "%-10d %-16s %8d %12.4f %16.3e\n" "$N" "$v" "$t" "$s" "$(awk -v n=$N -v s=$s -v t=$t 'BEGIN {print n / s / t}')"
    done
  done
done
