#!/bin/bash
# The porosity: sub-mapping of a material, read through bolide-eos: a valid
# entry loads; each bad one stops with exit 1 and one line
# "bolide-eos: error: FILE:LINE: material 'NAME': key 'porosity: K' ...".
set -u
eos="$BOLIDE_BUILDDIR/bolide-eos"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
n=0

# entry NAME POROSITY_MAPPING: a Murnaghan matrix with that porosity
entry() {
  printf '%s:\n  eos: murnaghan\n  rho0: 2700\n  K0: 2e10\n  n: 4\n  porosity: %s\n' "$1" "$2"
}

entry ok '{model: palpha, alpha_0: 2, p_e: 1e6, p_t: 5e7, p_s: 2e8, alpha_t: 1.3, n1: 6, n2: 3}' \
  >"$tmp/ok.yml"
"$eos" "$tmp/ok.yml" ok --nrho 2 --nu 1 >/dev/null 2>"$tmp/err" || fail "valid entry: $(cat "$tmp/err")"

# expect KEY WHAT MAPPING: bolide-eos fails naming line 6, the material and the key
expect() {
  n=$((n + 1))
  entry bad "$3" >"$tmp/b$n.yml"
  if "$eos" "$tmp/b$n.yml" bad >/dev/null 2>"$tmp/err"; then fail "$3: accepted"; fi
  [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "$3: more than one line: $(cat "$tmp/err")"
  grep -q "^bolide-eos: error: $tmp/b$n.yml:[0-9]*: material 'bad': key 'porosity: $1' $2" \
    "$tmp/err" || fail "$3: $(cat "$tmp/err")"
  echo "ok: $(cat "$tmp/err")"
}
expect p_t 'must be in' '{model: palpha, alpha_0: 2, p_e: 1e6, p_t: 3e8, p_s: 2e8}'
expect p_s 'must be larger than p_e' '{model: palpha, alpha_0: 2, p_e: 1e6, p_s: 1e5}'
expect p_s 'is required' '{model: palpha, alpha_0: 2, p_e: 1e6}'
expect alpha_e 'must not exceed alpha_0' '{model: palpha, alpha_0: 2, alpha_e: 3, p_e: 1e6, p_s: 2e8}'
expect n2 'must be positive' '{model: palpha, alpha_0: 2, p_e: 1e6, p_s: 2e8, n2: 0}'
expect c_e 'must be given together with c_s' '{model: palpha, alpha_0: 2, p_e: 1e6, p_s: 2e8, c_e: 1e3}'
expect alpha_0 'must be >= 1' '{model: epsalpha, alpha_0: 0.5, eps_e: -1e-4, eps_x: -0.1, kappa: 1}'
expect eps_x 'must not be larger than eps_e' '{model: epsalpha, alpha_0: 2, eps_e: -0.1, eps_x: -0.01, kappa: 1}'
expect model 'must be one of none|palpha|epsalpha' '{model: sirono}'
entry bad '{model: palpha, alpha_0: 2, p_e: 1e6, p_s: 2e8, p_q: 1}' >"$tmp/u.yml"
if "$eos" "$tmp/u.yml" bad >/dev/null 2>"$tmp/err"; then fail "unknown key accepted"; fi
grep -q "^bolide-eos: error: $tmp/u.yml:6: material 'bad': unknown key 'porosity: p_q'" "$tmp/err" \
  || fail "unknown key: $(cat "$tmp/err")"
echo "ok: $(cat "$tmp/err")"
