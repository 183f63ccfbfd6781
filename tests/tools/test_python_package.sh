#!/usr/bin/env bash
# The bolide Python package (issue 23 item 5): it installs with pip into a
# fresh virtual environment (no network: --no-deps and --no-build-isolation,
# the project's venv providing numpy, h5py, unyt, matplotlib to it), carries
# Bolide's version, and its functions and console scripts run on a small
# snapshot: load_snapshot / load_statistics give SI whatever the run's
# units, and bolide-plot-impact finds an intact planet in SWIFT's planetary
# units (Earth mass and radius) entirely bound (it reported 0 when it
# ignored the snapshot's units).
set -uo pipefail
B=${BOLIDE_BUILDDIR:?}; S=${BOLIDE_SRCDIR:?}
PY=${PYTHON:-$B/.venv/bin/python}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
fail=0
version=$(sed -n 's/^AC_INIT(\[bolide\], \[\([^]]*\)\].*/\1/p' "$S/configure.ac")

make -s -C "$B" python >/dev/null || { echo "FAIL: make python"; exit 1; }
# a fresh venv that sees the project venv's packages (numpy, h5py, unyt...)
site=$("$PY" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
/usr/bin/python3 -m venv --system-site-packages fresh || { echo "skip: no venv module"; exit 77; }
fresh/bin/python -c "import wheel" 2>/dev/null || { echo "skip: no wheel package to build with (Debian python3-wheel)"; exit 77; }
echo "$site" >"$(fresh/bin/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')/project.pth"
fresh/bin/python -m pip install -q --no-deps --no-build-isolation --disable-pip-version-check "$B/python" \
  >pip.log 2>&1 || { echo "FAIL: pip install $B/python"; cat pip.log; exit 1; }
got=$(cd / && "$work/fresh/bin/python" -c 'import bolide; print(bolide.__version__)')
[ "$got" = "$version" ] && echo "ok: installed, bolide.__version__ = $got" ||
  { echo "FAIL: bolide.__version__ '$got', expected '$version'"; fail=1; }
for s in bolide-plot-impact bolide-plot-fragments bolide-plot-profile bolide-plot-tasks; do
  fresh/bin/$s --help >/dev/null 2>&1 || { echo "FAIL: console script $s --help"; fail=1; }
done

# an intact planet, in SI and in SWIFT's planetary units, run for one step
"$B/bolide-ic" planet --materials iron,granite --mass 5.97e24 --mass-fractions 0.3,0.7 --n 2000 \
  --profile profile.txt -o planet.hdf5 >/dev/null 2>&1 || { echo "FAIL: bolide-ic planet"; exit 1; }
# the profile plot of the planet's profile, and one of a file that is not one
fresh/bin/bolide-plot-profile profile.txt profile.png >/dev/null 2>&1 && [ -s profile.png ] &&
  echo "ok: bolide-plot-profile" || { echo "FAIL: bolide-plot-profile profile.txt"; fail=1; }
fresh/bin/bolide-plot-profile planet.hdf5 bad.png >/dev/null 2>bad.err
[ $? -ne 0 ] && [ "$(wc -l <bad.err)" -eq 1 ] && grep -q "^bolide-plot-profile: error: planet.hdf5" bad.err &&
  [ ! -e bad.png ] || { echo "FAIL: bolide-plot-profile on an HDF5 file: not one error line:"; cat bad.err; fail=1; }
for sys in si earth; do
  mkdir -p $sys
  if [ $sys = earth ]; then
    units="InternalUnitSystem: {UnitMass_in_cgs: 5.9724e27, UnitLength_in_cgs: 6.371e8, UnitVelocity_in_cgs: 6.371e8}"
  else
    units="InternalUnitSystem: {UnitMass_in_cgs: 1000, UnitLength_in_cgs: 100, UnitVelocity_in_cgs: 100}"
  fi
  cat >$sys/p.yml <<YML
$units
InitialConditions: {file_name: ../planet.hdf5}
TimeIntegration: {time_end: 1000}
Snapshots: {subdir: out}
Gravity: {max_physical_baryon_softening: 0}
Materials: {100: {name: iron}, 101: {name: granite}}
YML
  (cd $sys && "$B/bolide" -s -G -n 1 p.yml >run.log 2>&1) || { echo "FAIL: run in $sys units"; tail -3 $sys/run.log; fail=1; }
  (cd $sys/out && "$work/fresh/bin/bolide-plot-impact" snapshot_0000.hdf5 --stats statistics.txt --prefix "$sys"_ \
     >../impact.txt 2>../impact.err) || { echo "FAIL: bolide-plot-impact ($sys)"; cat $sys/impact.err; fail=1; }
  frac=$(awk '!/^#/ {print $3; exit}' $sys/impact.txt)
  awk -v f="$frac" 'BEGIN {exit !(f > 0.999)}' && echo "ok: $sys units: bound fraction $frac" ||
    { echo "FAIL: $sys units: bound fraction '$frac' of an intact planet"; fail=1; }
  [ -f $sys/out/${sys}_bound.png ] && [ -f $sys/out/${sys}_energy.png ] || { echo "FAIL: plots ($sys)"; fail=1; }
done
# a bolide-fof table of the planet in Earth units, for snapshot.read_fragments
"$B/bolide-fof" earth/out/snapshot_0000.hdf5 -o fragments.txt >/dev/null 2>&1 || { echo "FAIL: bolide-fof"; fail=1; }
# the fragment plot: the intact planet is one fragment, all of the mass
fresh/bin/bolide-plot-fragments fragments.txt -o spectrum.png >spectrum.txt 2>&1 && [ -s spectrum.png ] &&
  awk '/^largest_fraction/ {f = $3} END {exit !(f > 0.999999)}' spectrum.txt &&
  echo "ok: bolide-plot-fragments: $(cat spectrum.txt)" || { echo "FAIL: bolide-plot-fragments"; cat spectrum.txt; fail=1; }
# the task plot of a task dump (-y 1)
(cd si && "$B/bolide" -s -G -n 1 -y 1 -P Snapshots:subdir:out_y p.yml >/dev/null 2>&1) &&
  fresh/bin/bolide-plot-tasks si/out_y/tasks_step000001.txt -o tasks.png >tasks.txt 2>&1 && [ -s tasks.png ] &&
  echo "ok: bolide-plot-tasks" || { echo "FAIL: bolide-plot-tasks"; cat tasks.txt; ls si/out_y; fail=1; }
# load_snapshot / load_statistics: the same SI numbers from both unit systems
(cd / && "$work/fresh/bin/python" - "$work" <<'PY') || fail=1
import sys, numpy as np, bolide
w = sys.argv[1]
a, b = (bolide.load_snapshot("%s/%s/out/snapshot_0000.hdf5" % (w, s)) for s in ("si", "earth"))
sa, sb = (bolide.load_statistics("%s/%s/out/statistics.txt" % (w, s)) for s in ("si", "earth"))
ok = True
for name in ("masses", "coordinates", "densities", "internal_energies"):
    x, y = getattr(a, name), getattr(b, name)
    same = str(x.units) == str(y.units) and np.allclose(x.value, y.value, rtol=1e-9, atol=0)
    print("ok " if same else "FAIL", "load_snapshot %s: %s in both unit systems" % (name, x.units))
    ok &= same
for name in ("mass", "E_int", "E_pot", "time"):
    x, y = getattr(sa, name), getattr(sb, name)
    same = str(x.units) == str(y.units) and np.allclose(x.value[:1], y.value[:1], rtol=1e-6)
    print("ok " if same else "FAIL", "load_statistics %s(t=0): %s in both unit systems" % (name, x.units))
    ok &= same
ok &= bool(abs(a.masses.sum().to("kg").value - 5.97e24) < 1e-6 * 5.97e24)
# every column's dimension is the one its "Unit =" line gives (no list by hand)
import unyt
for name, unit in (("time", "s"), ("mass", "kg"), ("px", "kg*m/s"), ("Lz", "kg*m**2/s"),
                   ("E_tot", "J"), ("W_plastic", "J"), ("m_removed", "kg"), ("n_particles", "dimensionless")):
    same = getattr(sb, name).units.dimensions == unyt.Unit(unit).dimensions
    print("ok " if same else "FAIL", "load_statistics %s in %s" % (name, getattr(sb, name).units))
    ok &= same
# read_fragments (what tools/ and examples/ read bolide-fof tables with):
# SI columns, the header's total mass and time; the intact planet is one fragment
from bolide import snapshot
cols, info = snapshot.read_fragments("%s/fragments.txt" % w)
same = (abs(info["total_mass"] - 5.97e24) < 1e-6 * 5.97e24 and info["time"] == 0.0
        and abs(cols["mass"][0] / info["total_mass"] - 1.0) < 1e-9 and int(cols["count"][0]) == a.masses.size)
print("ok " if same else "FAIL", "read_fragments: total mass %.6g kg, time %s s, largest fragment %.6g kg of %d particles"
      % (info["total_mass"], info["time"], cols["mass"][0], int(cols["count"][0])))
ok &= same
# the plots as functions (what the console scripts call), on the same files
import matplotlib
matplotlib.use("Agg")
from bolide import plot_fragments, plot_impact, plot_profile, plot_tasks
snaps = plot_impact.load_snapshots(["%s/earth/out/snapshot_0000.hdf5" % w])
hist = plot_impact.bound_history(snaps)
fig = plot_impact.collision_figure(snaps)
same = hist["fraction"][0] > 0.999 and list(hist["materials"]) == [100, 101] and len(fig.axes) >= 1
print("ok " if same else "FAIL", "plot_impact.bound_history: bound fraction %.6f, materials %s; collision_figure"
      % (hist["fraction"][0], [int(k) for k in hist["materials"]]))
ok &= bool(same)
fig, fr = plot_fragments.spectrum(["%s/fragments.txt" % w])
print("ok " if fr[0] > 0.999999 else "FAIL", "plot_fragments.spectrum: largest fraction %.6f" % fr[0])
ok &= bool(fr[0] > 0.999999)
fig = plot_profile.profile_figure("%s/profile.txt" % w)
print("ok " if len(fig.axes) == 4 else "FAIL", "plot_profile.profile_figure: %d panels" % len(fig.axes))
ok &= len(fig.axes) == 4
fig = plot_tasks.timeline("%s/si/out_y/tasks_step000001.txt" % w)
print("ok " if len(fig.axes) == 1 else "FAIL", "plot_tasks.timeline")
ok &= len(fig.axes) == 1
try:
    snapshot.read_fragments("%s/si/out/statistics.txt" % w)
    print("FAIL read_fragments accepts a statistics file"); ok = False
except snapshot.SnapshotError as exc:
    print("ok  read_fragments refuses a statistics file:", exc)
sys.exit(0 if ok else 1)
PY
exit $fail
