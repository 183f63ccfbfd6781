#!/bin/bash
# miluphcuda's ANEOS table format (issue 23 item 3): a table written by
# tools/eos_tables.py --format miluphcuda from the analytic ideal gas is read
# back by bolide-eos (eos: table, format: miluphcuda) and P, c and T at
# off-node points agree with the formula within the bound of bilinear
# interpolation in (ln rho, ln e); malformed tables stop with one line that
# names the file and the problem.
set -u
B=${BOLIDE_BUILDDIR:?}
S=${BOLIDE_SRCDIR:?}
PY=${PYTHON:-$B/.venv/bin/python}
eos="$B/bolide-eos"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
fail=0

"$PY" "$S/tools/eos_tables.py" --format miluphcuda --rho 1 1e4 --u 1e4 1e8 --n 40 50 \
  -o aneos.table || { echo "FAIL: eos_tables.py --format miluphcuda"; exit 1; }
[ "$(grep -vc '^#' aneos.table)" -eq 2000 ] && [ "$(head -n 3 aneos.table | grep -c '^#')" -eq 3 ] ||
  { echo "FAIL: expected 3 header lines and 40 x 50 rows"; exit 1; }
cat >lib.yml <<'YML'
aneos_gas:
  eos: table
  file: aneos.table
  format: miluphcuda
  n_rho: 40
  n_e: 50
  rho0: 100
no_counts:
  eos: table
  file: aneos.table
  format: miluphcuda
  rho0: 100
wrong_counts:
  eos: table
  file: aneos.table
  format: miluphcuda
  n_rho: 50
  n_e: 40
  rho0: 100
YML

# 1. off-node points against the ideal gas (gamma 5/3, c_v 1000 J/kg/K)
for m in aneos_gas no_counts; do
  "$PY" - "$eos" "$m" <<'PY' || fail=1
import subprocess, sys, numpy as np
eos, mat = sys.argv[1], sys.argv[2]
rng = np.random.default_rng(7)
rho = np.exp(rng.uniform(np.log(1.0), np.log(1e4), 400))
u = np.exp(rng.uniform(np.log(1e4), np.log(1e8), 400))
out = subprocess.run([eos, "--stdin", "lib.yml", mat], input="\n".join("%.17g %.17g" % p for p in zip(rho, u)),
                     capture_output=True, text=True, check=True).stdout
d = np.loadtxt(out.splitlines()[1:])
P_a, c_a, T_a = 2.0 / 3.0 * rho * u, np.sqrt(10.0 / 9.0 * u), u / 1000.0
eP, ec, eT = (np.max(np.abs(d[:, k] / ref - 1.0)) for k, ref in ((2, P_a), (3, c_a), (4, T_a)))
# P = C exp(x + y) in x = ln rho, y = ln e: bilinear interpolation errs by at
# most exp(hr + hu) (hr^2 + hu^2) / 8 relative; c^2 and T are C exp(y): at most
# exp(hu) hu^2 / 8 (c: half of that of c^2)
hr, hu = np.log(1e4) / 39, np.log(1e4) / 49
bP = np.exp(hr + hu) * (hr * hr + hu * hu) / 8
bT = np.exp(hu) * hu * hu / 8
ok = eP <= bP and ec <= bT / 2 + 1e-9 and eT <= bT
print("%s %s: miluphcuda table vs the ideal gas: max rel error P %.2e (bound %.2e), c %.2e (%.2e), T %.2e (%.2e)"
      % ("ok:" if ok else "FAIL:", mat, eP, bP, ec, bT / 2, eT, bT))
# not trivially exact: points between nodes do carry an interpolation error
sys.exit(0 if ok and eP > 1e-4 else 1)
PY
done

# 2. malformed tables: exit status != 0 and one line naming the file and the problem
expect_error() { # MATERIAL PATTERN
  if "$eos" lib.yml "$1" --nrho 2 --nu 2 >out.txt 2>err.txt; then
    echo "FAIL: $1: accepted"; fail=1; return
  fi
  if [ "$(wc -l <err.txt)" -ne 1 ] || ! grep -qE -- "$2" err.txt; then
    echo "FAIL: $1: expected one line matching '$2':"; cat err.txt; fail=1; return
  fi
  echo "ok: $1: $(cat err.txt)"
}
bad() { # NAME FILE: a material reading FILE
  printf '%s:\n  eos: table\n  file: %s\n  format: miluphcuda\n  rho0: 100\n' "$1" "$2" >>lib.yml
}
bad missing nowhere.table
expect_error missing "nowhere.table: cannot open the EOS table"
expect_error wrong_counts "aneos.table: miluphcuda ANEOS table: the first density has 50 energies, but n_e = 40"
head -n 1000 aneos.table >short.table
printf 'short:\n  eos: table\n  file: short.table\n  format: miluphcuda\n  n_rho: 40\n  n_e: 50\n  rho0: 100\n' >>lib.yml
expect_error short "short.table: miluphcuda ANEOS table: 997 rows, but n_rho x n_e = 40 x 50 = 2000"
# a NaN pressure in row 100
awk 'NR == 103 { $3 = "nan" } { print }' aneos.table >nan.table
bad nan nan.table
expect_error nan "nan.table:103: miluphcuda ANEOS table: column 3 is nan"
# two density blocks swapped: the densities do not increase
awk 'NR <= 3 { print; next } NR <= 53 { a[NR] = $0; next } NR <= 103 { print; next }
     NR == 104 { for (k = 4; k <= 53; k++) print a[k] } { print }' aneos.table >order.table
bad order order.table
expect_error order "order.table:54: miluphcuda ANEOS table: density .* the densities must increase"
# two energies of every density swapped: the energies do not increase
awk 'NR > 3 && (NR - 4) % 50 == 10 { hold = $0; next } NR > 3 && (NR - 4) % 50 == 11 { print; print hold; next }
     { print }' aneos.table >energy.table
bad energy energy.table
expect_error energy "energy.table: miluphcuda ANEOS table: energy node 11 .* the energies must increase"
# a table that is not log-spaced (Bolide's grid): said so, with the file
awk 'NR > 3 && (NR - 4) % 50 == 20 { $2 = $2 * 1.01 } { print }' aneos.table >lin.table
bad lin lin.table
expect_error lin "lin.table: energy node 20 .* not on the log-spaced grid"
# n_rho without format miluphcuda
printf 'counts_rho_u:\n  eos: table\n  file: aneos.table\n  n_rho: 40\n  n_e: 50\n  rho0: 100\n' >>lib.yml
expect_error counts_rho_u "keys n_rho, n_e belong to format: miluphcuda"
exit $fail
