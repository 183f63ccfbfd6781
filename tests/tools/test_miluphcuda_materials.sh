#!/usr/bin/env bash
# bolide-ic miluphcuda-materials (issue 23 item 7): miluphcuda's libconfig
# material file as a Bolide Materials section.  On
# tests/data/miluphcuda/material.cfg (written here in miluphcuda's layout:
# Tillotson with an @include, Tillotson + P-alpha, Murnaghan, ideal gas):
#   - the conversion with each plasticity switch gives a section that
#     `bolide --check` accepts in a parameter file, the values as
#     theory/miluphcuda.md's table says (Tillotson keys, the crush curve
#     rescaled to alpha_e = alpha_0, sqrt(3) on the pressure-dependent
#     yield strengths, friction angles as coefficients);
#   - every key not converted is named (a comment and a note);
#   - ANEOS (type 7) becomes `eos: table, format: miluphcuda` with its
#     table_path, n_rho, n_e, aneos_rho_0, aneos_gamma (gamma_vapor) and the
#     cs_limit default, and a table written by tools/eos_tables.py passes
#     `bolide --check`;
#   - ANEOS + P-alpha (type 13, tests/data/miluphcuda/aneos_palpha.cfg)
#     becomes the same table with the P-alpha porosity of types 5 and 6
#     (crush curves 0 and 1), and passes `bolide --check`;
#   - an EOS Bolide does not have (Sirono, type 10) and a measured crush
#     curve (crushcurve_style 2) are errors naming the key, all problems in
#     one pass, and nothing is written;
#   - an integer where miluphcuda reads a float is warned about.
# Skips (77) when bolide-ic was built without libconfig, after checking that
# the subcommand then says so in one line.
set -u
S=${BOLIDE_SRCDIR:?} B=${BOLIDE_BUILDDIR:?}
PY=${PYTHON:-$B/.venv/bin/python}
ic="$B/bolide-ic" bolide="$B/bolide"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/bolide_milucfg.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
fail=0
FAIL() { echo "FAIL: $*"; fail=1; }
cfg="$S/tests/data/miluphcuda/material.cfg"

if ! grep -q '^#define HAVE_LIBCONFIG 1' "$B/config.h"; then
  "$ic" miluphcuda-materials "$cfg" >out 2>err && FAIL "without libconfig: exit 0"
  [ "$(wc -l <err)" -eq 1 ] && grep -q "built without libconfig" err || FAIL "without libconfig: $(cat err)"
  [ "$fail" = 0 ] && echo "bolide-ic built without libconfig: skip"
  [ "$fail" = 0 ] && exit 77
  exit 1
fi

# initial conditions: one granite cube (material 0); the other materials are
# checked by --check all the same
"$ic" box --n 6 --size 1 --rho 2680 --u 1e4 --mat 0 -o cube.hdf5 >/dev/null || FAIL "bolide-ic box"
params() { # SECTION-FILE: a parameter file with the converted section
  cat <<'EOF'
InitialConditions:
  file_name: cube.hdf5
TimeIntegration:
  time_end: 1e-5
EOF
  cat "$1"
}
value() { # FILE ID KEY: the value of KEY of material ID
  awk -v id="  $2:" -v key="$3:" '
    index($0, id) == 1 { inside = 1; next }
    /^  [0-9]+:/ { inside = 0 }
    inside && $1 == key { print $2; exit }' "$1"
}
near() { # A B: |A - B| <= 1e-9 |B|
  awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; exit !(a != "" && d <= 1e-9 * m) }'
}
keys_near() { # FILE WHAT KEY=VALUE...: the first KEY: of FILE near VALUE
  local file=$1 what=$2 kv v
  shift 2
  for kv; do
    v=$(awk -v k="${kv%%=*}:" '$1 == k { print $2; exit }' "$file")
    near "$v" "${kv#*=}" || FAIL "$what: ${kv%%=*} is '$v', not ${kv#*=}"
  done
}

for pl in none von_mises drucker_prager mohr_coulomb collins collins_simple; do
  "$ic" miluphcuda-materials "$cfg" --plasticity "$pl" --fragmentation -o "m_$pl.yml" 2>"e_$pl" ||
    { FAIL "--plasticity $pl: conversion failed"; cat "e_$pl"; continue; }
  params "m_$pl.yml" >"p_$pl.yml"
  "$bolide" --check "p_$pl.yml" >"c_$pl" 2>&1 || { FAIL "--plasticity $pl: bolide --check"; cat "c_$pl"; }
