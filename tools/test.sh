#!/usr/bin/env bash
# Build Bolide in ./_build (installing missing Debian packages first) and run
# the whole test suite (make check).  Closes with one line
# "tests: N passed, N failed, N skipped".
# Usage: tools/test.sh [extra configure options]
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
"$top/tools/setup.sh" "$@"
cd "$top/_build"
jobs="$(nproc 2>/dev/null || echo 2)"
set +e
make -j"$jobs" check-summary >check.out 2>&1
rc=$?
set -e
grep -E '^(PASS|FAIL|SKIP|XFAIL|XPASS|ERROR):' check.out || true
if [ "$rc" -ne 0 ]; then
  for f in $(grep -l -E '^:test-result: (FAIL|ERROR)' $(find . -name '*.trs') 2>/dev/null); do
    echo "----- ${f%.trs}.log"; tail -30 "${f%.trs}.log"
  done
  grep -E 'error' check.out | head -20 || true
fi
grep -E '^tests: ' check.out || echo "tests: 0 passed, 1 failed, 0 skipped"
exit "$rc"
