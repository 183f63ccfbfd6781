#!/usr/bin/env bash
# CPU-only (every host core), GPU-only and hybrid (CPU workers beside the
# GPU) runs of the same problems, seconds per step and per derivative
# evaluation with every particle active, bus traffic and GPU memory.
#
# Problems (-p):
#   basalt   issue 7's solid reference (theory/validation.md, "Benchmarks",
#            solid-body impact on the GPU): a basalt sphere of radius 50 km hit by a basalt sphere of
#            6.25 km at 5 km/s and 45 degrees, both on a simple cubic lattice
#            (tools/bench/basalt_ic.py); Tillotson, Collins strength,
#            Grady-Kipp damage with Weibull flaws (N ln N), self-gravity with
#            opening angle 0.5; cubic spline with the support 2.8 spacings
#            (resolution_eta 1.534, about 90 neighbours)
#   gravity  the planetary reference impact of theory/validation.md (make_impact_ic.py,
#            Tillotson granite), hydro + self-gravity, the softening the
#            target's lattice spacing as the benchmark set has it (34.7 km
#            at 1.1e5, 16.1 km at 1.1e6, 7.5 km at 1.1e7; BENCH_SOFTENING
#            in metres overrides it: until 7eb3ef8 this script took 30 km
#            at every size, 1.9 spacings at 1.1e6 and 4 at 1.1e7, where the
#            pairs inside the softening's support, all summed directly,
#            made P2P most of the GPU's step)
#   impact   the same, hydro only
#   solid    the same ICs as basalt with Collins strength and damage, no gravity
#   box, sedov  periodic hydro tests
# Modes (-m): cpu (--no-gpu), gpu (Scheduler:gpu all: everything the GPU
#   can do, the CPU only where the GPU has no implementation), hybrid
#   (Scheduler:gpu auto: CPU workers run tasks while the GPU works),
#   gpu-rbhost (gpu with Scheduler:gpu_rebuild: host: every field copied
#   back, reordered on the host and uploaded at each rebuild), gpu@KEY:VALUE
#   (gpu with -P KEY:VALUE; several joined by @, e.g.
#   gpu@Gravity:gpu_reproducible:true: variants compared in one call).
# The steps are those of a run (the Courant step, SPH:CFL_condition 0.2):
# s/step is the mean wall time of the steps, rebuilds included; the
# rebuild column is the mean time of the run's rebuilds and their number.
# Median over REPEAT runs of STEPS steps (each run's mean step, the first
# force computation excluded); the evaluation time, the bus traffic and the
# GPU memory are those of the last run.  Bus: everything the run moved
# per step, and the part between the full copies of every field (start,
# rebuilds, snapshots, end), which a long run repeats every step; shares
# at 25 GB/s (PCIe 5 x16) of the median step.  Prints a markdown table and
# the GPU's stage times (with the device memory's largest uses).
#
# Usage: tools/bench/gpu.sh [-n "1e5 1e6"] [-p "basalt gravity"] [-m "cpu gpu hybrid"]
#                           [-r 3] [-s 4] [-g "GPU ARGS"] [-T SECONDS] [-S SWIFT_DIR]
#   -g  extra bolide arguments for the GPU runs only
#   -S  SWIFT beside Bolide on the same host (issue 21's benchmark): mode
#       "swift" (give it last in -m) runs SWIFT_DIR/swift (a build with
#       --with-hydro=planetary --with-equation-of-state=planetary) on the
#       same IC of the impact or gravity problem, every core, SWIFT's
#       settings of the benchmark set (tools/bench/swift_params.sh: eta
#       1.2348, CFL 0.2, alpha 1.5; epsilon_fmm 1e-3, theta 0.5) and the
#       same softening, with dt_max the mean step of the block's last Bolide
#       run and the run 2^20 such steps long: SWIFT then steps by half of
#       it, every particle in its top bin; s/step is the mean wall-clock
#       time of its steps after the first two that moved every particle
#       (SWIFT's step 0 is the first force computation; "timeout" if none
#       did), and a line after the block gives SWIFT's s/step over each
#       mode's
#   -T  time limit of each bolide run (default 0: none); a run over it is
#       killed (SIGKILL: a SIGTERM would let it finish its step and write a
#       restart file first, which at 1e7 particles takes minutes), reported
#       as "timeout", and the script goes on
# Env:   BOLIDE_BUILD (build folder), BOLIDE_BENCH_IC (make_impact_ic.py),
#        PYTHON (with numpy and h5py, for the reference impact IC),
#        BENCH_OUT (file the table lines are also appended to, as they come),
#        BENCH_KEEP (folder: the log of each case's last run, PROBLEM-N-MODE.log),
#        BENCH_IC_KEEP (folder: a copy of each generated IC, ic-PROBLEM-N.hdf5,
#        for runs beside the benchmark on the same particles),
#        BENCH_WRAP (a command put before each bolide run, e.g. a profiler:
#        "ncu --clock-control none -k regex:force -c 1"; its report lands in
#        the run's log, and the times it prints are the profiled run's)
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-python3}
gen=${BOLIDE_BENCH_IC:?"set BOLIDE_BENCH_IC to the reference impact IC generator of the benchmark set (make_impact_ic.py; theory/validation.md, Benchmarks)"}
sizes="1e5 1e6"; problems="basalt gravity"; modes="cpu gpu hybrid"; repeat=3; steps=4; gpu_args=""; tlimit=0
swift=""
while getopts "n:p:m:r:s:g:T:S:" o; do
  case $o in n) sizes=$OPTARG ;; p) problems=$OPTARG ;; m) modes=$OPTARG ;; r) repeat=$OPTARG ;;
             s) steps=$OPTARG ;; g) gpu_args=$OPTARG ;; T) tlimit=$OPTARG ;; S) swift=$OPTARG ;;
             *) exit 2 ;; esac
