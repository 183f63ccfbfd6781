#!/usr/bin/env bash
# One call on the lent GPU host (16 cores, one H100/H200, CUDA, no network,
# no libyaml, no h5py): set up what it lacks from .devkit/ (carried: the
# Debian libyaml .debs, an h5py wheel for its Python, the reference impact's
# IC generator make_impact_ic.py), build with CUDA in _dbuild/
# (kept between calls while the host stays warm), then run the named steps,
# each logged to STEP.log; the logs come back as $OUT/device-logs.tgz
# (the host returns at most 8 files).
#
# Usage (from the repository root, on the device):
#   tools/bench/device.sh STEP...
# Steps:
#   build            configure --with-cuda and make (implied by the others)
#   native           a second build with --enable-native in _dbuild_native
#   check-gpu        make check-gpu (test_gpu, GPU runs against CPU runs)
#   check-gpu-native make check-gpu in the --enable-native build
#   energy           tools/bench/energy.sh: the reference impact's budget to
#                    t = 4000 s at 2.2e4 and 1.1e5 particles, CPU (16 threads)
#                    and GPU (ENERGY_SIZES, ENERGY_MODES, ENERGY_T override;
#                    modes cpu-bins, gpu-bins: individual time steps)
#   cmd:'COMMAND'    any command, run in the repository root with the build's
#                    environment (BOLIDE_BUILD, PYTHON, BOLIDE_BENCH_IC set)
# DEVICE_NOBUILD=1 skips the CUDA build (for commands that build their own,
# such as the sanitizer builds).  DEVICE_DEADLINE (seconds from the start,
# default 570, for the run tool's 600-s calls; lower it with a shorter
# timeout_s): a step still running then is killed with everything it
# started, the later steps are skipped, and the logs still come back (a
# call that runs out of time returns nothing else).  /tmp/kit/python runs the host's python3
# with the carried h5py on its path whatever PYTHONPATH a Makefile sets
# (SAN_PYTHON=/tmp/kit/python for tools/test_sanitizers.sh).
set -uo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$top"
out=/tmp/dout
mkdir -p "$out"
kit=$top/.devkit
jobs=$(nproc)
if [ ! -d /tmp/kit/usr ]; then
  for f in "$kit"/*.deb; do dpkg -x "$f" /tmp/kit; done
  python3 -m pip install -q --no-index --no-deps --no-compile --target /tmp/site "$kit"/*.whl
fi
export CPPFLAGS="-I/tmp/kit/usr/include" LDFLAGS="-L/tmp/kit/usr/lib/x86_64-linux-gnu"
export LD_LIBRARY_PATH="/tmp/kit/usr/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export PYTHONPATH="/tmp/site${PYTHONPATH:+:$PYTHONPATH}"
export PYTHON=$(command -v python3)
printf '#!/bin/sh\nPYTHONPATH=/tmp/site${PYTHONPATH:+:$PYTHONPATH} exec %s "$@"\n' "$PYTHON" >/tmp/kit/python
chmod +x /tmp/kit/python
export BOLIDE_BENCH_IC=${BOLIDE_BENCH_IC:-$kit/make_impact_ic.py}

build() { # dir, extra configure options
  local dir=$1; shift
  [ -x configure ] || ./autogen.sh >"$out/autogen.log" 2>&1 || { tail -20 "$out/autogen.log"; return 1; }
  mkdir -p "$dir" && cd "$dir" || return 1
  if [ ! -f Makefile ]; then
    ../configure --with-cuda --with-python="$PYTHON" "$@" >configure.out 2>&1 || { tail -20 configure.out; return 1; }
    sed -n '/Bolide .* configuration/,/^---*$/p' configure.out
  fi
  make -j"$jobs" >make.out 2>&1 || { tail -30 make.out; return 1; }
  make -j"$jobs" tests/gpu/test_gpu >>make.out 2>&1 || { tail -30 make.out; return 1; }
  cd "$top"
}

export BOLIDE_BUILD=$top/_dbuild

# one step (the loop below runs each so, under the call's deadline)
one_step() {
  local step=$1 rc=0
  case $step in
    build) ;;
    native) build _dbuild_native --enable-native 2>&1 | tee "$out/native.log" || rc=1 ;;
    check-gpu) (cd _dbuild && make check-gpu PYTHON="$PYTHON") 2>&1 | tee "$out/check-gpu.log" | tail -40; [ ${PIPESTATUS[0]} -eq 0 ] || rc=1 ;;
    check-gpu-native) (cd _dbuild_native && make check-gpu PYTHON="$PYTHON") 2>&1 | tee "$out/check-gpu-native.log" | tail -40
                      [ ${PIPESTATUS[0]} -eq 0 ] || rc=1 ;;
    energy) tools/bench/energy.sh -n "${ENERGY_SIZES:-2.2e4 1.1e5}" -m "${ENERGY_MODES:-gpu cpu}" -t "$jobs" \
              -T "${ENERGY_T:-4000}" -o "$out/energy" 2>&1 | tee "$out/energy.log" || rc=1 ;;
    cmd:*) bash -c "${step#cmd:}" 2>&1 | tee -a "$out/cmd.log" || rc=1 ;;
    *) echo "device.sh: error: unknown step '$step'"; rc=1 ;;
  esac
  return $rc
}
if [ "${1:-}" = "--one-step" ]; then one_step "$2"; exit $?; fi

t0=$SECONDS
deadline=${DEVICE_DEADLINE:-570}
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader | tee "$out/gpu.txt"
if [ -z "${DEVICE_NOBUILD:-}" ]; then
  build _dbuild 2>&1 | tee "$out/build.log"
  [ ${PIPESTATUS[0]} -eq 0 ] || { [ -n "${OUT:-}" ] && tar czf "$OUT/device-logs.tgz" -C "$out" .; exit 1; }
fi
rc=0
for step in "$@"; do
  left=$((deadline - (SECONDS - t0)))
  echo "=== $step ($(date -u +%H:%M:%S), ${left} s left of DEVICE_DEADLINE=$deadline)"
  if [ "$left" -le 5 ]; then
    echo "device.sh: error: step '$step' not run: the call's deadline has passed"; rc=1; continue
  fi
  # GNU timeout kills the step's whole process group (bolide runs, builds)
  timeout -s KILL "$left" "$top/tools/bench/$(basename "$0")" --one-step "$step"
  src=$?
  if [ $src -eq 137 ]; then
    echo "device.sh: error: step '$step' killed at the call's deadline (DEVICE_DEADLINE=$deadline s)" | tee -a "$out/deadline.log"
  fi
  [ $src -eq 0 ] || rc=1
done
[ -n "${OUT:-}" ] && tar czf "$OUT/device-logs.tgz" -C "$out" .
exit $rc