done

m=m_collins.yml
# Tillotson from the @include, miluphcuda's rho_limit and cs_limit default
for kv in rho0=2680 A=18e9 B=18e9 E0=16e6 Eiv=3.5e6 Ecv=18e6 a=0.5 b=1.3 alpha=5 beta=5 \
  eta_min=0.85 density_floor=100 shear_modulus=24e9 bulk_modulus=36e9 weibull_k=1e61 weibull_m=16; do
  near "$(value $m 0 "${kv%%=*}")" "${kv#*=}" || FAIL "material 0: ${kv%%=*} is '$(value $m 0 "${kv%%=*}")', not ${kv#*=}"
done
near "$(value $m 0 cs_min)" "$(awk 'BEGIN { printf "%.17g", 0.01 * sqrt(18e9 / 2680) }')" || FAIL "material 0: cs_min"
# Collins: sqrt(3) on cohesions and limit, friction coefficients sqrt(3) tan(angle)
r3() { awk -v x="$1" 'BEGIN { printf "%.17g", sqrt(3) * x }'; }
near "$(value $m 0 yield_stress)" "$(r3 1e7)" || FAIL "material 0: yield_stress (cohesion)"
near "$(value $m 0 yield_stress_max)" "$(r3 3.5e9)" || FAIL "material 0: yield_stress_max"
near "$(value $m 0 cohesion_damaged)" "$(r3 1e4)" || FAIL "material 0: cohesion_damaged"
near "$(value $m 0 friction_intact)" "$(awk 'BEGIN { x = 0.9827937232; printf "%.17g", sqrt(3) * sin(x) / cos(x) }')" ||
  FAIL "material 0: friction_intact"
grep -q '^    strength: collins' $m || FAIL "no strength: collins"
# P-alpha, crush curve 1: alpha_e = alpha_0, alpha_t = 1 + (1.9 - 1)(2 - 1)/(4.64 - 1)
sed -n '/^  1:/,/^  2:/p' $m >mat1
keys_near mat1 "material 1 porosity" alpha_0=2 alpha_e=2 p_e=1e6 p_t=6.8e7 p_s=2.13e8 n1=12 n2=3
near "$(awk '$1 == "alpha_t:" { print $2 }' mat1)" "$(awk 'BEGIN { printf "%.17g", 1 + 0.9 / 3.64 }')" ||
  FAIL "material 1: alpha_t"
grep -q 'model: palpha' mat1 || FAIL "material 1: no palpha"
# Murnaghan (miluphcuda's default rho_limit), ideal gas; fluids have no strength
for kv in rho0=1000 K0=2.2e9 n=7 eta_limit=0.9; do
  near "$(value $m 2 "${kv%%=*}")" "${kv#*=}" || FAIL "material 2: ${kv%%=*}"
done
near "$(value $m 3 gamma)" 1.4 || FAIL "material 3: gamma"
[ -z "$(value $m 2 strength)" ] || FAIL "material 2 (no shear modulus) has a strength"
# the other switches
grep -q '^    strength: elastic' m_none.yml || FAIL "--plasticity none: not elastic"
near "$(value m_von_mises.yml 0 yield_stress)" 3.5e9 || FAIL "von_mises: yield_stress unscaled"
near "$(value m_drucker_prager.yml 0 yield_stress)" \
  "$(awk 'BEGIN { p = 0.9827937232; printf "%.17g", 6 * 1e7 * cos(p) / (3 - sin(p)) }')" || FAIL "drucker_prager: Y0"
