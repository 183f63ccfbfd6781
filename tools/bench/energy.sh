#!/usr/bin/env bash
# The conservation budget of the planetary reference impact of theory/validation.md
# (two Tillotson granite spheres, 2 km/s at 45 degrees, hydro + self-gravity,
# SWIFT's settings: cubic spline eta 1.2348, CFL 0.2, alpha 1.5, theta 0.5,
# softening = lattice spacing, `101: {}` with the library's defaults) run to
# time_end: |dE| / |E_pot(0)| (E_tot plus what left the box, nothing else
# added back) and |dL| / |L| at each statistics time, on the CPU and/or the
# GPU.  SWIFT's figures (theory/validation.md, "Benchmarks"): 3.6e-4 at 2000 s, 5.6e-4
# at 4000 s, |dL| / L 2.5e-4.
#
# Usage: tools/bench/energy.sh [-n "2.2e4 1.1e5"] [-m "cpu gpu"] [-t THREADS]
#                              [-T 4000] [-o OUTDIR]
#   -m  cpu: --no-gpu; gpu: the defaults with a GPU (the build must have CUDA);
#       cpu-bins, gpu-bins: the same with individual time steps
#       (TimeIntegration:global_step: false); cpu-binsall: cpu-bins with
#       self-gravity for every particle at every step (Gravity:active_only:
#       false, as the GPU computes it); cpu-binsw: cpu-bins with the
#       limiter's wakes decided in the density phase
#       (TimeIntegration:limiter_wake: density, CPU only); cpu-rk2, gpu-rk2, cpu-pc, gpu-pc:
#       the global step with the integrators TimeIntegration:scheme rk2
#       (its default error bound) and pc (theory/integrators.md)
#   -S DIR: SWIFT too, after Bolide's modes (DIR: a SWIFT build configured
#       with --with-hydro=planetary --with-equation-of-state=planetary
#       --with-kernel=cubic-spline, holding swift): the same IC, SWIFT's
#       settings of the benchmark set (eta 1.2348, CFL 0.2, alpha 1.5,
#       adaptive MAC epsilon_fmm 1e-3, theta 0.5, the same softening, 16^3
#       top-level cells) and its own time bins (dt_max 1000 s, or the run's
#       length if shorter), with as many
#       threads; its statistics every 100 s give the same columns (E_kin +
#       E_int + E_pot against abs(E_pot(0)); L of its "comoving angular
#       momentum", here the box frame's).  SWIFT removes particles that
#       leave the box without counting what they carried: its columns are
#       the budget only until the first ones leave (about 4500 s at 2.2e4
#       particles).  Build Bolide with --with-kernel=cubic-spline for the
#       same kernel.
# Columns: abs_dL/L about the box's origin (its corner), as the statistics
# file has it; dL/L_com about the start's centre of mass (L - c x p, c
# fixed), where a momentum error does not count again at the lever arm of
# the corner (the end-of-run budget line prints both).
# BOLIDE_RUN_FLAGS adds options to each run (-P SECTION:KEY:VALUE).
set -euo pipefail
# ENERGY_ETA: SPH:resolution_eta (default SWIFT's 1.2348 for the cubic spline;
# empty: the build kernel's default eta, e.g. Wendland C2's 1.7)
eta=${ENERGY_ETA-1.2348}
etaline=""; [ -n "$eta" ] && etaline="  resolution_eta: $eta
"
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
gen=${BOLIDE_BENCH_IC:?"set BOLIDE_BENCH_IC to the reference impact IC generator of the benchmark set (make_impact_ic.py; theory/validation.md, Benchmarks)"}
sizes="2.2e4"; modes="cpu"; threads=$(nproc); tend=4000; out=""; swift=""
while getopts "n:m:t:T:o:S:" o; do
  case $o in n) sizes=$OPTARG ;; m) modes=$OPTARG ;; t) threads=$OPTARG ;; T) tend=$OPTARG ;;
             o) out=$OPTARG ;; S) swift=$OPTARG ;; *) exit 2 ;; esac
