#!/bin/bash
# miluphcuda's ANEOS table format (issue 23 item 3): a table written by
# tools/eos_tables.py --format miluphcuda from the analytic ideal gas is read
# back by bolide-eos (eos: table, format: miluphcuda) and P, c and T at
# off-node points agree with the formula within the bound of bilinear
# interpolation in (ln rho, ln e), for log-spaced, linearly spaced and
# irregular axes (the bound taken per cell); outside the table the values
# are those of theory/eos.md T1 (miluphcuda's: ideal gas of gamma_vapor
# above the last energy, e clamped below the first, linear in rho beyond
# the densities); malformed tables stop with one line that names the file
# and the problem.
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

"$PY" "$S/tools/eos_tables.py" --format miluphcuda --spacing linear --rho 1e3 1e4 --u 1e6 1e7 --n 40 50 \
  -o linear.table || { echo "FAIL: eos_tables.py --spacing linear"; exit 1; }
"$PY" "$S/tools/eos_tables.py" --format miluphcuda --spacing irregular --rho 1 1e4 --u 1e4 1e8 --n 40 50 \
  -o irregular.table || { echo "FAIL: eos_tables.py --spacing irregular"; exit 1; }
printf 'linear:\n  eos: table\n  file: linear.table\n  format: miluphcuda\n  n_rho: 40\n  n_e: 50\n  rho0: 2000\n' >>lib.yml
printf 'irregular:\n  eos: table\n  file: irregular.table\n  format: miluphcuda\n  rho0: 100\n' >>lib.yml
printf 'vapor:\n  eos: table\n  file: aneos.table\n  format: miluphcuda\n  rho0: 100\n  gamma_vapor: 1.4\n' >>lib.yml

# 1. off-node points against the ideal gas (gamma 5/3, c_v 1000 J/kg/K); the
# bound of each point from the widths of its own cell in the file's axes
for mt in aneos_gas:aneos.table no_counts:aneos.table linear:linear.table irregular:irregular.table; do
  "$PY" - "$eos" "${mt%%:*}" "${mt#*:}" <<'PY' || fail=1
import subprocess, sys, numpy as np
eos, mat, table = sys.argv[1:4]
t = np.loadtxt(table, skiprows=3)
ax_r, ax_e = np.unique(t[:, 0]), t[t[:, 0] == t[0, 0], 1]
rng = np.random.default_rng(7)
rho = np.exp(rng.uniform(np.log(ax_r[0]), np.log(ax_r[-1]), 400))
u = np.exp(rng.uniform(np.log(ax_e[0]), np.log(ax_e[-1]), 400))
out = subprocess.run([eos, "--stdin", "lib.yml", mat], input="\n".join("%.17g %.17g" % p for p in zip(rho, u)),
                     capture_output=True, text=True, check=True).stdout
d = np.loadtxt(out.splitlines()[1:])
P_a, c_a, T_a = 2.0 / 3.0 * rho * u, np.sqrt(10.0 / 9.0 * u), u / 1000.0
eP, ec, eT = (np.abs(d[:, k] / ref - 1.0) for k, ref in ((2, P_a), (3, c_a), (4, T_a)))
# P = C exp(x + y) in x = ln rho, y = ln e: bilinear interpolation in a cell
# of widths hr, hu errs by at most exp(hr + hu) (hr^2 + hu^2) / 8 relative;
# c^2 and T are C exp(y): at most exp(hu) hu^2 / 8 (c: half of that of c^2)
i = np.searchsorted(ax_r, rho, side="right") - 1
j = np.searchsorted(ax_e, u, side="right") - 1
hr, hu = np.log(ax_r[i + 1] / ax_r[i]), np.log(ax_e[j + 1] / ax_e[j])
bP = np.exp(hr + hu) * (hr * hr + hu * hu) / 8
bT = np.exp(hu) * hu * hu / 8
ok = np.all(eP <= bP) and np.all(ec <= bT / 2 + 1e-9) and np.all(eT <= bT)
print("%s %s: miluphcuda table vs the ideal gas: max rel error P %.2e (max error/bound %.2f), c %.2e (%.2f), T %.2e (%.2f)"
      % ("ok:" if ok else "FAIL:", mat, eP.max(), np.max(eP / bP), ec.max(), np.max(ec / (bT / 2 + 1e-9)),
         eT.max(), np.max(eT / bT)))
