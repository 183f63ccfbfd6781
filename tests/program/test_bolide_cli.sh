#!/usr/bin/env bash
# The bolide command line (theory/architecture.md, "Programs and their contract"): --help
# and --version exit 0; every bad input gives one line "bolide: error: ..."
# naming the file or key and a non-zero exit, and leaves no half-written
# output; --check validates without running; -n 0 turns the initial
# conditions into a t = 0 snapshot with every field bit-identical, with an
# XDMF file beside it; a fluid run holds no solid fields; Snapshots:enabled.
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}; S=${BOLIDE_SRCDIR:?}
work=$(mktemp -d); trap 'chmod -R u+w "$work"; rm -rf "$work"' EXIT
cd "$work"
fail=0
bolide="$B/bolide"

# expect_error DESCRIPTION SUBSTRING COMMAND...: non-zero exit, exactly one
# stderr line starting with "bolide: error:" and containing SUBSTRING
expect_error() {
  local what=$1 sub=$2; shift 2
  "$@" >out.txt 2>err.txt; local rc=$?
  local lines; lines=$(wc -l <err.txt)
  if [ $rc -eq 0 ] || [ "$lines" -ne 1 ] || ! grep -q '^bolide: error: ' err.txt || ! grep -qF -- "$sub" err.txt; then
    echo "FAIL: $what (exit $rc, $lines stderr lines):"; cat err.txt; fail=1
  else
    echo "ok: $what: $(cat err.txt)"
  fi
}

"$bolide" --help >/dev/null || { echo "FAIL: --help"; fail=1; }
"$bolide" --version | grep -q '^bolide ' || { echo "FAIL: --version"; fail=1; }

"$B/bolide-ic" box --n 8 --size 1 --u 1 -o ics.hdf5 >/dev/null
cat >params.yml <<'YML'
InitialConditions:
  file_name: ics.hdf5
TimeIntegration:
  time_end: 0.01
Snapshots:
  subdir: out
YML
expect_error "no parameter file" "no parameter file" "$bolide"
expect_error "unknown option" "--frobnicate" "$bolide" --frobnicate params.yml
expect_error "missing parameter file" "nothere.yml" "$bolide" nothere.yml
expect_error "bad thread count" "--threads" "$bolide" -t zero params.yml
sed 's/time_end/time_edn/' params.yml >typo.yml
expect_error "misspelt key" "typo.yml:4" "$bolide" typo.yml
# a time step below dt_min names the particle and the criterion that set it
expect_error "time step below dt_min" "limited by the Courant condition" "$bolide" \
  -P TimeIntegration:dt_min:1 -P Snapshots:subdir:out_dtmin params.yml
expect_error "bad -P value" "TimeIntegration:time_end" "$bolide" -P TimeIntegration:time_end:soon params.yml
# individual time steps (issue 20) are accepted
"$bolide" --check -P TimeIntegration:global_step:false params.yml >bins.txt 2>&1 ||
  { echo "FAIL: TimeIntegration:global_step: false refused"; cat bins.txt; fail=1; }
expect_error "CSPM continuity without continuity density" "SPH:continuity_correction" "$bolide" --check \
  -P SPH:continuity_correction:true params.yml
expect_error "fluid-solid interface without CSPM continuity" "SPH:fluid_solid_interface" "$bolide" \
  --check -P SPH:density:continuity -P SPH:fluid_solid_interface:true params.yml
sed 's/ics.hdf5/missing.hdf5/' params.yml >noic.yml
expect_error "missing initial conditions" "missing.hdf5" "$bolide" noic.yml

# an IC with a NaN position and one with a negative mass
"$PYTHON" - <<'PY'
import h5py, shutil
for name, field, value in (("nan.hdf5", "Coordinates", float("nan")), ("neg.hdf5", "Masses", -1.0)):
    shutil.copy("ics.hdf5", name)
    with h5py.File(name, "r+") as f:
        d = f["PartType0/" + field]
        a = d[...]
        if a.ndim == 2: a[7, 1] = value
        else: a[7] = value
        d[...] = a
PY
sed 's/ics.hdf5/nan.hdf5/' params.yml >nan.yml
expect_error "NaN position" "nan.hdf5" "$bolide" nan.yml
sed 's/ics.hdf5/neg.hdf5/' params.yml >neg.yml
expect_error "negative mass" "neg.hdf5" "$bolide" neg.yml

# output folder that cannot be written: error, nothing left behind
mkdir -p ro && chmod a-w ro
if [ "$(id -u)" != 0 ]; then
  expect_error "read-only output folder" "ro" "$bolide" -P Snapshots:subdir:ro/sub params.yml
fi

# --check validates and runs nothing
"$bolide" --check params.yml >check.txt 2>&1 || { echo "FAIL: --check"; cat check.txt; fail=1; }
[ ! -e out ] || { echo "FAIL: --check wrote outputs"; fail=1; }

# -n 0: the IC becomes snapshot 0 bit for bit
"$bolide" -n 0 params.yml >run0.txt 2>&1 || { echo "FAIL: -n 0"; cat run0.txt; fail=1; }
[ -f out/snapshot_0000.hdf5 ] && [ -f out/snapshot_0000.xmf ] || { echo "FAIL: no snapshot/XDMF"; fail=1; }
[ -f out/used_parameters.yml ] || { echo "FAIL: no used_parameters.yml"; fail=1; }
ls out | grep -q '\.tmp' && { echo "FAIL: temporary files left"; fail=1; }
"$PYTHON" - <<'PY' || fail=1
import sys, h5py, numpy as np
ic = h5py.File("ics.hdf5", "r")["PartType0"]
sn = h5py.File("out/snapshot_0000.hdf5", "r")["PartType0"]
bad = 0
for name in ic:
    if not isinstance(ic[name], h5py.Dataset) or name not in sn:
        continue
    a, b = ic[name][...], sn[name][...]
    same = a.shape == b.shape and a.tobytes() == b.astype(a.dtype).tobytes()
    print("%-18s %s" % (name, "bit-identical" if same else "DIFFERENT"))
    bad += not same
