#!/usr/bin/env bash
# The GPU runner's scheduling policies (Scheduler:gpu) against the CPU, with
# self-gravity, where they differ: the conservation budgets of each run's
# statistics file must agree with the CPU run's (--no-gpu) and with the
# serial GPU run's (all) to 1e-8 relative to their scale (as
# test_gpu_run.sh: mass, E_tot, or sum m|v| for momenta).
#   all     one after the other: gravity's CPU part (multipoles, recorded
#           walks), its GPU part, then the hydrodynamics on the GPU
#   auto    the hybrid: the CPU workers walk while the GPU computes the
#           hydrodynamics; then gravity's GPU part and the kick
#           (all, auto, list: Scheduler:gpu_multipoles and gpu_walks host)
#   default no options: the defaults (multipoles and walks on the device;
#           with Gravity:reuse_steps, walks on the CPU)
#   list    [density, gradient, force, damage, drift, kick, gravity]: the same
#   nograv  [density, gradient, force, damage, drift, kick]: the whole of
#           self-gravity on the CPU workers while the GPU computes the
#           hydrodynamics; ga goes up for the kick
#   updev   auto with Scheduler:gpu_multipoles: device (P2M and M2M on the
#           GPU, the multipoles back for the CPU's walks)
#   alldev  all with the same
#   walkdev auto with Scheduler:gpu_walks: device (multipoles and walks on
#           the GPU: self-gravity entirely on the device)
#   allwalk all with the same
#  1. Evrard collapse (7,208 particles, hydro + tree gravity), 40 steps.
#  2. The same with Gravity:reuse_steps 2 (replayed steps), auto and nograv.
#  3. The basalt impact of test_gpu_run.sh (Collins strength, Grady-Kipp
#     damage) with self-gravity, 40 steps, auto.
# Each hybrid run must say so at start-up and must have run its phases
# with CPU work beside the GPU.  Part of `make check-gpu` (needs a GPU).
set -euo pipefail
B=${BOLIDE_BUILDDIR:?}; S=${BOLIDE_SRCDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
hydro="density, gradient, force, damage, drift, kick"
# gravity's multipoles and walks on the CPU (the hybrid's CPU share)
host=(-P Scheduler:gpu_multipoles:host -P Scheduler:gpu_walks:host)

# run CASE MODE STEPS: bolide in CASE/MODE (a copy of CASE/cpu's files)
run() {
  local c=$1 m=$2 n=$3 flag
  mkdir -p "$c/$m"; [ "$m" = cpu ] || cp "$c/cpu/"* "$c/$m/"
  case $m in
    cpu) flag=(--no-gpu) ;;
    all) flag=(--gpu -P Scheduler:gpu:all "${host[@]}") ;;
    auto) flag=(--gpu "${host[@]}") ;;
    list) flag=(--gpu -P "Scheduler:gpu:[$hydro, gravity]" "${host[@]}") ;;
    nograv) flag=(--gpu -P "Scheduler:gpu:[$hydro]") ;;
    default) flag=(--gpu) ;;
    updev) flag=(--gpu -P Scheduler:gpu_multipoles:device -P Scheduler:gpu_walks:host) ;;
    alldev) flag=(--gpu -P Scheduler:gpu:all -P Scheduler:gpu_multipoles:device -P Scheduler:gpu_walks:host) ;;
    walkdev) flag=(--gpu -P Scheduler:gpu_walks:device) ;;
    allwalk) flag=(--gpu -P Scheduler:gpu:all -P Scheduler:gpu_walks:device) ;;
  esac
  (cd "$c/$m" && "$B/bolide" "${flag[@]}" -n "$n" params.yml >run.log 2>&1) ||
    { tail -5 "$c/$m/run.log"; exit 1; }
}

# expect CASE MODE TEXT: the log of CASE/MODE holds TEXT
expect() {
  grep -qF -- "$3" "$1/$2/run.log" || { echo "FAIL: $1/$2: '$3' not in its log"; exit 1; }
}

# compare CASE A B: the budgets of CASE/A and CASE/B
compare() {
  echo "$1: $2 against $3"
  paste <(grep -v '^#' "$1/$2/statistics.txt") <(grep -v '^#' "$1/$3/statistics.txt") | awk '
  { n = NF / 2; for (k = 1; k <= n; k++) { c[k] = $k; g[k] = $(k + n) } rows++
    # columns: step time dt mass px py pz Lx Ly Lz E_kin E_int E_pot E_tot n n_removed
    scale_p = sqrt(2 * c[4] * (c[11] > 0 ? c[11] : 1e-300))
    for (k = 4; k <= 14; k++) {
      s = (k >= 5 && k <= 10) ? scale_p : ((k == 4) ? c[4] : (c[14] != 0 ? (c[14] < 0 ? -c[14] : c[14]) : 1))
      d = c[k] - g[k]; if (d < 0) d = -d; e = d / s
      if (e > worst[k]) worst[k] = e }
  }
  END { split("step time dt mass px py pz Lx Ly Lz E_kin E_int E_pot E_tot", name, " ")
        fail = 0; line = ""
        for (k = 4; k <= 14; k++) { line = line sprintf(" %s %.1e", name[k], worst[k])
                                     if (worst[k] > 1e-8) fail = 1 }
        printf " %s (worst relative differences, %d rows)\n", line, rows
        if (rows < 2) fail = 1
        exit fail }'
}

