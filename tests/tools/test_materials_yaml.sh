#!/bin/bash
# Materials from YAML: library lookups by name and by SWIFT id, overrides,
# inline definitions, the default ideal gas, and one-line errors naming the
# file, line, material and key.
set -u
prog="$BOLIDE_BUILDDIR/tests/unit/test_material_params"
eos="$BOLIDE_BUILDDIR/bolide-eos"
lib="$BOLIDE_SRCDIR/examples/materials.yml"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# the keys every run file needs besides Materials
base() {
  cat <<EOT
InitialConditions:
  file_name: ic.hdf5
TimeIntegration:
  time_end: 1.0
EOT
}

# 1. library by name + override, SWIFT id, inline definition
{ base; cat <<EOT
Materials:
  0: {name: basalt, weibull_m: 8, weibull_k: 5e34}
  101: {}
  7:
    eos: liquid
    name: rubber_inline
    rho0: 1000
    c0: 800
    shear_modulus: 1e8
    strength: elastic
  2: {name: ice, library: $lib}
EOT
} >"$tmp/run.yml"
"$prog" "$tmp/run.yml" >"$tmp/out" 2>"$tmp/err" || fail "valid file rejected: $(cat "$tmp/err")"
grep -qx "0 basalt tillotson 2700 2.67e+10 8" "$tmp/out" || fail "basalt: $(cat "$tmp/out")"
grep -qx "101 granite tillotson 2680 1.8e+10 0" "$tmp/out" || fail "SWIFT id 101: $(cat "$tmp/out")"
grep -qx "7 rubber_inline liquid 1000 800 0" "$tmp/out" || fail "inline: $(cat "$tmp/out")"
grep -qx "2 ice tillotson 917 9470000000 0" "$tmp/out" || fail "ice: $(cat "$tmp/out")"

# 1b. weakly compressible water by its bulk modulus K0 (c0 = sqrt(K0/rho0)),
# with a Newtonian viscosity, from the library and inline
{ base; cat <<EOT
Materials:
  8: {name: water_wc}
  9: {name: thick, eos: liquid, rho0: 1000, K0: 4e8, viscosity: 2.5}
EOT
} >"$tmp/water.yml"
"$prog" "$tmp/water.yml" >"$tmp/out" 2>"$tmp/err" || fail "water: $(cat "$tmp/err")"
grep -qx "8 water_wc liquid 1000 1483.239697 0" "$tmp/out" || fail "water_wc: $(cat "$tmp/out")"
grep -qx "9 thick liquid 1000 632.455532 0" "$tmp/out" || fail "inline K0: $(cat "$tmp/out")"

# 2. no Materials section: one ideal gas, id 0, gamma = SPH:gamma
{ base; printf 'SPH:\n  gamma: 1.4\n'; } >"$tmp/gas.yml"
"$prog" "$tmp/gas.yml" >"$tmp/out" 2>"$tmp/err" || fail "no Materials: $(cat "$tmp/err")"
grep -qx "0 ideal_gas ideal_gas 0 1.4 0" "$tmp/out" || fail "default gas: $(cat "$tmp/out")"

# 3. errors: one line, FILE:LINE, material and key
check_error() { # file expected-regex
  "$prog" "$1" >/dev/null 2>"$tmp/e" && fail "should fail: $1"
  [ "$(wc -l <"$tmp/e")" -eq 1 ] || fail "not one line: $(cat "$tmp/e")"
  grep -Eq "$2" "$tmp/e" || fail "message '$(cat "$tmp/e")' lacks '$2'"
}
{ base; printf 'Materials:\n  0: {name: basalt, A: -1e9}\n'; } >"$tmp/e1.yml"
check_error "$tmp/e1.yml" "e1.yml:6: material 'basalt': key 'A' must be positive"
{ base; printf 'Materials:\n  0: {name: basalt, Aa: 1e9}\n'; } >"$tmp/e2.yml"
check_error "$tmp/e2.yml" "e2.yml:6: material 'basalt': unknown key 'Aa'"
{ base; printf 'Materials:\n  0: {eos: tillotson, name: rock, rho0: 2700}\n'; } >"$tmp/e3.yml"
check_error "$tmp/e3.yml" "e3.yml:6: material 'rock': key 'A' is required"
{ base; printf 'Materials:\n  0: {name: granit}\n'; } >"$tmp/e4.yml"
check_error "$tmp/e4.yml" "e4.yml:6: material 0: 'granit' is not in the material library"
{ base; printf 'Materials:\n  x: {name: basalt}\n'; } >"$tmp/e5.yml"
check_error "$tmp/e5.yml" "e5.yml:6: Materials: 'x' is not a material id"
{ base; printf 'Materials:\n  0: {eos: tilotson}\n'; } >"$tmp/e6.yml"
check_error "$tmp/e6.yml" "e6.yml:6: .*key 'eos' must be one of"
{ base; printf 'Materials:\n  0: {name: basalt, Ecv: 1e6}\n'; } >"$tmp/e7.yml"
check_error "$tmp/e7.yml" "e7.yml:6: material 'basalt': key 'Ecv' must be larger than Eiv"

{ base; printf 'Materials:\n  0: {eos: liquid, name: w, rho0: 1000, c0: 1500, K0: 2.2e9}\n'; } >"$tmp/e8.yml"
check_error "$tmp/e8.yml" "e8.yml:6: material 'w': key 'c0' and K0 cannot both be given"
{ base; printf 'Materials:\n  0: {eos: liquid, name: w, rho0: 1000}\n'; } >"$tmp/e9.yml"
check_error "$tmp/e9.yml" "e9.yml:6: material 'w': key 'c0' is required for EOS liquid \\(or its bulk modulus K0\\)"
{ base; printf 'Materials:\n  0: {name: rubber, viscosity: 1.0}\n'; } >"$tmp/e10.yml"
check_error "$tmp/e10.yml" "e10.yml:6: material 'rubber': key 'viscosity' is for fluids \\(strength none\\) only"
{ base; printf 'Materials:\n  0: {name: water_wc, viscosity: -1}\n'; } >"$tmp/e11.yml"
check_error "$tmp/e11.yml" "e11.yml:6: material 'water_wc': key 'viscosity' must not be negative"

# 4. a bad library: the error names the library file and line
cat >"$tmp/lib.yml" <<EOT
rock:
  eos: tillotson
  rho0: 2700
  A: 2e10
  B: -1
EOT
"$eos" "$tmp/lib.yml" rock >/dev/null 2>"$tmp/e" && fail "bad library accepted"
grep -Eq "^bolide-eos: error: .*lib.yml:5: material 'rock': key 'B' must not be negative" "$tmp/e" \
  || fail "library error: $(cat "$tmp/e")"
echo "materials YAML: all checks passed"
