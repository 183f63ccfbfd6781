#!/usr/bin/env bash
# bolide-ic import-miluphcuda (issue 23 item 7, ASCII and HDF5 input): files written
# here in miluphcuda's ASCII layouts (a hydro run: x v m rho e mat; a solid,
# porous run: x v m rho e sml mat S(9) alpha_jutzi p) come out as initial
# conditions with the same values (h = sml / kernel_gamma, the symmetric
# part of S, alpha as the distention), pass `bolide --check` with a
# Materials section for their ids; a line with the wrong number of columns
# is one error line naming the file, the line and the expected columns.  The
# solid file written as miluphcuda's HDF5 input (its dataset names) imports
# to the same initial conditions as the ASCII one; an HDF5 file without /x is
# one error line.  FRAGMENTATION (--fragmentation; HDF5
# /activation_thresholds zero-padded and /DIM_root_of_damage_tensile): each
# particle's flaws (0 to 9, in no order) come out as Bolide's FlawOffsets and
# FlawThresholds, sorted, d as DamageCubeRoot and d^3 as Damage, the same
# from ASCII and HDF5, and `bolide --check` reads them; a negative threshold
# or a fractional flaw count is one error line.
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}; S=${BOLIDE_SRCDIR:?}
PY=${PYTHON:-$B/.venv/bin/python}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
fail=0
ic="$B/bolide-ic"
params_for() { # IC MATERIAL_0 MATERIAL_1: a parameter file for the initial conditions IC
  printf 'InitialConditions:\n  file_name: %s\nTimeIntegration:\n  time_end: 1\nMaterials:\n  0: %s\n  1: %s\n' "$@"
}

"$PY" - <<'PY' || exit 1
import numpy as np
rng = np.random.default_rng(7)
n = 500
# two bodies of 250 particles each, materials 0 and 1, on a 1 km lattice-ish cloud
x = rng.uniform(-5e3, 5e3, (n, 3)); x[250:, 0] += 2e4
v = np.zeros((n, 3)); v[250:, 0] = -3e3
m = np.full(n, 2.7e12)
rho = np.where(np.arange(n) < 250, 7800.0, 2700.0)
e = np.full(n, 1e4)
mat = (np.arange(n) >= 250).astype(int)
with open("hydro.0000", "w") as f:
    for i in range(n):
        f.write("%.17e\t%.17e\t%.17e\t%.17e\t%.17e\t%.17e\t%.17e\t%.17e\t%.17e\t%d\n"
                % (*x[i], *v[i], m[i], rho[i], e[i], mat[i]))
sml = np.full(n, 2.5e3)
Sm = rng.normal(0, 1e6, (n, 3, 3)); Sm = 0.5 * (Sm + Sm.transpose(0, 2, 1))
alpha = np.full(n, 1.25)
with open("solid.0000", "w") as f:
    for i in range(n):
        cols = list(x[i]) + list(v[i]) + [m[i], rho[i], e[i], sml[i]]
        f.write(" ".join("%.17e" % c for c in cols) + " %d " % mat[i]
                + " ".join("%.17e" % c for c in Sm[i].ravel()) + " %.17e 0\n" % alpha[i])
np.savez("truth.npz", x=x, v=v, m=m, rho=rho, e=e, mat=mat, sml=sml, S=Sm, alpha=alpha)
# the same solid, porous particles as miluphcuda's HDF5 input file (its
# dataset names; material_type an integer dataset, S as N x 9)
import h5py
with h5py.File("solid.h5", "w") as f:
    f["x"] = x; f["v"] = v; f["m"] = m; f["rho"] = rho; f["e"] = e; f["sml"] = sml
    f["material_type"] = mat.astype(np.int32); f["deviatoric_stress"] = Sm.reshape(n, 9)
    f["alpha_jutzi"] = alpha; f["p"] = np.zeros(n); f["time"] = np.array([0.0])
with h5py.File("nox.h5", "w") as f:
    f["v"] = v
# FRAGMENTATION: x v m rho e sml mat n_flaws d S(9), then the flaws
nf = rng.integers(0, 10, n); nf[:5] = 0
d = rng.uniform(0.0, 1.0, n); d[:20] = 0.0
flaws = [rng.uniform(1e-5, 1e-3, k) for k in nf]  # not sorted
with open("frag.0000", "w") as f:
    for i in range(n):
        cols = list(x[i]) + list(v[i]) + [m[i], rho[i], e[i], sml[i]]
        f.write(" ".join("%.17e" % c for c in cols) + " %d %d %.17e " % (mat[i], nf[i], d[i])
                + " ".join("%.17e" % c for c in Sm[i].ravel())
                + "".join(" %.17e" % c for c in flaws[i]) + "\n")
maxnof = nf.max()
at = np.zeros((n, maxnof))
for i in range(n):
    at[i, :nf[i]] = flaws[i]
