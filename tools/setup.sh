#!/usr/bin/env bash
# Install the Debian packages Bolide needs (if missing), then build it in
# ./_build with its Python virtual environment.  Used by tools/demo.sh,
# tools/test.sh and .ci/run.  (clang and its libFuzzer runtime are for the
# fuzzing harnesses: make fuzz, tools/test_sanitizers.sh; METIS for the domain
# decomposition, bolide --partition.  The MPI build is tools/test_mpi_build.sh.)
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
cd "$top"
need=""
for pkg in build-essential autoconf automake libtool pkg-config libhdf5-dev libyaml-dev \
           libhwloc-dev python3 python3-venv python3-dev clang libclang-rt-14-dev help2man libconfig-dev \
           libmetis-dev; do
  dpkg -s "$pkg" >/dev/null 2>&1 || need="$need $pkg"
done
if [ -n "$need" ]; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  echo "setup: installing$need"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $need >/dev/null
fi
jobs="$(nproc 2>/dev/null || echo 2)"
if [ ! -x configure ] || [ configure.ac -nt configure ] || [ Makefile.am -nt configure ]; then
  ./autogen.sh >/dev/null 2>&1 || { ./autogen.sh; exit 1; }
fi
mkdir -p _build
cd _build
if [ ! -f Makefile ] || [ "$#" -gt 0 ] || [ config.status -ot ../configure ]; then
  ../configure "$@" >configure.out 2>&1 || { tail -30 configure.out; exit 1; }
  sed -n '/Bolide .* configuration/,/^---*$/p' configure.out
fi
make -j"$jobs" >make.out 2>&1 || { tail -40 make.out; exit 1; }
if grep -q 'warning:' make.out; then grep 'warning:' make.out; echo "setup: the build has warnings" >&2; exit 1; fi
echo "setup: built $(ls bolide bolide-ic bolide-eos 2>/dev/null | tr '\n' ' ')in $top/_build"
make venv >venv.out 2>&1 || { tail -20 venv.out; exit 1; }