done
if [ -n "$swift" ]; then
  # shellcheck source=tools/bench/swift_params.sh
  . "$top/tools/bench/swift_params.sh"
  swift=$(cd "$swift" && pwd)
  [ -x "$swift/swift" ] || { echo "energy.sh: error: no swift in $swift (-S)" >&2; exit 1; }
fi
[ -f "$gen" ] || { echo "energy.sh: error: $gen not found (set BOLIDE_BENCH_IC)" >&2; exit 1; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
printf "# %s on %s (%s), %s threads\n" "$("$build/bolide" --version | head -1)" "$(uname -n)" \
  "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" "$threads"
printf "%-8s %-8s %8s %14s %12s %12s %10s %8s %10s\n" N mode t dE/abs_Epot0 abs_dL/L dL/L_com removed steps wall_s
for n in $sizes; do
  nt=$(awk -v n=$n 'BEGIN {printf "%d", n * 10 / 11}'); ni=$(awk -v n=$n 'BEGIN {printf "%d", n / 11}')
  "$python" "$gen" "$nt" "$ni" impact.hdf5 >ic.log
  soft=$(awk '/suggested softening/ {print $NF * 1e6}' ic.log)
  N=$(awk '/N_target=/ {sub(/.*N=/, ""); print}' ic.log)
  # the IC's centre of mass [m]: the fixed point of the second angular-momentum column
  com=$("$python" - impact.hdf5 <<'PY'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1], "r") as f:
    ul = float(f["Units"].attrs["Unit length in cgs (U_L)"]) / 100.0
    x = f["PartType0/Coordinates"][...] * ul
    m = f["PartType0/Masses"][...].astype(float)
print(*(m @ x / m.sum()))
PY
)
  for m in $modes; do
    base=${m%-bins}; base=${base%-binsall}; base=${base%-binsw}; base=${base%-rk2}; base=${base%-pc}
    gpu="--no-gpu"; [ "$base" = gpu ] && gpu=""
    glob=true; case $m in *-bins | *-binsall | *-binsw) glob=false ;; esac
    wake=force; [ "${m%-binsw}" != "$m" ] && wake=density
    scheme=kdk; case $m in *-rk2) scheme=rk2 ;; *-pc) scheme=pc ;; esac
    active=true; [ "${m%-binsall}" != "$m" ] && active=false
    cat >p.yml <<YML
InitialConditions:
  file_name: impact.hdf5
TimeIntegration:
  time_end: $tend
  global_step: $glob
  limiter_wake: $wake
  scheme: $scheme
Snapshots:
  subdir: out_$m
  delta_time: 1e30
Statistics:
  delta_time: 100
Materials:
  101: {}
SPH:
$etaline  CFL_condition: 0.2
  viscosity_alpha: 1.5
Gravity:
  enabled: true
  theta_cr: 0.5
  softening: $soft
  active_only: $active
Scheduler:
  max_top_level_cells: 16
YML
    w0=$(date +%s.%N)
    "$build/bolide" $gpu ${BOLIDE_RUN_FLAGS:-} -t "$threads" p.yml >run_$m.log 2>&1 || { tail -3 run_$m.log >&2; exit 1; }
    w1=$(date +%s.%N)
    [ -n "$out" ] && { mkdir -p "$out"; cp out_$m/statistics.txt "$out/stats_${N}_$m.txt"; cp run_$m.log "$out/run_${N}_$m.log"; }
    steps=$(awk '/^\[.*done:/ {print $5}' run_$m.log)
    "$python" - "$N" "$m" "$steps" "$(awk -v a=$w0 -v b=$w1 'BEGIN {print b - a}')" out_$m/statistics.txt $com <<'PY'
import sys
import numpy as np
N, mode, steps, wall, path = sys.argv[1:6]
com = np.array([float(v) for v in sys.argv[6:9]])
names = None
for line in open(path):
    if line.startswith("# step"):
        names = line[1:].split()
