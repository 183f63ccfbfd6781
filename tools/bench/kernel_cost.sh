#!/usr/bin/env bash
# The cost of the default kernel against the former one: seconds per step of
# the planetary reference impact of theory/validation.md (Tillotson granite spheres,
# 2 km/s at 45 degrees, make_impact_ic.py) in two builds, each
# with its own default SPH:resolution_eta (Wendland C2: 1.7, 149
# neighbours; cubic spline: 1.2348, 48), hydro only and hydro + gravity,
# every particle active (the first STEPS steps), on the CPU.  The runs of
# the two builds alternate within one invocation (REPEAT rounds), so that
# the load of a shared machine falls on both alike; the medians and their
# ratio are printed: wall seconds per step (the run log's steps) and CPU
# seconds per step (user + sys of a run of 1 + STEPS steps minus that of a
# run of 1 step, over STEPS: what a loaded machine's share does not change).
#
# Usage: tools/bench/kernel_cost.sh -a BUILD_A -b BUILD_B [-n 2.2e4] [-t 2]
#                                   [-r 3] [-s 3]
#   e.g. tools/bench/kernel_cost.sh -a _build_cubic -b _build
# (any two builds: also the cost of a change, A the build before it)
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
python=${PYTHON:-$top/_build/.venv/bin/python}
gen=${BOLIDE_BENCH_IC:?"set BOLIDE_BENCH_IC to the reference impact IC generator of the benchmark set (make_impact_ic.py; theory/validation.md, Benchmarks)"}
a=""; b=""; n=2.2e4; threads=$(nproc); repeat=3; steps=3
while getopts "a:b:n:t:r:s:" o; do
  case $o in a) a=$OPTARG ;; b) b=$OPTARG ;; n) n=$OPTARG ;; t) threads=$OPTARG ;;
             r) repeat=$OPTARG ;; s) steps=$OPTARG ;; *) exit 2 ;; esac
done
[ -n "$a" ] && [ -n "$b" ] || { echo "kernel_cost.sh: -a BUILD_A -b BUILD_B needed" >&2; exit 2; }
[ -f "$gen" ] || { echo "kernel_cost.sh: error: $gen not found (set BOLIDE_BENCH_IC)" >&2; exit 1; }
a=$(cd "$a" && pwd); b=$(cd "$b" && pwd)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
nt=$(awk -v n=$n 'BEGIN {printf "%d", n * 10 / 11}'); ni=$(awk -v n=$n 'BEGIN {printf "%d", n / 11}')
"$python" "$gen" "$nt" "$ni" impact.hdf5 >/dev/null
N=$("$python" -c "import h5py; print(len(h5py.File('impact.hdf5', 'r')['PartType0/Masses']))")
printf "# %s on %s (%s), %s threads, N = %s\n" "$(git -C "$top" rev-parse --short HEAD)" "$(uname -n)" \
  "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" "$threads" "$N"
printf "# median of %d runs of %d steps, every particle active; builds alternate\n" "$repeat" "$steps"
for v in hydro hydro+gravity; do
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
Gravity:
  enabled: $grav
  theta_cr: 0.5
Scheduler:
  max_top_level_cells: 16
YML
  for r in $(seq "$repeat"); do
    for build in "$a" "$b"; do
      /usr/bin/time -f "%U %S" -o cpu1 "$build/bolide" --no-gpu -n 1 -t "$threads" p.yml >run1.log 2>&1 ||
        { tail -3 run1.log >&2; exit 1; }
      /usr/bin/time -f "%U %S" -o cpu2 "$build/bolide" --no-gpu -n $((steps + 1)) -t "$threads" p.yml >run.log 2>&1 ||
        { tail -3 run.log >&2; exit 1; }
      cpu=$(awk -v s="$steps" 'NR == FNR {a = $1 + $2; next} {printf "%.6f", ($1 + $2 - a) / s}' cpu1 cpu2)
      awk -v bd="$build" -v cpu="$cpu" '$1 ~ /^[0-9]+$/ && NF == 6 && $1 > 1 {s += $5; c++}
        END {printf "%s %.6f %s\n", bd, s / c, cpu}' run.log >>"times_$v"
    done
  done
  for build in "$a" "$b"; do
    k=$("$build/bolide" --version | sed -n 's/^kernel: //p')
    eta=$("$build/bolide" --param-reference | awk '/^[A-Za-z]/ {s = $1} s == "SPH:" && $1 == "resolution_eta:" {print $2}')
    for col in 2 3; do
      med=$(awk -v bd="$build" -v c=$col '$1 == bd {print $c}' "times_$v" | sort -g |
            awk '{x[NR] = $1} END {print x[int((NR + 1) / 2)]}')
      all=$(awk -v bd="$build" -v c=$col '$1 == bd {printf "%s ", $c}' "times_$v")
      what=$([ $col = 2 ] && echo wall || echo CPU)
      printf "%-14s %-12s %-13s eta %-7s %-4s %10.4f s/step   (runs: %s)\n" "$v" "$(basename "$build")" "$k" "$eta" "$what" "$med" "$all"
      echo "$med" >>"med_${v}_$col"
    done
  done
  for col in 2 3; do
    what=$([ $col = 2 ] && echo wall || echo CPU)
    awk -v v="$v" -v w="$what" 'NR == 1 {x = $1} NR == 2 {printf "%-14s %-4s ratio B / A %.2f\n", v, w, $1 / x}' "med_${v}_$col"
  done
done
