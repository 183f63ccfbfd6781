#!/usr/bin/env bash
# Runs on the CPU (--no-gpu) and on the GPU (--gpu): the conservation
# budgets of the two statistics files (mass, momentum, angular momentum,
# kinetic, internal and total energy) must agree.
#  1. Sedov blast, 40 steps of 32,768 particles (fluid).
#  2. A basalt impactor (25 m, 400 particles) hitting a basalt target (100 m,
#     6,000 particles) at 2 km/s and 45 degrees, 40 steps through the
#     contact: Tillotson, Collins strength, artificial stress, Grady-Kipp
#     damage with Weibull flaws (the solid + damage FORCE phase on the GPU);
#     2b. again with the continuity density and XSPH.
#     2c. a porous (P-alpha) basalt cube squeezed: budgets, and distentions,
#     densities and energies particle by particle; 2d. the same with an
#     epsilon-alpha matrix.
#  3. Evrard collapse (7,208 particles, hydro + tree self-gravity), 40 steps:
#     multipoles and walks on the CPU, which record the interactions; M2L,
#     L2L, L2P, M2P and P2P on the GPU.
#  4. The same with Gravity:reuse_steps 2: the steps that reuse the far
#     field replay the interactions on the GPU (gravity_replay on the CPU).
#  5. Individual time steps (time bins): the Evrard collapse and the solid
#     impact, the same steps and particles kicked on both.
#  6. The rk2 and pc integrators: the solid impact and the Evrard collapse
#     with rk2, the porous cube with pc, the same steps on both.
#  7. Rebuilds of the resident particles (Scheduler:gpu_rebuild): reordered
#     on the device against every field copied back, reordered on the host
#     and uploaded: GPU runs of the Sedov blast (periodic: positions
#     wrapped), the solid impact, the Evrard collapse (self-gravity on the
#     device), the solid impact with rk2, and the solid impact and the Evrard
#     collapse in time bins, rebuilt often: each against a
#     CPU run as above, and bit for bit the same (self-gravity too, with
#     Gravity:gpu_reproducible: each cell's interactions sorted on the device).
# The runs differ only by the order of the SPH sums (round-off, ~1e-15
# relative per step, amplified along the run), so every column must agree
# to 1e-8 relative to its scale (mass, E_tot, or sum m|v| for momenta).
# Part of `make check-gpu` (needs a GPU); exits 77 without one.
set -euo pipefail
B=${BOLIDE_BUILDDIR:?}; S=${BOLIDE_SRCDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"

# run NAME STEPS [OPTION...]: bolide in NAME/cpu and NAME/gpu (each holds
# params.yml and the IC), with the options given
run() {
  local name=$1 steps=$2
  shift 2
  for mode in cpu gpu; do
    flag=--no-gpu; [ $mode = gpu ] && flag=--gpu
    (cd "$name/$mode" && "$B/bolide" $flag "$@" -n "$steps" params.yml >run.log 2>&1) ||
      { tail -5 "$name/$mode/run.log"; exit 1; }
  done
  grep -h "GPU" "$name/gpu/run.log" | head -3
}

# compare NAME: the budgets of NAME/cpu and NAME/gpu
compare() {
  echo "$1: CPU against GPU"
  paste <(grep -v '^#' "$1/cpu/statistics.txt") <(grep -v '^#' "$1/gpu/statistics.txt") | awk '
  { n = NF / 2; for (k = 1; k <= n; k++) { c[k] = $k; g[k] = $(k + n) } rows++
    # columns: step time dt mass px py pz Lx Ly Lz E_kin E_int E_pot E_tot n n_removed
    scale_p = sqrt(2 * c[4] * (c[11] > 0 ? c[11] : 1e-300))
    for (k = 4; k <= 14; k++) {
      s = (k >= 5 && k <= 10) ? scale_p : ((k == 4) ? c[4] : (c[14] != 0 ? (c[14] < 0 ? -c[14] : c[14]) : 1))
      d = c[k] - g[k]; if (d < 0) d = -d; e = d / s
      if (e > worst[k]) worst[k] = e }
  }
  END { split("step time dt mass px py pz Lx Ly Lz E_kin E_int E_pot E_tot", name, " ")
        fail = 0
        for (k = 4; k <= 14; k++) { printf "  %-6s CPU vs GPU worst relative difference %.3e\n", name[k], worst[k]
                                     if (worst[k] > 1e-8) fail = 1 }
        printf "  %d statistics rows compared\n", rows
        if (rows < 2) fail = 1
        exit fail }'
}

mkdir -p sedov/cpu sedov/gpu
"$B/bolide-ic" sedov --n 32 --energy 1 --rho 1 -o sedov/cpu/sedov.hdf5 >/dev/null
cp sedov/cpu/sedov.hdf5 sedov/gpu/
for m in cpu gpu; do cp "$S/examples/SedovBlast3D/params.yml" sedov/$m/; done
run sedov 40

mkdir -p impact/cpu impact/gpu
"$B/bolide-ic" impact --target "sphere,material=basalt,radius=100,n=6000,u=1e4" \
  --impactor "sphere,material=basalt,radius=25,n=400,u=1e4" --v-contact 2000 --angle 45 \
  --separation 126 --impactor-mat-offset 1000 -o impact/cpu/impact.hdf5 >/dev/null
cp impact/cpu/impact.hdf5 impact/gpu/
for m in cpu gpu; do
  cat >impact/$m/params.yml <<'YML'
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
Materials:
  103: &rock {name: basalt, strength: collins, yield_stress: 1e7, yield_stress_max: 3.5e9,
              friction_intact: 1.2, cohesion_damaged: 1e5, friction_damaged: 0.6,
              weibull_k: 5e34, weibull_m: 8}
  1103: *rock
Damage:
  seed: 11
YML
done
run impact 40
grep -q "gradient, extra ghost (plasticity, dS/dt), force, damage, kick2" impact/gpu/run.log ||
  { echo "FAIL: the solid + damage run did not run its FORCE phase on the GPU"; exit 1; }

# 2b. the same impact with the density from the continuity equation and XSPH
mkdir -p impactc/cpu impactc/gpu
for m in cpu gpu; do
  cp impact/cpu/impact.hdf5 impactc/$m/
  sed -e 's/^  viscosity_alpha: 1.5/  viscosity_alpha: 1.5\n  density: continuity\n  xsph_epsilon: 0.5/' \
    impact/$m/params.yml >impactc/$m/params.yml
done
grep -q "xsph_epsilon: 0.5" impactc/gpu/params.yml || { echo "FAIL: test set-up"; exit 1; }
run impactc 40
grep -q "GPU not used" impactc/gpu/run.log && { echo "FAIL: the continuity + XSPH run did not use the GPU"; exit 1; }

# 2c. P-alpha porosity: the porous cube of test_porosity_run.sh (Tillotson
# basalt matrix, alpha_0 1.8, continuity density) squeezed at -300/s x for
# 80 steps (alpha 1.31 to 1.68 at the end)
mkdir -p porous/cpu porous/gpu
for m in cpu gpu; do "${PYTHON:-python3}" "$S/tests/helpers/porous_cube.py" porous/$m/block.hdf5 1500 300; done
for m in cpu gpu; do
  cat >porous/$m/params.yml <<'YML'
InitialConditions:
  file_name: block.hdf5
TimeIntegration:
  time_end: 1
Snapshots:
  delta_time: 1
Statistics:
  delta_time: 2.5e-6
SPH:
  density: continuity
Materials:
  0: {name: basalt, porosity: {model: palpha, alpha_0: 1.8, alpha_t: 1.3, p_e: 1e6, p_t: 5e7,
                                p_s: 2e8, n1: 6, n2: 3}}
YML
done
run porous 80
grep -q "GPU not used" porous/gpu/run.log && { echo "FAIL: the porous run did not use the GPU"; exit 1; }
# 2d. the same cube with an epsilon-alpha Murnaghan matrix (test_epsalpha_run.sh's curve)
for m in cpu gpu; do
  mkdir -p porousea/$m; cp porous/$m/block.hdf5 porousea/$m/
  sed -e 's/^  0: {name: basalt, porosity: .*/  0: {name: porous, eos: murnaghan, rho0: 2700, K0: 2e10, n: 4,/' \
      -e 's/^                                p_s: 2e8, n1: 6, n2: 3}}/      porosity: {model: epsalpha, alpha_0: 1.8, eps_e: -0.05, eps_x: -0.3, kappa: 1.2, chi: 0.5}}/' \
      porous/$m/params.yml >porousea/$m/params.yml
done
grep -q "model: epsalpha" porousea/gpu/params.yml || { echo "FAIL: test set-up (epsilon-alpha)"; exit 1; }
run porousea 80

mkdir -p evrard/cpu evrard/gpu
"${PYTHON:-python3}" "$S/examples/EvrardCollapse/make_ic.py" 24 evrard/cpu/evrard.hdf5 >/dev/null
cp evrard/cpu/evrard.hdf5 evrard/gpu/
for m in cpu gpu; do cp "$S/examples/EvrardCollapse/params.yml" evrard/$m/; done
run evrard 40
grep -q "self-gravity entirely on the GPU (Scheduler:gpu_walks: device: multipoles, walks, M2L" \
  evrard/gpu/run.log || { echo "FAIL: the gravity run did not use the GPU"; exit 1; }

mkdir -p reuse/cpu reuse/gpu
for m in cpu gpu; do
  cp evrard/cpu/evrard.hdf5 reuse/$m/
  sed 's/^Gravity:$/Gravity:\n  reuse_steps: 2\n  reuse_tolerance: 0.05/' "$S/examples/EvrardCollapse/params.yml" >reuse/$m/params.yml
done
run reuse 40
grep "reused the far field" reuse/gpu/run.log
grep -q "GPU gravity, .* evaluations ([1-9][0-9]* replays)" reuse/gpu/run.log ||
  { echo "FAIL: the reuse run replayed no step on the GPU"; exit 1; }

# 5. individual time steps (TimeIntegration:global_step: false): the drift
# and the kick of time bins on the GPU (drift_part_bins, kick2_part_bins,
# the CPU's functions): the Evrard collapse (self-gravity) and the solid +
# damage impact, 40 steps each; the same particles kicked in each step
mkdir -p evbins/cpu evbins/gpu imbins/cpu imbins/gpu
for m in cpu gpu; do
  cp evrard/cpu/evrard.hdf5 evbins/$m/
  sed 's/^  dt_max: 0.01$/  dt_max: 0.01\n  global_step: false/' "$S/examples/EvrardCollapse/params.yml" >evbins/$m/params.yml
  cp impact/cpu/impact.hdf5 imbins/$m/
  sed 's/^  time_end: 1$/  time_end: 1\n  global_step: false/' impact/$m/params.yml >imbins/$m/params.yml
done
grep -q "global_step: false" evbins/gpu/params.yml && grep -q "global_step: false" imbins/gpu/params.yml ||
  { echo "FAIL: test set-up (bins)"; exit 1; }
# (self-gravity for the cells with particles that end their step only,
# Gravity:active_only, the default: on the CPU and on the device; the
# Evrard run writes statistics every 0.02, so most of its steps are such)
run evbins 40
run imbins 40
grep -q "gravity: [1-9][0-9]* of [0-9]* steps computed it only" evbins/gpu/run.log ||
  { echo "FAIL: evbins: no step computed gravity for the active particles only"; grep "gravity:" evbins/gpu/run.log; exit 1; }
for b in evbins imbins; do
  grep -q "GPU not used" $b/gpu/run.log && { echo "FAIL: the $b run did not use the GPU"; exit 1; }
  # the step lines (step, time, dt, particles kicked) of the two runs
  awk 'NF == 6 && $1 ~ /^[0-9]+$/ {print $1, $2, $3, $4}' $b/cpu/run.log >$b/cpu/steps.txt
  awk 'NF == 6 && $1 ~ /^[0-9]+$/ {print $1, $2, $3, $4}' $b/gpu/run.log >$b/gpu/steps.txt
  cmp -s $b/cpu/steps.txt $b/gpu/steps.txt ||
    { echo "FAIL: $b: the CPU and GPU runs kicked other particles or took other steps"; diff $b/cpu/steps.txt $b/gpu/steps.txt | head -5; exit 1; }
  echo "$b: $(wc -l <$b/cpu/steps.txt) steps, the same particles kicked on the CPU and the GPU ($(awk '{s += $4} END {print s}' $b/cpu/steps.txt) updates)"
done

# 6. the rk2 and pc integrators (TimeIntegration:scheme, theory/integrators.md):
# their stages on the device (drift_rk_stage in tasks/drift/drift_gpu.cu, the
# step's start and records in device memory): the solid + damage impact and
# the Evrard collapse with rk2, the porous cube with pc (its crush-curve
# return at each step's end); the same steps on both
for c in imrk2 evrk2 porpc; do mkdir -p $c/cpu $c/gpu; done
for m in cpu gpu; do
  cp impact/$m/impact.hdf5 impact/$m/params.yml imrk2/$m/
  cp evrard/$m/evrard.hdf5 evrard/$m/params.yml evrk2/$m/
  cp porous/$m/block.hdf5 porous/$m/params.yml porpc/$m/
done
run imrk2 20 -P TimeIntegration:scheme:rk2
run evrk2 20 -P TimeIntegration:scheme:rk2
run porpc 40 -P TimeIntegration:scheme:pc
for c in imrk2 evrk2 porpc; do
  grep -q "GPU not used" $c/gpu/run.log && { echo "FAIL: the $c run did not use the GPU"; exit 1; }
  grep -q "time integration: \(rk2\|pc\)" $c/gpu/run.log || { echo "FAIL: $c: not the scheme asked for"; exit 1; }
  awk 'NF == 6 && $1 ~ /^[0-9]+$/ {print $1, $2, $3}' $c/cpu/run.log >$c/cpu/steps.txt
  awk 'NF == 6 && $1 ~ /^[0-9]+$/ {print $1, $2, $3}' $c/gpu/run.log >$c/gpu/steps.txt
  cmp -s $c/cpu/steps.txt $c/gpu/steps.txt ||
    { echo "FAIL: $c: the CPU and GPU runs took other steps"; diff $c/cpu/steps.txt $c/gpu/steps.txt | head -5; exit 1; }
  echo "$c: $(wc -l <$c/cpu/steps.txt) steps, the same on the CPU and the GPU; $(grep -h "time integration [rp]" $c/gpu/run.log | sed 's/.*time integration //')"
done

# 7. rebuilds of resident particles (Scheduler:gpu_rebuild, gpu_engine_rebuild_begin):
# from the IC file and parameters of the case SRC, rebuilt whenever a
# particle drifted FRACTION of a cell width, a CPU run (NAME/cpu), a GPU run
# with the particles reordered on the device (NAME/gpu) and one with every
# field copied back at each rebuild (NAME/host).  The GPU run must agree with
# the CPU run as in the cases above (compare), and with SAME = bits, be the
# host-rebuild run bit for bit (with self-gravity too, under
# Gravity:gpu_reproducible, which makes every GPU run repeat bit for bit:
# without it the atomics of the device's walks order the sums differently
# from run to run).  With time bins (TimeIntegration:global_step: false)
# too: the solid impact and the Evrard collapse, whose steps kick some of
# the particles only.
# rebuild_same NAME SRC IC STEPS FRACTION SAME [OPTION...]
rebuild_same() {
  local name=$1 src=$2 ic=$3 steps=$4 frac=$5 same=$6
  shift 6
  for m in cpu gpu host; do
    mkdir -p $name/$m
    cp "$src/gpu/$ic" "$src/gpu/params.yml" $name/$m/
    local flag=--gpu; [ $m = cpu ] && flag=--no-gpu
    local where=device; [ $m = host ] && where=host
    (cd $name/$m && "$B/bolide" $flag -v -P Scheduler:gpu_rebuild:$where -P Scheduler:rebuild_fraction:$frac \
       "$@" -n "$steps" params.yml >run.log 2>&1) || { tail -5 $name/$m/run.log; exit 1; }
  done
  local nd nh
  nd=$(sed -n 's/^GPU rebuilds: \([0-9]*\) with the particles reordered on the device.*/\1/p' $name/gpu/run.log)
  nh=$(sed -n 's/^GPU rebuilds: [0-9]* with .*, \([0-9]*\) with every field.*/\1/p' $name/host/run.log)
  [ "${nd:-0}" -ge 1 ] || { echo "FAIL: $name: ${nd:-no} rebuilds reordered on the device"
    grep "GPU rebuild\|space: rebuild" $name/gpu/run.log | head; return 1; }
  for m in cpu gpu host; do
    awk 'NF == 6 && $1 ~ /^[0-9]+$/ {print $1, $2, $3, $4}' $name/$m/run.log >$name/$m/steps.txt
  done
  cmp -s $name/cpu/steps.txt $name/gpu/steps.txt ||
    { echo "FAIL: $name: the CPU run and the GPU run (rebuilds on the device) took other steps"; return 1; }
  compare $name || return 1
  if [ "$same" = bits ]; then
    cmp -s $name/gpu/steps.txt $name/host/steps.txt &&
      cmp -s $name/gpu/statistics.txt $name/host/statistics.txt ||
      { echo "FAIL: $name: the rebuilds on the device and on the host gave other runs"
        diff $name/gpu/statistics.txt $name/host/statistics.txt | head -4; return 1; }
    echo "$name: $nd rebuilds reordered on the device, $nh with every field copied (host): the same $(wc -l <$name/gpu/steps.txt) steps and statistics bit for bit"
  else
    echo "$name: $nd rebuilds reordered on the device, $nh with every field copied (host); $(cmp -s $name/gpu/statistics.txt $name/host/statistics.txt && echo "the same statistics bit for bit" || echo "statistics not bit for bit the same")"
  fi
}
fail=0
rebuild_same rbsedov sedov sedov.hdf5 40 0.01 bits || fail=1
rebuild_same rbimpact impact impact.hdf5 40 0.01 bits || fail=1
rebuild_same rbevrard evrard evrard.hdf5 80 0.01 bits -P Gravity:gpu_reproducible:true || fail=1
rebuild_same rbimrk2 impact impact.hdf5 20 0.02 bits -P TimeIntegration:scheme:rk2 || fail=1
rebuild_same rbimbins impact impact.hdf5 40 0.01 bits -P TimeIntegration:global_step:false || fail=1
rebuild_same rbevbins evrard evrard.hdf5 80 0.01 bits -P TimeIntegration:global_step:false \
  -P Gravity:gpu_reproducible:true || fail=1
compare sedov || fail=1
compare impact || fail=1
compare impactc || fail=1
compare porous || fail=1
compare porousea || fail=1
# the distentions and densities at the end of the porous runs, particle by particle
for case in porous porousea; do
"${PYTHON:-python3}" - "$case" <<'PY' || fail=1
import sys, glob, h5py, numpy as np
case = sys.argv[1]
def last(m):
    f = h5py.File(sorted(glob.glob("%s/%s/snapshot_*.hdf5" % (case, m)))[-1], "r")["PartType0"]
    o = np.argsort(f["ParticleIDs"][:])
    return {k: f[k][:][o] for k in ("Distentions", "Densities", "InternalEnergies")}
c, g = last("cpu"), last("gpu")
a = c["Distentions"]
print(case + ": %d of %d particles compacted (alpha < 1.8), %d fully (alpha = 1)" %
      ((a < 1.8 - 1e-12).sum(), a.size, (a == 1.0).sum()))
bad = 0
for k in c:
    d = np.max(np.abs(c[k] - g[k]) / (np.abs(c[k]) + 1e-300 + (1e-3 * np.abs(c[k]).max() if k == "InternalEnergies" else 0)))
    print("  %-16s CPU vs GPU worst relative difference %.3e" % (k, d))
    bad |= not d < 1e-8
if not (a < 1.8 - 1e-12).sum() > 0: print("  FAIL: nothing compacted"); bad = 1
raise SystemExit(bad)
PY
done
compare evrard || fail=1
compare reuse || fail=1
compare evbins || fail=1
compare imbins || fail=1
compare imrk2 || fail=1
compare evrk2 || fail=1
compare porpc || fail=1
exit $fail