done
case " $modes " in
  *" swift "*) [ -n "$swift" ] && [ -x "$swift/swift" ] ||
                 { echo "gpu.sh: error: mode swift needs -S DIR holding SWIFT's swift" >&2; exit 2; }
               swift=$(cd "$swift" && pwd)
               # shellcheck source=tools/bench/swift_params.sh
               . "$top/tools/bench/swift_params.sh" ;;
esac
out=${BENCH_OUT:-/dev/null}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
ncpu=$(nproc)
say() { printf "%s\n" "$*"; printf "%s\n" "$*" >>"$out"; }
say "$(printf "# %s on %s (%s, %d cores); GPU: %s" "$("$build/bolide" --version | head -1)" "$(uname -n)" \
  "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" "$ncpu" \
  "$(nvidia-smi --query-gpu=name --format=csv,noheader 2>/dev/null | head -1)")"
say "# median of $repeat runs of $steps steps, every particle active; cpu: --no-gpu -t $ncpu; gpu: --gpu -P Scheduler:gpu:all; hybrid: --gpu -P Scheduler:gpu:auto"
say "| problem | N | mode | s/step (rebuilds included) | s/evaluation | rebuild s (count) | vs cpu | bus MB/step | bus share at 25 GB/s | between full copies MB/step (share) | GPU bytes/particle |"
say "|---|---|---|---|---|---|---|---|---|---|---|"
stages=""

# one run of bolide with the arguments "$@"; prints "step eval" or "timeout"
one() {
  local lim=()
  [ "$tlimit" = 0 ] || lim=(timeout -s KILL "$tlimit")
  local wrap=()
  [ -z "${BENCH_WRAP:-}" ] || read -ra wrap <<<"$BENCH_WRAP"
  if ! "${lim[@]}" "${wrap[@]}" "$build/bolide" -n "$steps" -t "$ncpu" "$@" p.yml >run.log 2>&1; then
    if grep -q "error" run.log; then tail -3 run.log >&2; exit 1; fi
    echo timeout; return
  fi
  awk '$1 ~ /^[0-9]+$/ && NF == 6 {s += $5; n++} END {printf "%.6f ", s / n}' run.log
  awk '/derivative evaluations/ {for (k = 1; k <= NF; k++) if ($k == "s" && $(k + 1) == "each") printf "%s ", $(k - 1)}' run.log
  awk '/rebuilds \(cells/ {for (k = 1; k <= NF; k++) if ($k == "s" && $(k + 1) == "each") {c = $(k - 2); sub(",", "", c); r = sprintf("%s(%s)", $(k - 1), c)}}
       END {print (r == "" ? "-" : r)}' run.log
}

