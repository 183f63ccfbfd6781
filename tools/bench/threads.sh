#!/usr/bin/env bash
# Strong scaling in threads: particle updates per second and parallel
# efficiency for a uniform box of 1e5 and 1e6 particles (ideal gas, every
# particle active), a uniform ideal-gas sphere, and the planetary reference
# impact of theory/validation.md (Tillotson granite, 1.1e5 particles) when its
# generator is found.  Every figure is the median of REPEAT runs of STEPS
# steps (the initial force computation excluded: it is timed apart by
# bolide's "done:" line).
#
# Usage: tools/bench/threads.sh [-t "1 2 4 ..."] [-r REPEAT] [-s STEPS] [-n "1e5 1e6"]
# Environment: BOLIDE_BUILD (default: _build), PYTHON (default: the build's venv).
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
threads="1 $(nproc)"
repeat=3
steps=3
sizes="1e5 1e6"
while getopts "t:r:s:n:" o; do
  case $o in t) threads=$OPTARG ;; r) repeat=$OPTARG ;; s) steps=$OPTARG ;; n) sizes=$OPTARG ;;
             *) echo "usage: $0 [-t THREADS] [-r REPEAT] [-s STEPS] [-n SIZES]" >&2; exit 2 ;; esac
done
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"

params() { # params FILE IC [extra YAML]
  cat >"$1" <<YML
InitialConditions:
  file_name: $2
  periodic: ${4:-false}
TimeIntegration:
  time_end: 1e30
Snapshots:
  subdir: out
  delta_time: 1e30
$3
YML
}

# median wall time per step of `bolide -n STEPS` over REPEAT runs
time_per_step() { # time_per_step PARAMS THREADS
  for r in $(seq "$repeat"); do
    "$build/bolide" -n "$steps" -t "$2" "$1" >run.log 2>&1 || { tail -3 run.log >&2; exit 1; }
    # the step lines: "step time dt updates wall ETA"
    awk '$1 ~ /^[0-9]+$/ && NF == 6 {s += $5; n++} END {printf "%.6f\n", s / n}' run.log
  done | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'
}

cases=""
for n in $sizes; do
  side=$(awk -v n=$n 'BEGIN {printf "%d", n ^ (1 / 3) + 0.5}')
  "$build/bolide-ic" box --n "$side" --size 1 --u 1 --perturb 0.1 --periodic -o "box_$n.hdf5" >/dev/null
  params "box_$n.yml" "box_$n.hdf5" "" true
  cases="$cases box_$n"
done
# a uniform ideal-gas sphere of ~1e5 particles in an open box
"$python" - <<'PY'
import h5py, numpy as np
n = 58; dx = 1.0 / n
g = (np.arange(-n, n) + 0.5) * dx
x, y, z = np.meshgrid(g, g, g, indexing="ij")
r = np.sqrt(x**2 + y**2 + z**2)
keep = r < 0.5
pos = np.stack([x[keep], y[keep], z[keep]], axis=1) + 1.0
N = len(pos)
with h5py.File("sphere.hdf5", "w") as f:
    h = f.create_group("Header")
    h.attrs["BoxSize"] = [2.0, 2.0, 2.0]
    h.attrs["NumPart_Total"] = [N, 0, 0, 0, 0, 0]
    p = f.create_group("PartType0")
    p["Coordinates"] = pos
    p["Velocities"] = np.zeros_like(pos)
    p["Masses"] = np.full(N, dx**3)
    p["SmoothingLengths"] = np.full(N, 1.2348 * dx)
    p["InternalEnergies"] = np.full(N, 0.05)
    p["ParticleIDs"] = np.arange(1, N + 1)
PY
params sphere.yml sphere.hdf5 ""
cases="$cases sphere"
impact_gen=${BOLIDE_BENCH_IC:-}
if [ -f "$impact_gen" ]; then
  "$python" "$impact_gen" 100000 10000 impact.hdf5 >/dev/null
  params impact.yml impact.hdf5 "Materials:
  101: {}"
  cases="$cases impact"
fi

printf "# Bolide %s, %s, %s\n" "$("$build/bolide" --version | head -1)" "$(uname -n)" "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
printf "# median of %d runs of %d steps; every particle active\n" "$repeat" "$steps"
printf "%-12s %10s %8s %12s %14s %10s\n" case N threads s/step updates/s efficiency
for c in $cases; do
  N=$("$python" -c "import h5py; print(len(h5py.File('$c.hdf5', 'r')['PartType0/Masses']))")
  base=""
  for t in $threads; do
    s=$(time_per_step "$c.yml" "$t")
    rate=$(awk -v n=$N -v s=$s 'BEGIN {printf "%.3e", n / s}')
    [ -n "$base" ] || base=$(awk -v s=$s -v t=$t 'BEGIN {print s * t}')
    eff=$(awk -v b=$base -v s=$s -v t=$t 'BEGIN {printf "%.2f", b / (s * t)}')
    printf "%-12s %10d %8d %12.4f %14s %10s\n" "$c" "$N" "$t" "$s" "$rate" "$eff"
  done
done
