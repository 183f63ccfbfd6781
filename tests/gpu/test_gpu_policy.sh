#!/usr/bin/env bash
# Scheduler:gpu (src/gpu/gpu_policy.c): auto | off | all | [list of task
# families].  Needs no GPU: the value is checked in every build before any
# device is looked for.  A list naming some hydrodynamic families but not
# all, one naming gravity alone and an unknown family each stop bolide with
# exit status 1 and ONE line on stderr naming the file (or the -P argument)
# and the key: the missing families, or the known ones.  Valid forms (a YAML
# list, a comma-separated -P value, off, all) are accepted, and a list read
# back from used_parameters.yml is the same list.
set -u
B=${BOLIDE_BUILDDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
fails=0
"$B/bolide-ic" box --n 6 -o box.hdf5 >/dev/null || { echo "FAIL: bolide-ic"; exit 1; }
cat >base.yml <<'YML'
InitialConditions:
  file_name: box.hdf5
  periodic: true
TimeIntegration:
  time_end: 1
Snapshots:
  delta_time: 1
Statistics:
  delta_time: 1
YML

# expect_error FILE "ARGS" "SUBSTRING"...: bolide -n 0 ARGS FILE fails with one
# stderr line "bolide: error: ..." holding every SUBSTRING
expect_error() {
  local file=$1 args=$2; shift 2
  local err rc
  err=$(eval "\"$B/bolide\" -n 0 $args $file" 2>&1 >/dev/null); rc=$?
  if [ "$rc" -ne 1 ]; then
    echo "FAIL: bolide $args $file: exit status $rc, expected 1"; fails=$((fails + 1)); return
  fi
  if [ "$(printf '%s\n' "$err" | wc -l)" -ne 1 ]; then
    echo "FAIL: bolide $args $file: expected one line, got:"; echo "$err"; fails=$((fails + 1)); return
  fi
  for want in "bolide: error: " "$@"; do
    case $err in
      *"$want"*) ;;
      *) echo "FAIL: bolide $args $file: '$want' missing in: $err"; fails=$((fails + 1)); return ;;
    esac
  done
  echo "ok: $err"
}

# expect_ok FILE "ARGS" "SUBSTRING": bolide -n 0 ARGS FILE runs and logs SUBSTRING
expect_ok() {
  local file=$1 args=$2 want=$3 out
  if ! out=$(eval "\"$B/bolide\" -n 0 $args $file" 2>&1); then
    echo "FAIL: bolide $args $file failed:"; printf '%s\n' "$out" | tail -3; fails=$((fails + 1)); return
  fi
  case $out in
    *"$want"*) echo "ok: bolide $args $file: $want" ;;
    *) echo "FAIL: bolide $args $file: '$want' missing"; fails=$((fails + 1)) ;;
  esac
}

# some hydrodynamic families only (-P, YAML list syntax)
expect_error base.yml "--no-gpu -P 'Scheduler:gpu:[density, force]'" \
  "-P Scheduler:gpu:[density, force]" "Scheduler:gpu" "run on the GPU as one phase" \
  "lacks drift, gradient, damage, kick"
# the same as a comma-separated -P value
expect_error base.yml "-P Scheduler:gpu:density,gradient,force,damage,kick" "Scheduler:gpu" \
  "lacks drift"
# an unknown family
expect_error base.yml "-P 'Scheduler:gpu:[density, gradient, force, damage, drift, kick, gpu]'" \
  "'gpu' is not a task family" "auto, off, all or a list of drift, density, ghost, gradient, force, damage, kick, gravity"
# gravity alone, in the file: FILE:LINE: KEY
{ cat base.yml; printf 'Scheduler:\n  gpu: [gravity]\n'; } >grav_only.yml
expect_error grav_only.yml "" "grav_only.yml:11: Scheduler:gpu: " \
  "lacks drift, density, gradient, force, damage, kick"
# a mapping is no list
{ cat base.yml; printf 'Scheduler:\n  gpu: {density: 1}\n'; } >mapping.yml
expect_error mapping.yml "" "mapping.yml:11: " "Scheduler:gpu" "expected a word or a list of words"

# accepted forms
{ cat base.yml; printf 'Scheduler:\n  gpu: [density, ghost, gradient, force, damage, drift, kick, gravity]\n'; } >list.yml
# --no-gpu is logged by the CUDA build's GPU runner; a CPU-only build (no
# nvcc, or configure --without-cuda as the sanitizer builds) says so instead
gpu_off="GPU off (--no-gpu)"
"$B/bolide" -n 0 base.yml 2>&1 | grep -q 'CPU-only build' && gpu_off="CPU-only build: every task runs on the CPU"
expect_ok list.yml "--no-gpu -P Snapshots:subdir:out1" "$gpu_off"
expect_ok base.yml "--no-gpu -P Scheduler:gpu:density,gradient,force,damage,drift,kick" "$gpu_off"
expect_ok base.yml "-P Scheduler:gpu:off" "every task runs on the CPU"
expect_ok base.yml "-P 'Scheduler:gpu:[]'" "every task runs on the CPU"
expect_ok base.yml "--no-gpu -P Scheduler:gpu:all" "$gpu_off"
# the list as written to used_parameters.yml reads back as the same list
used=$(find . -name used_parameters.yml -path '*out1*' | head -1)
got=$("$B/tests/helpers/params_check" "$used" Scheduler:gpu 2>&1 | tail -1)
if [ "$got" = "Scheduler:gpu=[density, ghost, gradient, force, damage, drift, kick, gravity]" ]; then
  echo "ok: used_parameters.yml: $got"
else
  echo "FAIL: used_parameters.yml gives '$got'"; fails=$((fails + 1))
fi

[ $fails -eq 0 ] || { echo "$fails failures"; exit 1; }
echo PASS