# one SWIFT run on ic.hdf5 (mode swift); prints "step - -" or "timeout"
one_swift() {
  local lim=()
  [ "$tlimit" = 0 ] || lim=(timeout -s KILL "$tlimit")
  local phys=(--hydro)
  [ "$prob" = gravity ] && phys+=(--self-gravity)
  # (a run of 2^20 top-bin steps: the time line's top bin is dt_max itself)
  swift_params ic.hdf5 "$(awk -v d="$swift_dt" 'BEGIN {printf "%.17g", d * 1048576 * (1 - 1e-9)}')" "$swift_dt" 1e10 \
    "$(awk -v e="$soft" 'BEGIN {printf "%.6g", e / 1e6}')" 16 >swift.yml
  if ! "${lim[@]}" "$swift/swift" "${phys[@]}" --threads="$ncpu" -n "$((steps + 1))" swift.yml >swift.log 2>&1; then
    grep -qi "error" swift.log && { tail -3 swift.log >&2; exit 1; }
    echo timeout; return
  fi
  # (the steps that moved every particle: a step of a few particles, where
  # some limit fell below dt_max, is not the step measured)
  awk -v n="$N" '$1 ~ /^[0-9]+$/ && NF >= 15 && $1 > 1 && $8 == n {s += $13 / 1000; c++}
                 END {if (c) printf "%.6f - -\n", s / c; else print "timeout"}' swift.log
}

# median over the repeats of "$@"; sets med_step, last_eval
measure() {
  local res=() r
  for r in $(seq "$repeat"); do
    if [ "$1" = swift ]; then r=$(one_swift); else r=$(one "$@"); fi
    [ "$r" = timeout ] && { med_step=timeout; last_eval=-; last_rebuild=-; return; }
    res+=("$r")
  done
  med_step=$(printf "%s\n" "${res[@]}" | awk '{print $1}' | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
  last_eval=$(printf "%s\n" "${res[@]}" | tail -1 | awk '{print $2}')
  last_rebuild=$(printf "%s\n" "${res[@]}" | tail -1 | awk '{print $3}')
}

for prob in $problems; do
  for n in $sizes; do
    side=$(awk -v n=$n 'BEGIN {printf "%d", n ^ (1 / 3) + 0.5}')
    eta=1.2348; visc=1.5; mats=""; extra="  periodic: false"
    case $prob in
      box)
        "$build/bolide-ic" box --n "$side" --perturb 0.1 -o ic.hdf5 >/dev/null
        extra="  periodic: true" ;;
      sedov)
        "$build/bolide-ic" sedov --n "$side" --energy 1 --rho 1 -o ic.hdf5 >/dev/null
        extra="  periodic: true" ;;
      impact|solid|gravity)
        nt=$(awk -v n=$n 'BEGIN {printf "%d", n * 10 / 11}'); ni=$(awk -v n=$n 'BEGIN {printf "%d", n / 11}')
        "$python" "$gen" "$nt" "$ni" ic.hdf5 >ic.log
        soft=${BENCH_SOFTENING:-$(awk '/suggested softening/ {print $NF * 1e6}' ic.log)} ;;
      basalt)
        "$python" "$top/tools/bench/basalt_ic.py" "$n" ic.hdf5 1.534 >/dev/null
        nt=$(awk -v n=$n 'BEGIN {printf "%d", n * 512 / 513}')
        soft=$(awk -v n=$nt 'BEGIN {printf "%.4g", 0.5 * 5e4 * (4.18879 / n) ^ (1 / 3)}')
        eta=1.534; visc=1.0
        mats=$'Materials:\n  103: {name: basalt, strength: collins, yield_stress: 1e7, yield_stress_max: 3.5e9, friction_intact: 1.2, cohesion_damaged: 1e5, friction_damaged: 0.6, weibull_k: 5e34, weibull_m: 8}\nDamage:\n  seed: 1\nGravity:\n  enabled: true\n  theta_cr: 0.5\n  softening: '"$soft" ;;
      *) echo "gpu.sh: unknown problem $prob" >&2; exit 2 ;;
    esac
    [ -n "${BENCH_IC_KEEP:-}" ] && mkdir -p "$BENCH_IC_KEEP" && cp ic.hdf5 "$BENCH_IC_KEEP/ic-$prob-$n.hdf5"
    [ $prob = impact ] && mats=$'Materials:\n  101: {}'
    [ $prob = gravity ] && mats=$'Materials:\n  101: {}\nGravity:\n  enabled: true\n  softening: '"$soft"
    [ $prob = solid ] && mats=$'Materials:\n  101: {name: basalt, strength: collins, yield_stress: 1e7, yield_stress_max: 3.5e9, friction_intact: 1.2, cohesion_damaged: 1e5, friction_damaged: 0.6, weibull_k: 1e61, weibull_m: 16}\nDamage:\n  seed: 1'
    cat >p.yml <<YML
InitialConditions:
  file_name: ic.hdf5
$extra
TimeIntegration:
  time_end: 1e30
  dt_min: 1e-30
Snapshots:
  subdir: out
  delta_time: 1e30
Statistics:
  delta_time: 1e30
$mats
SPH:
  resolution_eta: $eta
  CFL_condition: 0.2
  viscosity_alpha: $visc
