#!/usr/bin/env bash
# Sanitizer checks (issue 18 item 9), run by CI after tools/test.sh:
#  1. AddressSanitizer + UndefinedBehaviorSanitizer build in ./_build_asan
#     (without CUDA) and the fast tests of make check under it; every report
#     fails the test (halt_on_error);
#  2. ThreadSanitizer build of the scheduler stress test in ./_build_tsan;
#  3. a short run of each libFuzzer harness (make fuzz, FUZZ_SECONDS, 30 s
#     by default) when clang has libFuzzer.
# Usage: tools/test_sanitizers.sh [asan|tsan|fuzz|all] [TEST...]
#   (TEST...: the tests of step 1, default SAN_FAST_TESTS below; FULL runs
#   the whole make check under ASan + UBSan; HEAVY the tests that FAST
#   leaves out and that take minutes each under ASan, SAN_HEAVY_TESTS below.)
#   SAN_JOBS: tests (and compilations) at once, default the number of cores
#   (SAN_JOBS=1 on a shared machine: one test at a time).
#   SAN_BUILDDIR: the ASan build folder (default _build_asan);
#   SAN_CONFIGURE: further configure options (--with-kernel=cubic-spline, say);
#   SAN_PYTHON: the interpreter the Python tests run with instead of the
#   build's venv (a host without network: its python3 with h5py and numpy).
# On a 16-core host the whole suite: tools/test_sanitizers.sh asan FULL
# Closes with one line "sanitizers: ..." and exits non-zero on any failure.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
what="${1:-all}"
shift || true
jobs="${SAN_JOBS:-$(nproc 2>/dev/null || echo 2)}"
[ -x "$top/configure" ] || "$top/tools/setup.sh" >/dev/null
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1"
# The fast tests (about 6 minutes under ASan on 2 cores): the unit tests, the
# readers' and the CLI's error tests, the hostile inputs and the fuzz corpus,
# and short runs of bolide (restart, porosity).
SAN_FAST_TESTS="tests/unit/test_graph tests/unit/test_budget tests/unit/test_scheduler tests/unit/test_kernels
  tests/unit/test_pairs tests/unit/test_space_errors tests/unit/test_partition tests/unit/test_params tests/unit/test_units
  tests/unit/test_params_reference tests/program/test_params_errors.sh tests/unit/test_io_roundtrip
  tests/program/test_ic_errors.sh tests/unit/test_eos tests/unit/test_material tests/tools/test_bolide_eos.sh
  tests/tools/test_materials_yaml.sh tests/unit/test_porosity tests/tools/test_porosity_errors.sh
  tests/unit/test_damage tests/unit/test_flaws tests/unit/test_fof tests/unit/test_gravity_ops tests/unit/test_solids
  tests/program/test_bolide_cli.sh tests/program/test_restart.sh tests/program/test_hostile_inputs.sh
  tests/program/test_fuzz_corpus.sh tests/unit/test_timeline tests/unit/test_timestep tests/program/test_swift_params.sh
  tests/tools/test_miluphcuda_import.sh tests/tools/test_miluphcuda_materials.sh tests/tools/test_mesh_import.py"
# The heavy tests (hydrodynamic forms, self-gravity, the SEA shells, the
# Evrard collapse, the energy budget, the solid benchmarks): part of FULL,
# or alone with HEAVY.
SAN_HEAVY_TESTS="tests/unit/test_hydro_forms tests/unit/test_gravity_walk tests/unit/test_gravity_hsoft
  tests/unit/test_gravity_reuse tests/unit/test_gravity tests/physics/test_gravity_accuracy.sh tests/physics/test_energy_budget.sh
  tests/physics/test_sea_shells.py tests/physics/test_evrard.sh tests/physics/test_rotating_sphere.py tests/physics/test_rubber_rings.py"
status=0 summary=""

# configure DIR SANITIZERS: a build folder with the sanitizers, sharing _build's venv
configure_in() {
  local dir="$top/$1"
  mkdir -p "$dir"
  if [ ! -f "$dir/Makefile" ] || [ "$dir/config.status" -ot "$top/configure" ]; then
    (cd "$dir" && "$top/configure" --enable-sanitizers="$2" --without-cuda ${SAN_CONFIGURE:-} >configure.out 2>&1) ||
      { tail -20 "$dir/configure.out"; return 1; }
  fi
  if [ -d "$top/_build/.venv" ] && [ ! -e "$dir/.venv" ]; then ln -s "$top/_build/.venv" "$dir/.venv"; fi
}

if [ "$what" = all ] || [ "$what" = asan ]; then
  asan_dir="${SAN_BUILDDIR:-_build_asan}"
  configure_in "$asan_dir" address,undefined
  cd "$top/$asan_dir"
  pyarg=""; [ -n "${SAN_PYTHON:-}" ] && pyarg="PYTHON=$SAN_PYTHON"
  tests="${*:-$SAN_FAST_TESTS}"
  [ "$tests" = HEAVY ] && tests=$SAN_HEAVY_TESTS
  start=$(date +%s)
  set +e
  if [ "$tests" = FULL ]; then
    make -j"$jobs" check-summary $pyarg >check.out 2>&1
  else
    make -j"$jobs" check-summary $pyarg TESTS="$(echo $tests)" >check.out 2>&1
  fi
  rc=$?
  set -e
  grep -E '^(FAIL|ERROR|XPASS):' check.out || true
  if [ $rc -ne 0 ]; then
    for f in $(grep -l -E '^:test-result: (FAIL|ERROR)' $(find . -name '*.trs') 2>/dev/null); do
      echo "----- ${f%.trs}.log"; tail -40 "${f%.trs}.log"
    done
    status=1
  fi
  summary="$summary asan+ubsan: $(grep -E '^tests: ' check.out || echo 'build failed') in $(( $(date +%s) - start )) s;"
fi

if [ "$what" = all ] || [ "$what" = tsan ]; then
  configure_in _build_tsan thread
  cd "$top/_build_tsan"
  start=$(date +%s)
  if make -j"$jobs" tests/unit/test_scheduler >make.out 2>&1 && ./tests/unit/test_scheduler >tsan.out 2>&1; then
    summary="$summary tsan: test_scheduler passed in $(( $(date +%s) - start )) s;"
  else
    tail -40 make.out tsan.out; status=1
    summary="$summary tsan: test_scheduler FAILED;"
  fi
fi

if [ "$what" = all ] || [ "$what" = fuzz ]; then
  set +e
  FUZZ_SECONDS="${FUZZ_SECONDS:-30}" "$top/tools/fuzz.sh" "$top/_build_asan"
  rc=$?
  set -e
  if [ $rc -eq 77 ]; then summary="$summary fuzz: skipped (no clang with libFuzzer);"
  elif [ $rc -ne 0 ]; then summary="$summary fuzz: FAILED;"; status=1
  else summary="$summary fuzz: ${FUZZ_SECONDS:-30} s per harness, no crash;"; fi
fi
echo "sanitizers:$summary"
exit $status