near "$(value m_mohr_coulomb.yml 0 yield_stress)" "$(r3 1e7)" || FAIL "mohr_coulomb: cohesion"
[ -z "$(value m_collins_simple.yml 0 cohesion_damaged)" ] || FAIL "collins_simple has a damaged curve"
# what is not converted is said
grep -q '# not converted: sml, interactions, artificial_viscosity.alpha' $m || FAIL "no 'not converted' comment"
grep -q "material.cfg:[0-9]*: material 1: eos.cs_porous not converted" e_collins || FAIL "no note on cs_porous"
grep -q '#     viscosity_alpha: 1' $m || FAIL "no hint on SPH:viscosity_alpha"
# --hydro: fluids only
"$ic" miluphcuda-materials "$cfg" --hydro >m_hydro.yml 2>/dev/null || FAIL "--hydro"
grep -q 'strength' m_hydro.yml && FAIL "--hydro: a material with strength"
params m_hydro.yml >p_hydro.yml
"$bolide" --check p_hydro.yml >c_hydro 2>&1 || { FAIL "--hydro: bolide --check"; cat c_hydro; }

# ANEOS: the lookup table read in miluphcuda's format (n_rho, n_e are ints there)
"$PY" "$S/tools/eos_tables.py" --format miluphcuda --rho 100 1e4 --u 1e3 1e8 --n 20 30 -o aneos.table ||
  FAIL "eos_tables.py --format miluphcuda"
cat >aneos.cfg <<'EOF'
materials = (
{
    ID = 0
    name = "gas.ANEOS"
    eos = { type = 7; table_path = "aneos.table"; n_rho = 20; n_e = 30;
            aneos_rho_0 = 2680.0; aneos_bulk_cs = 5500.0; aneos_e_norm = 335418.4; };
}
);
EOF
"$ic" miluphcuda-materials aneos.cfg --hydro -o m_aneos.yml 2>e_aneos || { FAIL "ANEOS: conversion failed"; cat e_aneos; }
grep -q 'is an integer' e_aneos && FAIL "ANEOS: n_rho, n_e (ints in miluphcuda) warned about"
grep -q "aneos.cfg:[0-9]*: material 0: eos.aneos_e_norm not converted" e_aneos || FAIL "ANEOS: no note on aneos_e_norm"
grep -q '^    eos: table' m_aneos.yml && grep -q '^    format: miluphcuda' m_aneos.yml &&
  grep -q '^    file: "aneos.table"' m_aneos.yml || FAIL "ANEOS: not eos: table, format: miluphcuda, file"
for kv in n_rho=20 n_e=30 rho0=2680 cs_min=55; do
  near "$(value m_aneos.yml 0 "${kv%%=*}")" "${kv#*=}" || FAIL "ANEOS: ${kv%%=*} is '$(value m_aneos.yml 0 "${kv%%=*}")', not ${kv#*=}"
done
params m_aneos.yml >p_aneos.yml
"$bolide" --check p_aneos.yml >c_aneos 2>&1 || { FAIL "ANEOS: bolide --check"; cat c_aneos; }
grep -q "material 0: no eos.aneos_gamma > 1: .* Bolide clamps e" e_aneos || FAIL "ANEOS: no note on aneos_gamma"
[ -z "$(value m_aneos.yml 0 gamma_vapor)" ] || FAIL "ANEOS without aneos_gamma: gamma_vapor written"

# ANEOS + P-alpha (type 13): the table, gamma_vapor and the porosity of types 5, 6
"$ic" miluphcuda-materials "$S/tests/data/miluphcuda/aneos_palpha.cfg" -o m_ap.yml 2>e_ap ||
  { FAIL "ANEOS + P-alpha: conversion failed"; cat e_ap; }
for id in 0 1 2; do
  sed -n "/^  $id:/,/^  $((id + 1)):/p" m_ap.yml >ap$id
  grep -q '^    eos: table' ap$id && grep -q '^    format: miluphcuda' ap$id &&
    grep -q '^    file: "aneos.table"' ap$id || FAIL "ANEOS + P-alpha: material $id not eos: table, format: miluphcuda"
done
for kv in n_rho=20 n_e=30 rho0=3320 gamma_vapor=1.4 cs_min=65 shear_modulus=40e9; do
  near "$(value m_ap.yml 0 "${kv%%=*}")" "${kv#*=}" || FAIL "type 13: ${kv%%=*} is '$(value m_ap.yml 0 "${kv%%=*}")', not ${kv#*=}"