# not trivially exact: points between nodes do carry an interpolation error
sys.exit(0 if ok and eP.max() > 1e-4 else 1)
PY
done

# 1b. outside the table (theory/eos.md T1; axes rho 1..1e4, e 1e4..1e8, 40 x 50)
"$PY" - "$eos" <<'PY' || fail=1
import subprocess, sys, numpy as np
eos = sys.argv[1]
def run(mat, rho, u):
    out = subprocess.run([eos, "--stdin", "lib.yml", mat], capture_output=True, text=True, check=True,
                         input="\n".join("%.17g %.17g" % p for p in zip(rho, u))).stdout
    return np.loadtxt(out.splitlines()[1:], ndmin=2)
hr, hu = np.log(1e4) / 39, np.log(1e4) / 49
rng = np.random.default_rng(3)
rho_in = np.exp(rng.uniform(0.0, np.log(1e4), 50))
u_in = np.exp(rng.uniform(np.log(1e4), np.log(1e8), 50))
ok = True
def check(what, got, ref, bound):
    global ok
    e = np.max(np.abs(got / ref - 1.0))
    good = e <= bound
    ok = ok and good
    print("%s outside the table: %s: max rel error %.2e (bound %.2e)" % ("ok:" if good else "FAIL:", what, e, bound))
# above the last energy, gamma_vapor 1.4: the ideal gas (T1), exact up to
# bolide-eos's output of 10 significant digits (5e-10 relative)
u_hi = 1e8 * np.exp(rng.uniform(0.0, np.log(100.0), 50))
d = run("vapor", rho_in, u_hi)
check("e > e_max with gamma_vapor: P = 0.4 rho e", d[:, 2], 0.4 * rho_in * u_hi, 5e-10)
check("e > e_max with gamma_vapor: c^2 = 1.4 * 0.4 e", d[:, 3], np.sqrt(0.56 * u_hi), 5e-10)
# without gamma_vapor: e clamped to e_max (interpolated in rho only)
d = run("no_counts", rho_in, u_hi)
check("e > e_max without gamma_vapor: P(rho, e_max)", d[:, 2], 2.0 / 3.0 * rho_in * 1e8, np.exp(hr) * hr * hr / 8)
# below the first energy: clamped to e_min (the cold curve), with and without gamma_vapor
u_lo = 1e4 * np.exp(-rng.uniform(0.0, np.log(100.0), 50))
for m in ("vapor", "no_counts"):
    d = run(m, rho_in, u_lo)
    check("%s: e < e_min: P(rho, e_min)" % m, d[:, 2], 2.0 / 3.0 * rho_in * 1e4, np.exp(hr) * hr * hr / 8)
# beyond the densities: linear in rho from the outermost cell, which is exact
# in rho for P = (2/3) rho e (the error is that of the e interpolation);
# a clamp would be off by the ratio rho / rho_edge (here at least 1.25)
rho_out = np.concatenate([1e4 * np.exp(rng.uniform(np.log(1.25), np.log(3.0), 25)),
                          np.exp(-rng.uniform(np.log(1.25), np.log(4.0), 25))])
d = run("vapor", rho_out, u_in)
check("rho outside: P linear in rho", d[:, 2], 2.0 / 3.0 * rho_out * u_in, np.exp(hu) * hu * hu / 8)
check("rho outside: c (c^2 of e only)", d[:, 3], np.sqrt(10.0 / 9.0 * u_in), np.exp(hu) * hu * hu / 16 + 1e-9)
sys.exit(0 if ok else 1)
PY

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
# an energy axis that does not stay positive (interpolated in ln e)
awk 'NR > 3 && (NR - 4) % 50 == 0 { $2 = 0 } { print }' aneos.table >zero.table
bad zero zero.table
expect_error zero "zero.table: energy node 0 is 0: table axes must be positive"
# gamma_vapor between 0 and 1
printf 'soft_vapor:\n  eos: table\n  file: aneos.table\n  format: miluphcuda\n  rho0: 100\n  gamma_vapor: 0.5\n' >>lib.yml
expect_error soft_vapor "gamma_vapor.*must be 0 .* or larger than 1"
# n_rho without format miluphcuda
printf 'counts_rho_u:\n  eos: table\n  file: aneos.table\n  n_rho: 40\n  n_e: 50\n  rho0: 100\n' >>lib.yml
expect_error counts_rho_u "keys n_rho, n_e belong to format: miluphcuda"
exit $fail
