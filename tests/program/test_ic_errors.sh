#!/usr/bin/env bash
# ic_read on malformed initial conditions: each must stop with exactly one
# line on stderr that names the file and the problem, and exit non-zero.
# The files are made by tests/data/make_bad_ics.py.
set -u
[ -x "${PYTHON:-}" ] || { echo "no Python venv: skip"; exit 77; }
dump="$BOLIDE_BUILDDIR/tests/helpers/ic_dump"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
"$PYTHON" "$BOLIDE_SRCDIR/tests/data/make_bad_ics.py" "$dir" || exit 1
fail=0

# expect CASE REGEX [extra ic_dump args]: one stderr line matching REGEX, rc != 0
expect() {
  local case="$1" regex="$2"; shift 2
  local f="$dir/$case.hdf5"
  "$dump" "$f" "$@" >"$dir/out" 2>"$dir/err"
  local rc=$? lines
  lines=$(wc -l <"$dir/err")
  if [ "$rc" -eq 0 ] || [ "$lines" -ne 1 ] || ! grep -Eq -- "^ic_dump: error: $f: $regex" "$dir/err"; then
    echo "FAIL $case: rc=$rc, $lines line(s):"; cat "$dir/err"; fail=1
  else
    echo "ok   $case: $(cat "$dir/err")"
  fi
}

expect nan_position 'particle 7 \(id 8\): position is nan \(must be finite\)'
expect negative_mass 'particle 5 \(id 6\): mass is -1 \(must be positive\)'
expect zero_h 'particle 9 \(id 10\): smoothing length is 0 \(must be positive\)'
expect duplicate_ids 'particles 3 and 12 have the same id 4'
expect mismatched_lengths 'dataset /PartType0/Masses has 19 particles but /PartType0/Coordinates has 20'
expect missing_dataset 'missing required dataset /PartType0/Masses'
expect unknown_material 'particle 4 \(id 5\): material id 999 is not a known material' --mat 101,102
expect wrong_shape 'dataset /PartType0/Velocities has the wrong shape'
expect id_too_large 'particle 2: ParticleIDs is 9223372036854775813 \(too large\)'
expect material_out_of_range 'particle 6: MaterialIDs is 1099511627776 \(out of range\)'
expect material_not_integer 'particle 8: MaterialIDs is 101.5 \(must be an integer\)'
expect negative_u 'particle 4 \(id 5\): InternalEnergies is -1 \(must be >= 0\)'
expect negative_density 'particle 2 \(id 3\): Densities is -[0-9.e+]* \(must be >= 0\)'
expect damage_above_one 'particle 11 \(id 12\): Damage is 1.5 \(must be in \[0, 1\]\)'
expect shear_damage_negative 'particle 1 \(id 2\): ShearDamage is -0.25 \(must be in \[0, 1\]\)'
expect numpart_minus_one '/Header/NumPart_Total\[0\] is -1 \(must be in \[0, 2\^32\)\)'
expect nan_time '/Header/Time is nan \(must be finite\)'
expect inf_box '/Header/BoxSize is inf \(must be finite and >= 0\)'
expect zero_particles 'no particles in /PartType0'
expect one_point 'particles 0 \(id 1\) and 1 \(id 2\) are at the same position \(0.5, 0.5, 0.5\)'
expect same_position 'particles 6 \(id 7\) and 13 \(id 14\) are at the same position'
expect many_same_position 'particles 123456 \(id 123457\) and 400000 \(id 400001\) are at the same position'
expect not_hdf5 'not an HDF5 file'
expect does_not_exist 'cannot open initial conditions: No such file or directory'

# the valid files load, with or without a material list (and the file of
# many particles whose positions share hashes of the reader, not positions)
for case in good aliases_no_units many_hash_collisions; do
  count=20; [ $case = many_hash_collisions ] && count=600000
  if ! "$dump" "$dir/$case.hdf5" --mat 101 >"$dir/out" 2>"$dir/err" || ! grep -q "^count $count\$" "$dir/out"; then
    echo "FAIL $case does not load:"; cat "$dir/err" "$dir/out"; fail=1
  else
    echo "ok   $case loads"
  fi
done
# the alias file (float32 etc.) holds the same values as the good one, so
# every field but those stored in single precision agrees: compare masses
m1=$("$dump" "$dir/good.hdf5" | grep mass_total)
m2=$("$dump" "$dir/aliases_no_units.hdf5" | grep -v '^\[' | grep mass_total)
python_check=$("$PYTHON" -c "import sys; a=float('$m1'.split()[1]); b=float('$m2'.split()[1]); print(abs(a-b) < 1e-7*a)")
[ "$python_check" = True ] || { echo "FAIL alias masses $m1 vs $m2"; fail=1; }
# the alias file has no /Units: one log line says so
"$dump" "$dir/aliases_no_units.hdf5" | grep -q 'no /Units group' || { echo "FAIL no log line for missing /Units"; fail=1; }

# snapshot_write failures: a missing folder, and a full disk (simulated with a
# file-size limit; SIGXFSZ ignored so that write() fails with EFBIG).  One
# line, exit 1, and neither the temporary nor the final file left behind.
"$BOLIDE_BUILDDIR/bolide-ic" box --n 40 -o "$dir/big.hdf5" >/dev/null || fail=1
"$dump" "$dir/big.hdf5" --write "$dir/missing/snap.hdf5" >/dev/null 2>"$dir/err"
rc=$?
if [ $rc -ne 1 ] || [ "$(wc -l <"$dir/err")" -ne 1 ] ||
   ! grep -q "^ic_dump: error: $dir/missing/snap.hdf5: cannot create .*No such file or directory" "$dir/err"; then
  echo "FAIL write into a missing folder: rc=$rc"; cat "$dir/err"; fail=1
else
  echo "ok   missing folder: $(cat "$dir/err")"
fi
mkdir -p "$dir/full"
(trap '' XFSZ; ulimit -f 200; "$dump" "$dir/big.hdf5" --write "$dir/full/snap.hdf5" >/dev/null 2>"$dir/err")
rc=$?
if [ $rc -ne 1 ] || [ "$(wc -l <"$dir/err")" -ne 1 ] ||
   ! grep -q "^ic_dump: error: $dir/full/snap.hdf5: cannot write dataset /PartType0/" "$dir/err" ||
   [ -n "$(ls -A "$dir/full")" ]; then
  echo "FAIL write on a full disk: rc=$rc, left: $(ls -A "$dir/full")"; cat "$dir/err"; fail=1
else
  echo "ok   disk full: $(cat "$dir/err")"
fi
exit $fail
