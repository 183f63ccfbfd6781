#!/bin/bash
# bolide-eos: header line, column count, values against the Tillotson formula
# computed here independently (awk), --stdin, one-line errors, --plot.
set -u
eos="$BOLIDE_BUILDDIR/bolide-eos"
lib="$BOLIDE_SRCDIR/examples/materials.yml"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$eos" --help | grep -q '^Usage: bolide-eos' || fail "--help"
"$eos" --version | grep -q '^bolide-eos ' || fail "--version"

# grid: 4 densities x 2 energies of basalt (which has cv: a temperature column)
"$eos" "$lib" basalt --nrho 4 --nu 2 >"$tmp/t.txt" 2>"$tmp/err" || fail "grid run: $(cat "$tmp/err")"
[ "$(head -n 1 "$tmp/t.txt")" = "density specific_internal_energy pressure sound_speed temperature" ] \
  || fail "header: $(head -n 1 "$tmp/t.txt")"
[ "$(tail -n +2 "$tmp/t.txt" | wc -l)" -eq 8 ] || fail "expected 8 rows"
tail -n +2 "$tmp/t.txt" | awk 'NF != 5 { exit 1 }' || fail "every row must have 5 columns"
# at rho0, u = 0: P = 0 and c = sqrt(A / rho0)
awk 'NR > 1 && $1 == 2700 && $2 == 0 { found = 1
       if ($3 != 0 || ($4 - sqrt(26.7e9 / 2700)) ^ 2 > 1e-12 * $4 ^ 2) exit 1 }
     END { exit !found }' "$tmp/t.txt" || fail "P, c at rho0, u = 0"

# --stdin against the compressed Tillotson form (Melosh 1989) computed by awk
printf '3000 1e6\n# a comment\n4050 0\n' | "$eos" "$lib" basalt --stdin >"$tmp/s.txt" \
  || fail "--stdin run"
[ "$(tail -n +2 "$tmp/s.txt" | wc -l)" -eq 2 ] || fail "--stdin: expected 2 rows"
tail -n +2 "$tmp/s.txt" | awk '
  { rho = $1; u = $2; eta = rho / 2700; mu = eta - 1; w = u / (487e6 * eta * eta) + 1
    P = (0.5 + 1.5 / w) * rho * u + 26.7e9 * mu + 26.7e9 * mu * mu
    if ((($3 - P) / P) ^ 2 > 1e-18) { printf "rho %g u %g: P %.10g, expected %.10g\n", rho, u, $3, P; bad = 1 } }
  END { exit bad }' || fail "--stdin values"

# errors: one line on stderr, exit status 1
check_error() { # expected-regex command...
  local want="$1"; shift
  "$@" >/dev/null 2>"$tmp/e" && fail "should fail: $*"
  [ "$(wc -l <"$tmp/e")" -eq 1 ] || fail "not one line: $(cat "$tmp/e")"
  grep -Eq "^bolide-eos: error: $want" "$tmp/e" || fail "message '$(cat "$tmp/e")' lacks '$want'"
}
check_error ".*no material 'nope'" "$eos" "$lib" nope
check_error "unknown or incomplete option" "$eos" --bogus "$lib" basalt
check_error "option --nrho: 'x' is not a positive integer" "$eos" "$lib" basalt --nrho x
check_error "the energy range" "$eos" "$lib" basalt --log --u-min 0
echo "1e3" | check_error "stdin:1: expected" "$eos" "$lib" basalt --stdin
# hostile input (issue 18): a NUL byte is an error, not a skipped line; a
# line longer than any buffer is one line
printf '3000 1e6\n\0004000 1e6\n' | check_error "stdin:2: a NUL byte" "$eos" "$lib" basalt --stdin
{ printf '3000'; printf ' %.0s' $(seq 1 600); printf '1e6\n'; } | "$eos" "$lib" basalt --stdin >"$tmp/long.txt" 2>"$tmp/e" ||
  fail "a 604-byte line: $(cat "$tmp/e")"
[ "$(tail -n +2 "$tmp/long.txt" | wc -l)" -eq 1 ] || fail "a 604-byte line: expected 1 row"

# --plot (needs the venv's matplotlib)
if [ -x "${PYTHON:-}" ] && "$PYTHON" -c 'import matplotlib' 2>/dev/null; then
  PYTHON="$PYTHON" "$eos" "$lib" granite --nu 4 --plot "$tmp/g.png" >/dev/null || fail "--plot"
  [ -s "$tmp/g.png" ] || fail "--plot wrote no PNG"
  # an unwritable target: one line before any work, no traceback
  check_error "--plot $tmp/no/g.png: $tmp/no: No such file or directory" "$eos" "$lib" granite --plot "$tmp/no/g.png"
  check_error "--plot $tmp: Is a directory" "$eos" "$lib" granite --plot "$tmp"
  mkdir "$tmp/ro"; chmod 555 "$tmp/ro"
  if [ "$(id -u)" -ne 0 ]; then
    check_error "--plot $tmp/ro/g.png: $tmp/ro: Permission denied" "$eos" "$lib" granite --plot "$tmp/ro/g.png"
  fi
  # the script itself, if it cannot write: one line
  "$PYTHON" "$BOLIDE_SRCDIR/tools/plot_eos.py" "$tmp/t.txt" "$tmp/no/g.png" 2>"$tmp/e" && fail "plot_eos.py into a missing folder"
  [ "$(wc -l <"$tmp/e")" -eq 1 ] && grep -q "^plot_eos.py: error: $tmp/no/g.png: No such file or directory" "$tmp/e" ||
    fail "plot_eos.py: $(cat "$tmp/e")"
else
  echo "no Python with matplotlib: --plot not tested"
fi
echo "bolide-eos: all checks passed"
