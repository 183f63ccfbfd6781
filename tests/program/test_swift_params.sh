#!/usr/bin/env bash
# SWIFT's parameter files (issue 23 item 2): the SWIFT-style files of
# tests/data/swift (written for these tests in SWIFT's layout and keys) pass
# `bolide --check` unchanged, every SWIFT key without an effect getting one
# note; SWIFT's EoS section gives materials (its tables read in SWIFT's
# format, checked against the analytic EOS they were written from); every
# problem of a file is reported in one pass; "did you mean" looks in the
# key's own section first.
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}; S=${BOLIDE_SRCDIR:?}
PY=${PYTHON:-$B/.venv/bin/python}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
fail=0
bolide="$B/bolide"
cp "$S"/tests/data/swift/*.yml .

# initial conditions and an EOS table in SWIFT's format (ids 400, 0)
mkdir -p tables
"$PY" "$S/tools/eos_tables.py" --format swift --rho 1 1e4 --T 10 1e5 --n 48 64 -o tables/forsterite_like.txt ||
  { echo "FAIL: eos_tables.py"; exit 1; }
"$B/bolide-ic" box --n 8 --size 2 --rho 3300 --u 1e6 --mat 400 -o impact.hdf5 >/dev/null
"$B/bolide-ic" sod -o sod.hdf5 >/dev/null
"$B/bolide-ic" box --n 8 --size 2 --rho 1 --u 0.05 -o evrard.hdf5 >/dev/null
"$B/bolide-ic" box --n 6 --size 1 --rho 1 --u 1 -o box.hdf5 >/dev/null
"$B/bolide-ic" sedov --n 8 -o sedov.hdf5 >/dev/null
"$B/bolide-ic" box --n 8 --size 2 --rho 3300 --u 1e6 --mat 301 -o earth_impact.hdf5 >/dev/null
for m in iron basalt; do  # SESAME_iron (300), SESAME_basalt (301) in SWIFT's format
  "$PY" "$S/tools/eos_tables.py" --format swift --rho 1 1e4 --T 10 1e5 --n 24 32 \
    -o tables/SESAME_${m}_like.txt || { echo "FAIL: eos_tables.py ($m)"; exit 1; }
done

# 1. every file of tests/data/swift passes --check (with SWIFT's flags: -s
# for the hydro tests, -s -G for a file with a Gravity section) and gives
# no error
files=$(cd "$S/tests/data/swift" && ls ./*.yml | sed 's|^\./||')
[ "$(echo "$files" | wc -w)" -ge 6 ] || { echo "FAIL: fewer than 6 SWIFT-style files in tests/data/swift"; fail=1; }
for f in $files; do
  flags=-s; grep -q '^Gravity:' "$f" && flags="-s -G"
  # shellcheck disable=SC2086
  if "$bolide" --check $flags "$f" >"$f.out" 2>"$f.err"; then
    echo "ok: $f passes --check ($(grep -c 'note:' "$f.err") notes, $(grep -c 'warning:' "$f.err") warnings)"
  else
    echo "FAIL: $f does not pass --check:"; cat "$f.err"; fail=1
  fi
  grep -v -E '^bolide: (note|warning): ' "$f.err" && { echo "FAIL: $f: stderr lines other than notes and warnings"; fail=1; }
done

# 2. the notes: one line per SWIFT key without effect, naming file and line
expect_line() { # FILE PATTERN: a line of FILE.err matches PATTERN
  grep -q -E -- "$2" "$1.err" || { echo "FAIL: $1: no line matching '$2'"; cat "$1.err"; fail=1; }
}
expect_line planetary_impact.yml "note: planetary_impact.yml:[0-9]+: SPH:delta_neighbours \(SWIFT's\) has no effect"
expect_line planetary_impact.yml "note: planetary_impact.yml:[0-9]+: Gravity:mesh_side_length \(SWIFT's\) has no effect"
expect_line planetary_impact.yml "note: planetary_impact.yml: SWIFT's EoS section read as materials 400 \(ANEOS_forsterite\), 100 \(iron\), 101 \(granite\).*Materials"
expect_line sod_shock.yml "note: sod_shock.yml:[0-9]+: section 'EAGLECooling' \(SWIFT's\) has no effect in Bolide"
expect_line evrard.yml "note: evrard.yml:[0-9]+: SPH:H_mass_fraction"
expect_line earth_impact_sesame.yml "note: earth_impact_sesame.yml: SWIFT's EoS section read as materials 300 \(SESAME_iron\), 301 \(SESAME_basalt\)"
expect_line earth_impact_sesame.yml "note: earth_impact_sesame.yml:[0-9]+: Snapshots:int_time_label_on \(SWIFT's\) has no effect"
expect_line sedov_blast.yml "note: sedov_blast.yml:[0-9]+: Snapshots:distributed \(SWIFT's\) has no effect"
expect_line every_key.yml "warning: every_key.yml:[0-9]+: section 'Cosmology' \(SWIFT's\) has no effect"
expect_line every_key.yml "warning: every_key.yml:[0-9]+: EoS:isothermal_internal_energy"
n=$(grep -c "every_key.yml:[0-9]*: .*(SWIFT's) has no effect" every_key.yml.err)
[ "$n" -ge 100 ] || { echo "FAIL: every_key.yml: $n notes, expected one per SWIFT key without effect (>= 100)"; fail=1; }
if grep -q "self-gravity is off" evrard.yml.err; then echo "FAIL: Gravity warning despite -G"; fail=1; fi

# 3. the SWIFT keys Bolide understands take effect (used_parameters.yml of a -n 0 run)
"$bolide" -s -G -n 0 -P Snapshots:subdir:out_ev evrard.yml >/dev/null 2>&1 || { echo "FAIL: evrard -n 0"; fail=1; }
grep -A30 '^Gravity:' out_ev/used_parameters.yml | grep -q 'epsilon_fmm: 0$' ||
  { echo "FAIL: Gravity:MAC: geometric does not turn the adaptive criterion off"; fail=1; }
grep -A3 '^PhysicalConstants:' out_ev/used_parameters.yml | grep -q 'G: 1$' ||
  { echo "FAIL: PhysicalConstants:G not taken"; fail=1; }
"$bolide" -s -n 2 -P Snapshots:subdir:out_sod -P Statistics:time_first:1e9 sod_shock.yml >/dev/null 2>&1 ||
  { echo "FAIL: sod -n 2"; fail=1; }
# time_first after the run: only the closing line of the run
[ "$(grep -vc '^#' out_sod/statistics.txt)" -eq 1 ] || { echo "FAIL: Statistics:time_first not followed"; fail=1; }
"$bolide" -s -n 1 -P Snapshots:subdir:out_rs -P Restarts:enable:1 -P Restarts:subdir:out_rs/r \
  -P Restarts:basename:mine sod_shock.yml >/dev/null 2>&1 || { echo "FAIL: restart run"; fail=1; }
[ -f out_rs/r/mine.bin ] || { echo "FAIL: Restarts:basename not used"; ls out_rs/r; fail=1; }

# 4. the table read in SWIFT's format against the analytic ideal gas it holds
cat >lib.yml <<'YML'
table_swift:
  eos: table
  file: tables/forsterite_like.txt
  format: swift
  rho0: 100
YML
"$PY" - <<'PY' || fail=1
import os, subprocess, sys, numpy as np
rng = np.random.default_rng(23)
rho = np.exp(rng.uniform(np.log(2.0), np.log(5e3), 300))
u = np.exp(rng.uniform(np.log(2e4), np.log(5e7), 300))
out = subprocess.run(["%s/bolide-eos" % os.environ["BOLIDE_BUILDDIR"],
                      "--stdin", "lib.yml", "table_swift"], input="\n".join("%.17g %.17g" % p for p in zip(rho, u)),
                     capture_output=True, text=True, check=True).stdout
d = np.loadtxt(out.splitlines()[1:])
P_a, c_a, T_a = 2.0 / 3.0 * rho * u, np.sqrt(10.0 / 9.0 * u), u / 1000.0
err = [np.max(np.abs(d[:, k] / ref - 1.0)) for k, ref in ((2, P_a), (3, c_a), (4, T_a))]
# bilinear in (ln rho, ln u) on 48 x 64 nodes over 4 and 4 decades: (dln^2/8) ~ 5e-3
print("SWIFT-format table vs the analytic ideal gas: max relative error P %.2e, c %.2e, T %.2e" % tuple(err))
sys.exit(0 if max(err) < 1e-2 else 1)
PY

# 4b. every table material of SWIFT (ids 300-307, 400-402) from SWIFT's keys,
# each reading its own planetary_*_table_file: table k is the ideal gas with
# gamma_k = 1.1 + 0.05 k, and after one step of 1e-9 s the pressure of each
# material's particles is (gamma_k - 1) rho u to the interpolation bound of
# a 48 x 64 table (theory/eos.md: (dln_rho^2 + dln_T^2) / 8 = 7.5e-3), while
# a neighbour's gamma would be off by 7e-2 or more
swift_tables="SESAME_iron:300 SESAME_basalt:301 SESAME_water:302 SS08_water:303 AQUA:304 CMS19_H:305
  CMS19_He:306 CD21_HHe:307 ANEOS_forsterite:400 ANEOS_iron:401 ANEOS_Fe85Si15:402"
{
  echo "InternalUnitSystem: {UnitMass_in_cgs: 1000, UnitLength_in_cgs: 100, UnitVelocity_in_cgs: 100}"
  echo "InitialConditions: {file_name: all_tables.hdf5}"
  echo "TimeIntegration: {time_end: 1, dt_max: 1e-9}"
  echo "Snapshots: {subdir: out_tab}"
  echo "EoS:"
  k=0
  for nm in $swift_tables; do
    g=$(awk -v k=$k 'BEGIN {printf "%.2f", 1.1 + 0.05 * k}')
    "$PY" "$S/tools/eos_tables.py" --format swift --gamma "$g" --rho 1 1e4 --T 10 1e5 --n 48 64 \
      -o "tables/t${nm#*:}.txt" || echo "FAIL: eos_tables.py --gamma $g" >&2
    echo "  planetary_use_${nm%:*}: 1"
    echo "  planetary_${nm%:*}_table_file: tables/t${nm#*:}.txt"
    k=$((k + 1))
  done
} >all_tables.yml
"$B/bolide-ic" box --n 8 --size 2 --rho 3300 --u 1e6 --mat 300 -o all_tables.hdf5 >/dev/null
if "$PY" -c 'import h5py, numpy as np
ids = [300, 301, 302, 303, 304, 305, 306, 307, 400, 401, 402]
with h5py.File("all_tables.hdf5", "r+") as f:
    m = f["PartType0/MaterialIDs"]
    m[...] = np.array([ids[i % len(ids)] for i in range(m.shape[0])], dtype=m.dtype)' &&
  "$B/bolide" -s -n 1 all_tables.yml >all_tables.out 2>&1; then
  "$PY" - <<'PY' || fail=1
import sys, h5py, numpy as np
ids = [300, 301, 302, 303, 304, 305, 306, 307, 400, 401, 402]
with h5py.File("out_tab/snapshot_0001.hdf5", "r") as f:
    g = f["PartType0"]
    P, rho, u, mat = (g[k][...] for k in ("Pressures", "Densities", "InternalEnergies", "MaterialIDs"))
bad = 0
for k, i in enumerate(ids):
    s = mat == i
    err = np.max(np.abs(P[s] / ((0.1 + 0.05 * k) * rho[s] * u[s]) - 1.0)) if s.any() else np.inf
    ok = err < 1e-2
    bad += not ok
    print("%s: material %d from its own SWIFT table (gamma %.2f): %d particles, max |P/P_exact - 1| %.2e"
          % ("ok" if ok else "FAIL", i, 1.1 + 0.05 * k, s.sum(), err))
sys.exit(1 if bad else 0)
PY
else
  echo "FAIL: run with every SWIFT table material:"; tail -5 all_tables.out; fail=1
fi

# 5. problems: all of a file in one pass, did-you-mean in the key's section
cat >many.yml <<'YML'
InitialConditions:
  file_name: box.hdf5
TimeIntegration:
  time_end: 1
SPH:
  h_maxx: 1
  CFL_condition: fast
Gravity:
  eta: 0.025
  softning: 0.1
Statisics:
  delta_time: 1
YML
"$bolide" --check many.yml >many.out 2>many.err; rc=$?
[ $rc -ne 0 ] && [ "$(wc -l <many.err)" -eq 4 ] || { echo "FAIL: many.yml: exit $rc, expected 4 error lines:"; cat many.err; fail=1; }
for want in "many.yml:6: unknown key 'SPH:h_maxx' (did you mean 'SPH:h_max'?)" \
            "many.yml:7: SPH:CFL_condition: expected a number" \
            "many.yml:10: unknown key 'Gravity:softning' (did you mean 'Gravity:softening'?)" \
            "many.yml:11: unknown section 'Statisics' (did you mean 'Statistics'?)"; do
  grep -qF -- "bolide: error: $want" many.err || { echo "FAIL: many.yml: no line '$want'"; fail=1; }
done
# a key of another section: the same name there is suggested
printf 'InitialConditions:\n  file_name: box.hdf5\nTimeIntegration:\n  time_end: 1\nSPH:\n  theta_cr: 0.5\n' >wrong.yml
"$bolide" --check wrong.yml >wrong.out 2>&1
grep -qF "wrong.yml:6: unknown key 'SPH:theta_cr' (did you mean 'Gravity:theta_cr'?)" wrong.out ||
  { echo "FAIL: wrong section suggestion"; fail=1; }
# EoS: a misspelt SWIFT key, a table material without its file: one pass, the Materials hint
cat >eos_bad.yml <<'YML'
InitialConditions:
  file_name: impact.hdf5
TimeIntegration:
  time_end: 1
EoS:
  planetary_use_ANEOS_forsterit: 1
  planetary_use_Til_iron: maybe
YML
"$bolide" --check eos_bad.yml >eos.out 2>eos.err
grep -qF "eos_bad.yml:6: unknown key 'EoS:planetary_use_ANEOS_forsterit' (did you mean 'planetary_use_ANEOS_forsterite'?)" eos.err &&
  grep -qF "eos_bad.yml:7: EoS:planetary_use_Til_iron: expected 0 or 1" eos.err ||
  { echo "FAIL: EoS problems:"; cat eos.err; fail=1; }
printf 'InitialConditions:\n  file_name: impact.hdf5\nTimeIntegration:\n  time_end: 1\nEoS:\n  planetary_use_ANEOS_iron: 1\n' >eos_nofile.yml
"$bolide" --check eos_nofile.yml >eos_nofile.out 2>&1
grep -qE "eos_nofile.yml:6: EoS:planetary_use_ANEOS_iron: material 401 is a SWIFT table: give its file as EoS:planetary_ANEOS_iron_table_file \(or define material 401 in the Materials section\)" eos_nofile.out ||
  { echo "FAIL: EoS table without file"; "$bolide" --check eos_nofile.yml; fail=1; }
# a table that is not there: its key and line, where SWIFT's tables come from
printf 'InitialConditions:\n  file_name: impact.hdf5\nTimeIntegration:\n  time_end: 1\nEoS:\n  planetary_use_ANEOS_forsterite: 1\n  planetary_ANEOS_forsterite_table_file: ../EoSTables/ANEOS_forsterite_S19.txt\n' >eos_missing.yml
"$bolide" --check eos_missing.yml >eos_missing.out 2>&1
grep -qF "eos_missing.yml:7: EoS:planetary_ANEOS_forsterite_table_file: cannot read the table ../EoSTables/ANEOS_forsterite_S19.txt" eos_missing.out &&
  grep -q "get_eos_tables.sh" eos_missing.out || { echo "FAIL: missing SWIFT table:"; cat eos_missing.out; fail=1; }
exit $fail
