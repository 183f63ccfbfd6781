#!/usr/bin/env bash
# Every input in tests/data/fuzz (the seeds and each crash the libFuzzer
# harnesses found, named HARNESS-WHAT) replayed through its harness built
# without libFuzzer (tests/fuzz_replay_HARNESS): each must be read or
# refused without a crash (under the sanitizer builds: without a report).
set -u
B=${BOLIDE_BUILDDIR:?}
S=${BOLIDE_SRCDIR:?}
# a refused input leaves what the reader had allocated (the harness jumps
# out of error_exit, see tests/fuzz/fuzz_common.h): no leak detection
export ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0"
fail=0 n=0
for h in params ic restart; do
  for f in "$S"/tests/data/fuzz/"$h"-*; do
    [ -e "$f" ] || continue
    n=$((n + 1))
    if timeout 20 "$B/tests/fuzz_replay_$h" "$f" >/dev/null 2>err.$$; then
      echo "ok   $h $(basename "$f")"
    else
      echo "FAIL $h $(basename "$f"):"; tail -20 err.$$; fail=1
    fi
  done
done
rm -f err.$$
echo "$n inputs replayed"
exit $fail
