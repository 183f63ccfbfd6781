#!/usr/bin/env bash
# Build Bolide in ./_build and run the whole test suite (make check).
# Usage: tools/test.sh [extra configure options]
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
jobs="$(nproc 2>/dev/null || echo 2)"
cd "$top"
[ -x configure ] && [ configure -nt configure.ac ] || ./autogen.sh >/dev/null
mkdir -p _build
cd _build
if [ ! -f Makefile ] || [ "$#" -gt 0 ] || [ config.status -ot ../configure ]; then
  ../configure "$@" >configure.out || { tail -30 configure.out; exit 1; }
  sed -n '/Bolide .* configuration/,/^---*$/p' configure.out
fi
make -j"$jobs" >make.out 2>&1 || { tail -40 make.out; exit 1; }
if grep -q 'warning:' make.out; then grep 'warning:' make.out; echo "test.sh: the build has warnings" >&2; exit 1; fi
make venv >venv.out 2>&1 || { tail -20 venv.out; exit 1; }
set +e
make -j"$jobs" check-summary >check.out 2>&1
rc=$?
set -e
grep -E '^(PASS|FAIL|SKIP|XFAIL|XPASS|ERROR|tests:)|^# ' check.out || tail -40 check.out
if [ "$rc" -ne 0 ]; then
  for f in $(grep -l -E '^:test-result: (FAIL|ERROR)' $(find . -name '*.trs') 2>/dev/null); do
    echo "----- ${f%.trs}.log"; tail -30 "${f%.trs}.log"
  done
fi
exit "$rc"
