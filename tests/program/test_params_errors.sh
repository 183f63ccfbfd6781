#!/bin/bash
# Every class of parameter error stops params_read with exit status 1 and ONE
# line on stderr that names the file (or the -P argument), the line and the
# key, with the expected explanation.  The bad inputs are
# tests/data/params_err_*.yml; tests/helpers/params_check reads them as bolide does.
set -u
check="$BOLIDE_BUILDDIR/tests/helpers/params_check"
data="$BOLIDE_SRCDIR/tests/data"
valid="$data/params_valid.yml"
fails=0

# expect_error "ARGS" "SUBSTRING"...: params_check ARGS must fail with one
# stderr line "params_check: error: ..." containing every SUBSTRING.
expect_error() {
  local args=$1; shift
  local err rc
  err=$(eval "\"$check\" $args" 2>&1 >/dev/null); rc=$?
  if [ "$rc" -ne 1 ]; then
    echo "FAIL: params_check $args: exit status $rc, expected 1"; fails=$((fails + 1)); return
  fi
  if [ "$(printf '%s\n' "$err" | wc -l)" -ne 1 ]; then
    echo "FAIL: params_check $args: expected one line, got:"; echo "$err"; fails=$((fails + 1)); return
  fi
  case $err in
    "params_check: error: "*) ;;
    *) echo "FAIL: params_check $args: no 'params_check: error:' prefix: $err"; fails=$((fails + 1)); return ;;
  esac
  for want in "$@"; do
    case $err in
      *"$want"*) ;;
      *) echo "FAIL: params_check $args: '$want' missing in: $err"; fails=$((fails + 1)); return ;;
    esac
  done
  echo "ok: $err"
}

# expect_error_file NAME LINE "SUBSTRING"...: tests/data/params_err_NAME.yml fails at LINE
expect_error_file() {
  local name=$1 line=$2; shift 2
  expect_error "'$data/params_err_$name.yml'" "params_err_$name.yml:$line: " "$@"
}

expect_error_file unknown_key 6 "unknown key 'SPH:CFL_conditon'" "(did you mean 'SPH:CFL_condition'?)"
expect_error_file wrong_section 7 "unknown key 'SPH:theta_cr'" "(did you mean 'Gravity:theta_cr'?)"
expect_error_file unknown_section 5 "unknown section 'SHP'" "(did you mean 'SPH'?)"
expect_error_file int 7 "Snapshots:compression" "expected an integer" "'1.5'"
expect_error_file real 6 "SPH:CFL_condition" "expected a number" "'fast'"
expect_error_file bool 6 "Gravity:enabled" "expected true or false" "'maybe'"
expect_error_file enum 6 "SPH:density" "'sumation' is not one of: summation, continuity"
expect_error_file array 3 "InitialConditions:shift" "element 2: expected a number" "'abc'"
expect_error_file array_map 3 "InitialConditions:shift" "got a mapping"
expect_error_file scalar_seq 4 "TimeIntegration:time_end" "got a sequence"
expect_error_file range 6 "SPH:CFL_condition" "5 is out of range" "[0.0001, 1]"
expect_error_file range_int 6 "Snapshots:compression" "12 is out of range" "[0, 9]"
expect_error_file range_array 3 "InitialConditions:box_size" "-2 is out of range" ">= 0"
expect_error_file duplicate 8 "duplicate key 'SPH:CFL_condition'" "first given at line 6"
expect_error_file duplicate_section 5 "duplicate key 'InitialConditions'" "first given at line 1"
expect_error_file syntax 7 "YAML syntax error" "flow sequence started at line 6"
expect_error_file not_mapping 5 "section 'SPH' must be a mapping"
expect_error_file top_level 2 "must be a mapping of sections"
expect_error_file two_documents 6 "second YAML document"
expect_error_file alias_loop 5 "recursive or exploding alias"
expect_error_file alias_bomb 2 "100000 values"
# a missing required key has no line: the file, the key and its meaning
expect_error "'$data/params_err_missing.yml'" "params_err_missing.yml: missing required key 'TimeIntegration:time_end'" "(simulation time at which the run stops)"
# files that cannot be read
expect_error "'$data/no_such_file.yml'" "no_such_file.yml: cannot open: No such file or directory"
expect_error "'$data'" "data: cannot open: Is a directory"
# bad -P overrides name the argument
expect_error "'$valid' -P SPH:CFL_condition:abc" "-P SPH:CFL_condition:abc: SPH:CFL_condition: expected a number, got 'abc'"
expect_error "'$valid' -P SPH:CFL_condition:7" "-P SPH:CFL_condition:7: SPH:CFL_condition: 7 is out of range"
expect_error "'$valid' -P SPH:CFL_conditon:0.1" "-P SPH:CFL_conditon:0.1: unknown key 'SPH:CFL_conditon'" "did you mean 'SPH:CFL_condition'"
expect_error "'$valid' -P Gravity:enabled:maybe" "-P Gravity:enabled:maybe: Gravity:enabled: expected true or false"
expect_error "'$valid' -P 'InitialConditions:shift:[1, 2'" "-P InitialConditions:shift:[1, 2: YAML syntax error"
expect_error "'$valid' -P nonsense" "-P nonsense: expected Section:key:value"
expect_error "'$valid' -P Materials:rock:1" "-P Materials:rock:1: section 'Materials' cannot be set with -P"

