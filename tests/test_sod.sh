#!/usr/bin/env bash
# Sod shock tube (VALIDATION.md): L1 errors of density, velocity and pressure
# against the exact Riemann solution at t = 0.2, at two resolutions (7,776
# and 18,432 particles), each below a stated bound and falling with
# resolution.  The bounds and the measured values are in theory/tests.md.
set -euo pipefail
B=${BOLIDE_BUILDDIR:?}; S=${BOLIDE_SRCDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
declare -A bound=( [48,density]=0.020 [48,velocity]=0.035 [48,pressure]=0.025
                   [64,density]=0.016 [64,velocity]=0.028 [64,pressure]=0.021 )
fail=0
for nx in 48 64; do
  mkdir -p "n$nx"; cd "n$nx"
  "$B/bolide-ic" sod --nx $nx --size 2,0.25,0.25 -o sod.hdf5 >/dev/null
  cp "$S/examples/SodShock3D/params.yml" .
  "$B/bolide" -t 2 params.yml >run.log 2>&1 || { tail -5 run.log; exit 1; }
  "$PYTHON" "$S/tools/plot_sod.py" sod_0002.hdf5 --out sod.png >l1.txt
  for q in density velocity pressure; do
    v=$(awk -v q=$q '$1=="L1" && $2==q {print $3}' l1.txt)
    eval "L1_${nx}_$q=$v"
    ok=$(awk -v v=$v -v b=${bound[$nx,$q]} 'BEGIN{print (v < b) ? 1 : 0}')
    echo "nx=$nx L1($q) = $v (bound ${bound[$nx,$q]})"
    [ "$ok" = 1 ] || { echo "FAIL: L1($q) above its bound"; fail=1; }
  done
  cd ..
done
for q in density velocity pressure; do
  a=$(eval echo \$L1_48_$q); b=$(eval echo \$L1_64_$q)
  ok=$(awk -v a=$a -v b=$b 'BEGIN{print (b < a) ? 1 : 0}')
  [ "$ok" = 1 ] || { echo "FAIL: L1($q) does not fall with resolution ($a -> $b)"; fail=1; }
done
exit $fail