done
grep -q 'model: palpha' ap0 && grep -q 'model: palpha' ap1 || FAIL "type 13: no palpha"
grep -q 'model: palpha' ap2 && FAIL "type 7: has a porosity"
# crush curve 1 rescaled to alpha_e = alpha_0: alpha_t = 1 + (1.9 - 1)(1.8 - 1)/(4.64 - 1)
keys_near ap0 "type 13 porosity" alpha_0=1.8 alpha_e=1.8 p_e=1e6 p_t=6.8e7 p_s=2.13e8 n1=12 n2=3
near "$(awk '$1 == "alpha_t:" { print $2 }' ap0)" "$(awk 'BEGIN { printf "%.17g", 1 + 0.9 * 0.8 / 3.64 }')" ||
  FAIL "type 13: alpha_t"
# crush curve 0: the quadratic curve through alpha_0
keys_near ap1 "type 13, crush curve 0" alpha_0=2.5 alpha_e=2.5 p_e=1e5 p_s=1e8 gamma_vapor=1.3 rho0=910
grep -q 'alpha_t:' ap1 && FAIL "type 13, crush curve 0: has alpha_t"
grep -q "aneos_palpha.cfg:[0-9]*: material 0: eos.cs_porous not converted" e_ap || FAIL "type 13: no note on cs_porous"
grep -q "material 2: no eos.aneos_gamma" e_ap || FAIL "type 7: no note on aneos_gamma"
# (initial conditions of the plain ANEOS material 2: the porous ones are
# checked as materials all the same)
"$ic" box --n 6 --size 1 --rho 2680 --u 1e4 --mat 2 -o cube2.hdf5 >/dev/null || FAIL "bolide-ic box (material 2)"
params m_ap.yml | sed 's/cube.hdf5/cube2.hdf5/' >p_ap.yml
"$bolide" --check p_ap.yml >c_ap 2>&1 || { FAIL "ANEOS + P-alpha: bolide --check"; cat c_ap; }

# errors: Sirono, a measured crush curve and a missing ID in one pass,
# nothing written; an integer
cat >bad.cfg <<'EOF'
materials = (
{
    ID = 0
    eos = { type = 10; porsirono_K_0 = 1e5; };
},
{
    name = "no ID"
    eos = { type = 9; polytropic_gamma = 1.4; };
},
{
    ID = 2
    eos = { type = 1; rho_0 = 1000.0; bulk_modulus = 2.2e9; n = 7; };
},
{
    ID = 3
    eos = { type = 13; table_path = "aneos.table"; aneos_rho_0 = 2000.0; aneos_gamma = 1.4;
            porjutzi_alpha_0 = 2.0; porjutzi_p_elastic = 1e3; porjutzi_p_compacted = 1e7;
            crushcurve_style = 2; };
}
);
EOF
"$ic" miluphcuda-materials bad.cfg -o bad.yml >bad.out 2>bad.err && FAIL "bad.cfg: exit 0"
[ -e bad.yml ] && FAIL "bad.cfg: a file was written"
grep -q "bad.cfg:4: material 0: eos.type 10 (Sirono porosity) has no Bolide equation of state" bad.err ||
  FAIL "bad.cfg: Sirono not reported: $(cat bad.err)"
grep -q "bad.cfg:18: material 3: eos.crushcurve_style = 2 cannot be converted: .* not of Bolide's P-alpha form" bad.err ||
  FAIL "bad.cfg: crush curve 2 not reported: $(cat bad.err)"
grep -q "bad.cfg:[0-9]*: a material without an integer ID" bad.err || FAIL "bad.cfg: missing ID not reported"
grep -q "bad.cfg:12: n = 7 is an integer" bad.err || FAIL "bad.cfg: integer not warned about"
grep -q "3 problems above: nothing written" bad.err || FAIL "bad.cfg: last line: $(tail -1 bad.err)"
# libconfig's own syntax errors: one line with file and line
printf 'materials = ( { ID = 0 \n eos = { type = ; } } );\n' >syntax.cfg
"$ic" miluphcuda-materials syntax.cfg >/dev/null 2>syn.err && FAIL "syntax error: exit 0"
[ "$(wc -l <syn.err)" -eq 1 ] && grep -q "syntax.cfg:2:" syn.err || FAIL "syntax error: $(cat syn.err)"

[ "$fail" = 0 ] && echo "ok: miluphcuda material files convert and pass bolide --check"
exit "$fail"