d = np.loadtxt(path, comments="#", ndmin=2)
c = {k: d[:, i] for i, k in enumerate(names)}
Ep = abs(c["E_pot"][0])
dE = np.abs(c["E_tot"] + c["E_removed"] - c["E_tot"][0]) / Ep
L = np.stack([c[k] + c[k + "_removed"] for k in ("Lx", "Ly", "Lz")], 1)
dL = np.linalg.norm(L - L[0], axis=1) / np.linalg.norm(L[0])
# about the start's centre of mass (fixed): L - com x p, so that a momentum
# error does not count again at the lever arm of the box's corner
P = np.stack([c[k] + c[k + "_removed"] for k in ("px", "py", "pz")], 1)
Lc = L - np.cross(com, P)
dLc = np.linalg.norm(Lc - Lc[0], axis=1) / np.linalg.norm(Lc[0])
for t in sorted({1000.0, 2000.0, 3000.0, 4000.0, float(c["time"][-1])} | {5000.0 * q for q in range(1, int(c["time"][-1] // 5000) + 1)}):
    k = np.argmin(np.abs(c["time"] - t))
    if abs(c["time"][k] - t) > 60:
        continue
    print(f"{N:8s} {mode:8s} {c['time'][k]:8.0f} {dE[k]:14.3e} {dL[k]:12.3e} {dLc[k]:12.3e} {int(c['n_removed'][k]):10d} "
          f"{steps:>8s} {float(wall):10.1f}")
PY
  done
  [ -n "$swift" ] || continue
  # SWIFT with its own time bins on the same IC (units of make_impact_ic.py: 1e24 kg, 1e6 m, 1 s)
  seps=$(awk -v e="$soft" 'BEGIN {printf "%.6g", e / 1e6}')
  swift_params impact.hdf5 "$tend" "$(awk -v t="$tend" 'BEGIN {print (t < 1000 ? t : 1000)}')" 100 "$seps" 16 1.0 >swift.yml
  rm -f statistics.txt
  w0=$(date +%s.%N)
  "$swift/swift" --hydro --self-gravity --threads="$threads" swift.yml >run_swift.log 2>&1 ||
    { tail -5 run_swift.log >&2; echo "energy.sh: SWIFT failed (log above)" >&2; exit 1; }
  w1=$(date +%s.%N)
  [ -n "$out" ] && { mkdir -p "$out"; cp statistics.txt "$out/stats_${N}_swift.txt"; cp run_swift.log "$out/run_${N}_swift.log"; }
  steps=$(awk '$1 ~ /^[0-9]+$/ && NF >= 15 {s = $1} END {print s}' run_swift.log)
  "$python" - "$N" "$steps" "$(awk -v a=$w0 -v b=$w1 'BEGIN {print b - a}')" statistics.txt <<'PY'
import sys
import numpy as np
N, steps, wall, path = sys.argv[1:5]
d = np.loadtxt(path, comments="#", ndmin=2)
# SWIFT's columns: (1) time, (13) E_kin, (14) E_int, (15) E_pot, (24-26) angular momentum
t, E = d[:, 1], d[:, 13] + d[:, 14] + d[:, 15]
dE = np.abs(E - E[0]) / abs(d[0, 15])
L = d[:, 24:27]
dL = np.linalg.norm(L - L[0], axis=1) / np.linalg.norm(L[0])
# about the start's centre of mass, (18-20), with the momentum (21-23); SWIFT
# counts no removed particles, so after the first ones leave the box its
# columns lose what they carried
Lc = L - np.cross(d[0, 18:21], d[:, 21:24])
dLc = np.linalg.norm(Lc - Lc[0], axis=1) / np.linalg.norm(Lc[0])
for tt in sorted({1000.0, 2000.0, 3000.0, 4000.0, float(t[-1])} | {5000.0 * q for q in range(1, int(t[-1] // 5000) + 1)}):
    k = np.argmin(np.abs(t - tt))
    if abs(t[k] - tt) > 60:
        continue
    print(f"{N:8s} {'swift':8s} {t[k]:8.0f} {dE[k]:14.3e} {dL[k]:12.3e} {dLc[k]:12.3e} {'-':>10s} {steps:>8s} {float(wall):10.1f}")
PY
done