Scheduler:
  max_top_level_cells: 16
YML
    N=$(awk '/read [0-9]+ particles/ {for (k = 1; k <= NF; k++) if ($k == "read") print $(k + 1)}' \
        <("$build/bolide" --check p.yml 2>&1 || true) | head -1)
    cpu_step=""; declare -A mode_step=()
    for mode in $modes; do
      case $mode in
        swift)
          [ $prob = impact ] || [ $prob = gravity ] ||
            { echo "gpu.sh: mode swift runs the impact and gravity problems only" >&2; exit 2; }
          [ -f run.log ] || { echo "gpu.sh: give mode swift after a Bolide mode (its step)" >&2; exit 2; }
          swift_dt=$(awk '$1 ~ /^[0-9]+$/ && NF == 6 {s += $3; n++} END {printf "%.6g", s / n}' run.log)
          measure swift ;;
        cpu) measure --no-gpu ;;
        gpu) measure --gpu -P Scheduler:gpu:all $gpu_args ;;
        hybrid) measure --gpu -P Scheduler:gpu:auto $gpu_args ;;
        gpu-rbhost) measure --gpu -P Scheduler:gpu:all -P Scheduler:gpu_rebuild:host $gpu_args ;;
        gpu@*) pset=(); IFS=@ read -ra keys <<<"${mode#gpu@}"
               for k in "${keys[@]}"; do pset+=(-P "$k"); done
               measure --gpu -P Scheduler:gpu:all "${pset[@]}" $gpu_args ;;
        *) echo "gpu.sh: unknown mode $mode" >&2; exit 2 ;;
      esac
      [ $mode = cpu ] && cpu_step=$med_step
      mode_step[$mode]=$med_step
      log=run.log; [ $mode = swift ] && log=swift.log
      [ -n "${BENCH_KEEP:-}" ] && mkdir -p "$BENCH_KEEP" && cp $log "$BENCH_KEEP/$prob-$n-$mode.log"
      ratio=-; bus=-; share=-; mem=-; rec=-
      if [ "$med_step" != timeout ] && [ -n "$cpu_step" ] && [ "$cpu_step" != timeout ]; then
        ratio=$(awk -v a=$cpu_step -v b=$med_step 'BEGIN {printf "%.2f", a / b}')
      fi
      if [ $mode != cpu ] && [ $mode != swift ] && [ "$med_step" != timeout ]; then
        bus=$(awk '/^GPU \(/ {for (k = 1; k <= NF; k++) if ($k == "bus") {u = $(k + 1); d = $(k + 4)}} END {printf "%.1f", u + d}' run.log)
        share=$(awk -v b=$bus -v t=$med_step 'BEGIN {printf "%.1f%%", 100 * b * 1e6 / 25e9 / t}')
        rec=$(awk -v t=$med_step '/^GPU \(/ {for (k = 1; k <= NF; k++) if ($k == "copies") r = $(k + 1)}
              END {if (r == "") print "-"; else printf "%.1f (%.1f%%)", r, 100 * r * 1e6 / 25e9 / t}' run.log)
        mem=$(awk '/^GPU memory:/ {gsub(/\(/, ""); for (k = 1; k <= NF; k++) if ($k == "bytes") print $(k - 1)}' run.log)
        stages="$stages$prob $N $mode: $(grep '^GPU (' run.log | sed 's/^GPU ([^)]*), //' | tr '\n' ' '); $(grep '^GPU host\|^GPU gravity' run.log | tr '\n' ' ') $(grep -o 'rebuilds (cells.*' run.log | tr '\n' ' ') $(grep -o "rebuilds' cells and order.*" run.log | tr '\n' ' ') $(grep '^GPU rebuilds' run.log | tr '\n' ' ') $(grep '^GPU memory by use' run.log | cut -c1-300)"$'\n'
      fi
      say "| $prob | $N | $mode | $med_step | $last_eval | $last_rebuild | $ratio | $bus | $share | $rec | $mem |"
    done
    if [ -n "${mode_step[swift]:-}" ]; then
      swift_line="# $prob $N: SWIFT (dt_max $swift_dt, every particle active) s/step over each mode's:"
      for m in $modes; do
        [ $m = swift ] && continue
        swift_line="$swift_line $m $(awk -v a="${mode_step[swift]}" -v b="${mode_step[$m]}" \
          'BEGIN {if (a + 0 > 0 && b + 0 > 0) printf "%.2f", a / b; else print "-"}')"
      done
      say "$swift_line"
    fi
  done
done
printf "\nGPU stage times of the last run of each case:\n%s" "$stages" | tee -a "$out"
