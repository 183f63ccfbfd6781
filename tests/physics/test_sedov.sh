#!/usr/bin/env bash
# Sedov-Taylor blast (theory/validation.md): at t = 0.05 the shock radius is within
# 3% of the similarity solution (moment estimator of tools/plot_sedov.py)
# and the total energy is conserved to 0.5%.  32,768 particles.
set -euo pipefail
B=${BOLIDE_BUILDDIR:?}; S=${BOLIDE_SRCDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$B/bolide-ic" sedov --n 32 --energy 1 --rho 1 -o sedov.hdf5 >/dev/null
cp "$S/examples/SedovBlast3D/params.yml" .
"$B/bolide" -t 2 params.yml >run.log 2>&1 || { tail -5 run.log; exit 1; }
"$PYTHON" "$S/tools/plot_sedov.py" sedov_0002.hdf5 --initial sedov.hdf5 --out sedov.png >out.txt
cat out.txt
fail=0
rel=$(awk '$1=="shock_radius_moment" {print $7}' out.txt)
awk -v r=$rel 'BEGIN{exit !(r < 0.03 && r > -0.03)}' || { echo "FAIL: shock radius off by $rel"; fail=1; }
# energy: first and last E_tot of the statistics file (column named E_tot)
drift=$(awk '/^# step/ {for (k = 2; k <= NF; k++) if ($k == "E_tot") c = k - 1}
             !/^#/ {if (first == "") first = $c; last = $c}
             END {printf "%.6e", (last - first) / first}' statistics.txt)
echo "relative energy change $drift"
awk -v d=$drift 'BEGIN{exit !(d < 0.005 && d > -0.005)}' || { echo "FAIL: energy not conserved"; fail=1; }
exit $fail