sys.exit(1 if bad else 0)
PY

# SWIFT's command line (issue 23 item 1): its flags are listed by --help and
# accepted; -s/-G decide the physics as in SWIFT; its options for physics
# Bolide lacks stop with one line naming them; a Gravity section with
# gravity off is warned about
"$bolide" --help >help.txt
for flag in --hydro --self-gravity --threads --steps --param --restart --task-dumps --fpe --verbose --dry-run; do
  grep -q -- "$flag" help.txt || { echo "FAIL: --help does not list $flag"; fail=1; }
done
for args in "-s -v 1 --threads=1 -d" "--hydro --self-gravity -v 0 --dry-run" "-s -G -e --check" "-a -D --limiter -T 1 --check"; do
  # shellcheck disable=SC2086
  "$bolide" $args params.yml >swift.txt 2>&1 || { echo "FAIL: SWIFT flags $args"; cat swift.txt; fail=1; }
done
grep -q "note: option --pin" swift.txt || { echo "FAIL: no note for --pin"; fail=1; }
expect_error "SWIFT option Bolide lacks" "--cosmology" "$bolide" -c params.yml
expect_error "SWIFT long option Bolide lacks" "cooling" "$bolide" --cooling params.yml
expect_error "bad -y" "--task-dumps" "$bolide" -y often params.yml
expect_error "-r without a restart file" "no restart file" "$bolide" -r params.yml
"$bolide" -G -y 1 -n 1 -P Snapshots:subdir:out_g params.yml >g.txt 2>&1 || { echo "FAIL: -G run"; cat g.txt; fail=1; }
grep -q "enabled: true" <(sed -n '/^Gravity:/,/^[A-Z]/p' out_g/used_parameters.yml) &&
  grep -q "hydro: false" out_g/used_parameters.yml || { echo "FAIL: -G alone is not a gravity-only run"; fail=1; }
ls out_g/tasks_step000001.txt >/dev/null || { echo "FAIL: -y 1 wrote no task dump"; fail=1; }
printf 'Gravity:\n  theta_cr: 0.5\n' | cat params.yml - >grav.yml
"$bolide" --check grav.yml >grav.txt 2>&1
grep -q "grav.yml:7: .*Gravity section but self-gravity is off.*-G" grav.txt || { echo "FAIL: no Gravity warning"; cat grav.txt; fail=1; }
"$bolide" --check -s -G grav.yml >grav.txt 2>&1
grep -q "self-gravity is off" grav.txt && { echo "FAIL: Gravity warning with -G"; fail=1; }

# a short run: steps, statistics, final snapshot
"$bolide" -t 2 params.yml >run.txt 2>&1 || { echo "FAIL: run"; tail -5 run.txt; fail=1; }
[ -f out/statistics.txt ] && [ -f out/snapshot_0001.hdf5 ] || { echo "FAIL: run outputs"; ls out; fail=1; }

# a run without stress, damage or another integrator than kdk does not hold
# the solid and damage fields (parts_drop): its memory line says so, and
# its snapshots still have those datasets, zeros; rk2 holds them
grep -q "particle memory: 440 bytes per particle (the solid and damage fields not held" run.txt ||
  { echo "FAIL: the fluid run's particle memory"; grep "particle memory" run.txt; fail=1; }
"$PYTHON" - <<'PY' || { echo "FAIL: the fluid run's snapshot lacks the solid fields' zeros"; fail=1; }
import sys, h5py, numpy as np
p = h5py.File("out/snapshot_0001.hdf5", "r")["PartType0"]
for name in ("DeviatoricStress", "Damage", "PlasticStrains", "ShearDamage", "NumberOfFlaws"):
    if name not in p or np.any(p[name][...] != 0):
        sys.exit("%s: %s" % (name, "missing" if name not in p else "not zero"))
PY
"$bolide" --check -P TimeIntegration:scheme:rk2 params.yml >rk2.txt 2>&1
grep -q "particle memory: 824 bytes per particle$" rk2.txt ||
  { echo "FAIL: rk2's particle memory"; grep "particle memory" rk2.txt; fail=1; }

# Snapshots:enabled: false writes no snapshot, not the first nor the last,
# and the statistics all the same; -n 0 writes its snapshot anyway
"$bolide" -t 2 -P Snapshots:subdir:out_none -P Snapshots:enabled:false params.yml >none.txt 2>&1 ||
  { echo "FAIL: run without snapshots"; tail -5 none.txt; fail=1; }
[ -f out_none/statistics.txt ] && [ -z "$(ls out_none | grep -E 'hdf5|xmf')" ] ||
  { echo "FAIL: Snapshots:enabled: false"; ls out_none; fail=1; }
"$bolide" -n 0 -P Snapshots:subdir:out_none0 -P Snapshots:enabled:false params.yml >none0.txt 2>&1 &&
  [ -f out_none0/snapshot_0000.hdf5 ] || { echo "FAIL: -n 0 with Snapshots:enabled: false"; fail=1; }
exit $fail