# 1. Evrard
mkdir -p evrard/cpu
"${PYTHON:-python3}" "$S/examples/EvrardCollapse/make_ic.py" 24 evrard/cpu/evrard.hdf5 >/dev/null
cp "$S/examples/EvrardCollapse/params.yml" evrard/cpu/
for m in cpu all auto list nograv default updev alldev walkdev allwalk; do run evrard $m 40; done
expect evrard all "(one after the other: the CPU part, the GPU part, then the hydrodynamics)"
expect evrard all "GPU runner (serial)"
for m in auto list; do
  expect evrard $m "(hybrid: the CPU workers walk while the GPU computes the hydrodynamics"
  expect evrard $m "GPU runner (hybrid)"
done
expect evrard nograv "self-gravity entirely on the CPU workers"
expect evrard nograv "GPU runner (gravity on the CPU)"
for m in auto list nograv; do
  grep -q "at the same time (4[0-9] phases)" evrard/$m/run.log ||
    { echo "FAIL: evrard/$m: its FORCE phases did not run the CPU beside the GPU"; exit 1; }
done
grep -h "^GPU runner" evrard/*/run.log
for m in default updev alldev walkdev allwalk; do
  grep -q "upward passes (P2M, M2M) on the device" evrard/$m/run.log ||
    { echo "FAIL: evrard/$m: no upward pass ran on the device"; exit 1; }
done
for m in default walkdev allwalk; do
  grep -q "walks on the device" evrard/$m/run.log ||
    { echo "FAIL: evrard/$m: no walk ran on the device"; exit 1; }
  expect evrard $m "self-gravity entirely on the GPU (Scheduler:gpu_walks: device"
done

# 2. reuse of the far field
mkdir -p reuse/cpu
cp evrard/cpu/evrard.hdf5 reuse/cpu/
sed 's/^Gravity:$/Gravity:\n  reuse_steps: 2\n  reuse_tolerance: 0.05/' "$S/examples/EvrardCollapse/params.yml" >reuse/cpu/params.yml
grep -q "reuse_steps: 2" reuse/cpu/params.yml || { echo "FAIL: test set-up (reuse)"; exit 1; }
for m in cpu auto nograv default updev; do run reuse $m 40; done
for m in auto default; do
  grep -q "GPU gravity, .* evaluations ([1-9][0-9]* replays)" reuse/$m/run.log ||
    { echo "FAIL: the reuse run reuse/$m replayed no step on the GPU"; exit 1; }
done
expect reuse default "walks on the CPU"
grep -q "steps reused the far field" reuse/nograv/run.log ||
  { echo "FAIL: the reuse run with gravity on the CPU did not report its reuse"; exit 1; }
grep -h "reused the far field" reuse/*/run.log

# 3. impact: solids, damage and self-gravity
mkdir -p impact/cpu
"$B/bolide-ic" impact --target "sphere,material=basalt,radius=100,n=6000,u=1e4" \
  --impactor "sphere,material=basalt,radius=25,n=400,u=1e4" --v-contact 2000 --angle 45 \
  --separation 126 --impactor-mat-offset 1000 -o impact/cpu/impact.hdf5 >/dev/null
cat >impact/cpu/params.yml <<'YML'
InitialConditions:
  file_name: impact.hdf5
  periodic: false
TimeIntegration:
  time_end: 1
Snapshots:
  delta_time: 1
Statistics:
  delta_time: 1e-4
SPH:
  resolution_eta: 1.2348
  CFL_condition: 0.2
  viscosity_alpha: 1.5
  artificial_stress_epsilon: 0.3
Gravity:
  enabled: true
  softening: 5
Materials:
  103: &rock {name: basalt, strength: collins, yield_stress: 1e7, yield_stress_max: 3.5e9,
              friction_intact: 1.2, cohesion_damaged: 1e5, friction_damaged: 0.6,
              weibull_k: 5e34, weibull_m: 8}
  1103: *rock
Damage:
  seed: 11
YML
for m in cpu all auto default updev walkdev; do run impact $m 40; done
expect impact auto "gradient, extra ghost (plasticity, dS/dt), force, damage, kick2"
expect impact auto "GPU runner (hybrid)"

fail=0
for m in all auto list nograv default updev alldev walkdev allwalk; do compare evrard cpu $m || fail=1; done
for m in auto list default updev alldev walkdev allwalk; do compare evrard all $m || fail=1; done
for m in auto nograv default updev; do compare reuse cpu $m || fail=1; done
for m in all auto default updev walkdev; do compare impact cpu $m || fail=1; done
compare impact all auto || fail=1
[ $fail -eq 0 ] && echo PASS
exit $fail