with h5py.File("frag.h5", "w") as f:
    f["x"] = x; f["v"] = v; f["m"] = m; f["rho"] = rho; f["e"] = e; f["sml"] = sml
    f["material_type"] = mat.astype(np.int32); f["deviatoric_stress"] = Sm.reshape(n, 9)
    f["activation_thresholds"] = at; f["DIM_root_of_damage_tensile"] = d
    f["number_of_activated_flaws"] = np.zeros(n, np.int32)
    f["maximum_number_of_flaws"] = np.array([maxnof], np.int32)
np.savez("frag_truth.npz", nf=nf, d=d, eps=np.concatenate(flaws))
PY

"$ic" import-miluphcuda hydro.0000 -o hydro.hdf5 >hydro.log 2>&1 || { echo "FAIL: import hydro"; cat hydro.log; fail=1; }
"$ic" import-miluphcuda solid.0000 --sml --solid --palpha -o solid.hdf5 >solid.log 2>&1 ||
  { echo "FAIL: import solid"; cat solid.log; fail=1; }
# HDF5 input: its datasets name the columns, no switches
"$ic" import-miluphcuda solid.h5 -o solid_h5.hdf5 >solid_h5.log 2>&1 ||
  { echo "FAIL: import solid.h5"; cat solid_h5.log; fail=1; }
grep -q "deviatoric_stress alpha_jutzi" solid_h5.log || { echo "FAIL: solid.h5: datasets read: $(cat solid_h5.log)"; fail=1; }
# FRAGMENTATION's flaws and damage, ASCII and HDF5
"$ic" import-miluphcuda frag.0000 --sml --fragmentation --solid -o frag.hdf5 >frag.log 2>&1 ||
  { echo "FAIL: import frag.0000"; cat frag.log; fail=1; }
"$ic" import-miluphcuda frag.h5 -o frag_h5.hdf5 >frag_h5.log 2>&1 ||
  { echo "FAIL: import frag.h5"; cat frag_h5.log; fail=1; }
grep -q "activation_thresholds DIM_root_of_damage_tensile" frag_h5.log || { echo "FAIL: frag.h5: datasets read: $(cat frag_h5.log)"; fail=1; }
"$PY" - <<'PY' || fail=1
import h5py, numpy as np, sys
# the HDF5 import equals the ASCII import of the same particles, field by
# field (the flaws' datasets included)
fails = 0
for name in ("solid", "frag"):
    with h5py.File(name + ".hdf5", "r") as a, h5py.File(name + "_h5.hdf5", "r") as b:
        ga, gb = a["PartType0"], b["PartType0"]
        bad = [k for k in ga if not np.array_equal(ga[k][...], gb[k][...])] + sorted(set(ga) ^ set(gb))
        print(("FAIL %s.h5 differs from %s.0000 in %s" % (name, name, " ".join(bad))) if bad
              else "ok   %s.h5 (HDF5) imports as %s.0000 (ASCII): %d fields equal" % (name, name, len(ga)))
        fails += len(bad)
sys.exit(1 if fails else 0)
PY
params_for frag.hdf5 "{name: iron, shear_modulus: 80e9, weibull_k: 1e61, weibull_m: 16}" \
  "{name: granite, shear_modulus: 24e9, weibull_k: 1e61, weibull_m: 16}" >pf.yml
"$B/bolide" --check pf.yml >checkf.log 2>&1 || { echo "FAIL: bolide --check on the import with flaws"; cat checkf.log; fail=1; }
# a step of the run takes the flaws from the initial conditions, all of them
nflaws=$("$PY" -c 'import numpy as np; print(int(np.load("frag_truth.npz")["nf"].sum()))')
"$B/bolide" -n 1 pf.yml >runf.log 2>&1 || { echo "FAIL: bolide -n 1 with the flaws"; tail -5 runf.log; fail=1; }
grep -q "damage: $nflaws Weibull flaws .* from the initial conditions" runf.log &&
  echo "ok: the run reads the $nflaws flaws from the initial conditions" ||
  { echo "FAIL: the run does not read the $nflaws flaws: $(grep damage: runf.log)"; fail=1; }
# bad flaws: one line with the file and line
awk 'NR == 7 { $NF = "-1e-4" } { print }' frag.0000 >badflaw.0000
awk 'NR == 9 { $12 = "2.5" } { print }' frag.0000 >badcount.0000
for b in "badflaw.0000:7: activation threshold .* is -0.0001 (must be finite and >= 0)" \
         "badcount.0000:9: number of flaws 2.5 must be an integer >= 0"; do
  file=${b%%:*}
  "$ic" import-miluphcuda "$file" --sml --fragmentation --solid -o bad_f.hdf5 >/dev/null 2>bad_f.err &&
    { echo "FAIL: $file: exit 0"; fail=1; }
  [ "$(wc -l <bad_f.err)" -eq 1 ] && grep -q "$b" bad_f.err && echo "ok: $(cat bad_f.err)" ||
    { echo "FAIL: $file: $(cat bad_f.err)"; fail=1; }
