#!/usr/bin/env bash
# The MPI build (issue 22): installs OpenMPI and the MPI flavour of HDF5 when
# missing (Debian libopenmpi-dev openmpi-bin libhdf5-openmpi-dev, beside the
# serial libhdf5-dev of the default build), builds ./_build_mpi with
# configure --with-mpi (CPU only) and runs the tests of the MPI layer there:
# test_mpi.sh (mpirun -n 1 bit for bit the default build's snapshot, more
# ranks stop with one line or report the partition), test_partition.sh and
# the unit test of the partition.  Uses ./_build (tools/setup.sh) for the
# virtual environment and as the serial reference.  Run by CI.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
[ -x "$top/_build/.venv/bin/python" ] && [ -x "$top/_build/bolide" ] || "$top/tools/setup.sh" >/dev/null
need=""
for pkg in libopenmpi-dev openmpi-bin libhdf5-openmpi-dev; do
  dpkg -s "$pkg" >/dev/null 2>&1 || need="$need $pkg"
done
if [ -n "$need" ]; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  echo "test_mpi_build: installing$need"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $need >/dev/null
fi
jobs="$(nproc 2>/dev/null || echo 2)"
mkdir -p "$top/_build_mpi" && cd "$top/_build_mpi"
[ -f Makefile ] || ../configure --with-mpi --without-cuda >configure.out 2>&1 ||
  { tail -20 configure.out; exit 1; }
make -j"$jobs" >make.out 2>&1 || { tail -30 make.out; exit 1; }
if grep -q 'warning:' make.out; then grep 'warning:' make.out; echo "MPI build: warnings" >&2; exit 1; fi
tests="tests/program/test_mpi.sh tests/program/test_partition.sh tests/program/test_partition_counts.sh tests/unit/test_partition"
BOLIDE_SERIAL_BUILDDIR="$top/_build" make -j"$jobs" check TESTS="$tests" \
  PYTHON="$top/_build/.venv/bin/python" >check.out 2>&1 || true
rc=0
for t in $tests; do
  grep -q '^:test-result: PASS' "${t%.sh}.trs" 2>/dev/null || { echo "MPI build: $t FAIL"; tail -20 "${t%.sh}.log"; rc=1; }
done
[ $rc -eq 0 ] && echo "MPI build: $tests PASS"
exit $rc