# hostile values (issue 18): arrays of the wrong length, texts too long or empty
for v in '[]' '[1]' '[1, 2]' '[1, 2, 3, 4]'; do
  n=$(echo "$v" | tr -cd ',' | wc -c); [ "$v" = '[]' ] && n=-1
  expect_error "'$valid' -P 'InitialConditions:shift:$v'" "InitialConditions:shift: $((n + 1)) value" "(expected 3)"
done
expect_error "'$valid' -P 'InitialConditions:box_size:[1, 2]'" "InitialConditions:box_size: 2 values given (expected 0, 1 or 3)"
long=$(printf 'd%.0s' $(seq 1 1100))
expect_error "'$valid' -P Snapshots:subdir:$long" "Snapshots:subdir: 'dddd" "is 1100 bytes long (at most 1023)"
expect_error "'$valid' -P Restarts:subdir:$long" "Restarts:subdir: 'dddd" "is 1100 bytes long (at most 1023)"
expect_error "'$valid' -P 'Snapshots:basename:'" "Snapshots:basename: must not be empty"
printf 'Snapshots:\n  basename: ""\nInitialConditions:\n  file_name: ics.hdf5\nTimeIntegration:\n  time_end: 1\n' >"${TMPDIR:-/tmp}/empty_basename.$$.yml"
expect_error "'${TMPDIR:-/tmp}/empty_basename.$$.yml'" "empty_basename.$$.yml:2: Snapshots:basename: must not be empty"
rm -f "${TMPDIR:-/tmp}/empty_basename.$$.yml"
# many keys with a duplicate at the end: the check was quadratic (90,000
# keys: 4e9 comparisons).  Timed against a tenth as many keys, so that a
# loaded machine does not fail it: 8x the keys must take < 25x the time
# (quadratic: 64x).
big="${TMPDIR:-/tmp}/many_keys.$$.yml"
keys_ms() { # N: milliseconds to refuse N keys + a duplicate
  { echo 'SPH:'; seq 1 "$1" | sed 's/.*/  k&: 1/'; echo '  k7: 2'; } >"$big"
  local start=$(date +%s%N)
  expect_error "'$big'" "many_keys.$$.yml:$(($1 + 2)): duplicate key 'SPH:k7' (first given at line 8)" >/dev/null
  echo $(( ($(date +%s%N) - start) / 1000000 ))
}
ms1=$(keys_ms 10000)
ms8=$(keys_ms 80000)
if [ "$ms8" -gt $((25 * ms1 + 200)) ]; then
  echo "FAIL: 80,000 keys took $ms8 ms, 10,000 keys $ms1 ms (quadratic?)"; fails=$((fails + 1))
else
  echo "ok: 80,000 keys refused in $ms8 ms (10,000 in $ms1 ms)"
fi
rm -f "$big"

# and the valid file passes, with a -P value holding ':'
out=$("$check" "$valid" -P "MetaData:run_name:a:b" MetaData:run_name SPH:CFL_condition 2>&1)
if [ "$out" != "$(printf 'MetaData:run_name=a:b\nSPH:CFL_condition=0.29999999999999999')" ]; then
  echo "FAIL: valid file: $out"; fails=$((fails + 1))
fi

[ "$fails" -eq 0 ] || { echo "$fails failures"; exit 1; }
exit 0