done
"$ic" import-miluphcuda nox.h5 -o nox.hdf5 >nox.out 2>nox.err && { echo "FAIL: nox.h5: exit 0"; fail=1; }
[ "$(wc -l <nox.err)" -eq 1 ] && grep -q "nox.h5: an HDF5 file without /x" nox.err ||
  { echo "FAIL: nox.h5: $(cat nox.err)"; fail=1; }
"$PY" - <<'PY' || fail=1
import h5py, numpy as np, sys
t = np.load("truth.npz")
bad = 0
def check(c, msg):
    global bad
    print(("ok  " if c else "FAIL") + " " + msg)
    bad += not c
for name in ("hydro", "solid"):
    with h5py.File(name + ".hdf5", "r") as f:
        g = f["PartType0"]
        x = g["Coordinates"][...]
        d = x - x.mean(0) - (t["x"] - t["x"].mean(0))
        check(np.abs(d).max() < 1e-9 * 2e4, "%s: positions (shifted into the box)" % name)
        check(np.allclose(g["Velocities"][...], t["v"], rtol=1e-15), "%s: velocities" % name)
        check(np.allclose(g["Masses"][...], t["m"], rtol=1e-15), "%s: masses" % name)
        check(np.allclose(g["Densities"][...], t["rho"], rtol=1e-15), "%s: densities" % name)
        check(np.allclose(g["InternalEnergies"][...], t["e"], rtol=1e-15), "%s: internal energies" % name)
        check(np.array_equal(g["MaterialIDs"][...], t["mat"]), "%s: material ids" % name)
        if name == "solid":
            h = g["SmoothingLengths"][...]
            gam = t["sml"][0] / h[0]
            check(np.allclose(h * gam, t["sml"], rtol=1e-12) and 1.7 < gam < 2.5,
                  "solid: h = sml / kernel_gamma (gamma %.4f)" % gam)
            S6 = g["DeviatoricStress"][...]
            S = t["S"]
            ref = np.stack([S[:, 0, 0], S[:, 0, 1], S[:, 0, 2], S[:, 1, 1], S[:, 1, 2], S[:, 2, 2]], 1)
            check(np.allclose(S6, ref, rtol=1e-12), "solid: deviatoric stress (6 of 9)")
            check(np.allclose(g["Distentions"][...], t["alpha"]), "solid: distention from alpha_jutzi")
# FRAGMENTATION: flaws and damage, ASCII and HDF5
t = np.load("frag_truth.npz")
for name in ("frag.hdf5", "frag_h5.hdf5"):
    with h5py.File(name, "r") as f:
        g = f["PartType0"]
        off, eps = g["FlawOffsets"][...], g["FlawThresholds"][...]
        check(off[0] == 0 and np.array_equal(np.diff(off), t["nf"]), "%s: flaw counts per particle" % name)
        ref = np.concatenate([np.sort(t["eps"][a:b]) for a, b in zip(np.r_[0, np.cumsum(t["nf"])[:-1]], np.cumsum(t["nf"]))])
        check(np.array_equal(eps, ref), "%s: thresholds, sorted per particle (%d)" % (name, len(eps)))
        check(np.array_equal(g["DamageCubeRoot"][...], t["d"]), "%s: DamageCubeRoot = d" % name)
        check(np.allclose(g["Damage"][...], t["d"] ** 3, rtol=1e-15, atol=0), "%s: Damage = d^3" % name)
sys.exit(1 if bad else 0)
PY

# the imported file runs through --check with materials for its ids
params_for hydro.hdf5 "{name: iron}" "{name: granite}" >p.yml
"$B/bolide" --check p.yml >check.log 2>&1 || { echo "FAIL: bolide --check on the import"; cat check.log; fail=1; }

# a wrong column count: one line naming file, line and the expected layout
sed '3s/\t[0-9]*$//' hydro.0000 >bad.0000
"$ic" import-miluphcuda bad.0000 -o bad.hdf5 >bad.out 2>bad.err; rc=$?
if [ $rc -ne 0 ] && [ "$(wc -l <bad.err)" -eq 1 ] &&
   grep -q "bolide-ic: error: bad.0000:3: 9 columns, expected 10 for these switches (x y z vx vy vz m rho e mat" bad.err; then
  echo "ok: $(cat bad.err)"
else
  echo "FAIL: wrong column count (exit $rc):"; cat bad.err; fail=1
fi
[ ! -e bad.hdf5 ] || { echo "FAIL: output written despite the error"; fail=1; }
exit $fail
