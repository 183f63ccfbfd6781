#!/usr/bin/env bash
# Build the libFuzzer harnesses of tests/fuzz with clang (AddressSanitizer +
# UndefinedBehaviorSanitizer) and run each for FUZZ_SECONDS seconds.
#   tools/fuzz.sh [BUILDDIR [HARNESS...]]     (what `make fuzz` runs)
# BUILDDIR: a configured build folder (its config.h is used; default _build);
# HARNESS: params, ic, restart (default: all three).  The seeds are the
# parameter files of tests/data and examples, and the corpus files
# tests/data/fuzz/HARNESS-*; the growing corpus is kept in
# BUILDDIR/fuzz/corpus-HARNESS.  A crash, a leak-free hang (-timeout) or a
# sanitizer report stops the run with status 1 and leaves the input as
# BUILDDIR/fuzz/crash-HARNESS-*: copy it to tests/data/fuzz/HARNESS-NAME and
# it becomes a regression input that tests/program/test_fuzz_corpus.sh replays.
# Exit 77 (skip) when clang or its libFuzzer is missing.
# Environment: FUZZ_SECONDS (default 60; 0: build only), FUZZ_TIMEOUT (seconds
# for one input before it counts as a hang; default 60: a loaded machine
# made a 0.8 s input take over 10 s), FUZZ_JOBS (parallel jobs per
# harness, default 1), CLANG (default clang).
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:-$top/_build}" && pwd)"
shift || true
harnesses="${*:-params ic restart}"
secs="${FUZZ_SECONDS:-60}"
CLANG="${CLANG:-clang}"
command -v "$CLANG" >/dev/null || { echo "fuzz: no $CLANG: skip"; exit 77; }
[ -f "$build/config.h" ] || { echo "fuzz: $build is not a configured build folder" >&2; exit 1; }
out="$build/fuzz"
mkdir -p "$out"
echo 'int LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n) { return 0; }' >"$out/probe.c"
"$CLANG" -fsanitize=fuzzer "$out/probe.c" -o "$out/probe" 2>/dev/null ||
  { echo "fuzz: $CLANG has no libFuzzer (-fsanitize=fuzzer): skip"; exit 77; }

hdf5_cflags="$(pkg-config --cflags hdf5 2>/dev/null || echo -I/usr/include/hdf5/serial)"
hdf5_libs="$(pkg-config --libs hdf5 2>/dev/null || echo -L/usr/lib/x86_64-linux-gnu/hdf5/serial -lhdf5)"
srcs="src/error.c src/paths.c src/part.c src/io/params.c src/io/units.c src/io/ic.c src/io/restart.c src/io/ragged_io.c
      tasks/damage/flaws.c src/materials/material.c src/materials/material_params.c
      src/materials/porosity.c"
flags="-fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -g -O1 -std=gnu11
       -DHAVE_CONFIG_H -DBOLIDE_SRCDIR=\"$top\" -I$build -I$top $hdf5_cflags"
for h in $harnesses; do
  bin="$out/fuzz_$h"
  if [ ! -x "$bin" ] || [ -n "$(cd "$top" && find $srcs tests/fuzz -newer "$bin" | head -1)" ]; then
    echo "fuzz: building $bin"
    (cd "$top" && "$CLANG" $flags $srcs "tests/fuzz/fuzz_$h.c" -o "$bin" $hdf5_libs -lyaml -lm -pthread)
  fi
done

[ "$secs" = 0 ] && { echo "fuzz: built (FUZZ_SECONDS=0: not run)"; exit 0; }
rc=0
for h in $harnesses; do
  corpus="$out/corpus-$h"
  seeds="$out/seeds-$h"
  rm -rf "$seeds"; mkdir -p "$corpus" "$seeds"
  cp "$top"/tests/data/fuzz/"$h"-* "$seeds"/ 2>/dev/null || true
  if [ "$h" = params ]; then
    for f in "$top"/tests/data/*.yml "$top"/examples/*/params.yml; do cp "$f" "$seeds/$(basename "$(dirname "$f")")-$(basename "$f")"; done
  fi
  # inputs up to 64 KiB; the restart harness 256 KiB, so that its far-field
  # seed (tests/data/fuzz/restart-farfield.bin, 228 KiB) is not cut
  maxlen=65536
  [ "$h" = restart ] && maxlen=262144
  echo "fuzz: $h for $secs s (corpus $corpus)"
  set +e
  (cd "$out" && ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=1 \
    "./fuzz_$h" -max_total_time="$secs" -timeout="${FUZZ_TIMEOUT:-60}" -rss_limit_mb=2048 -max_len="$maxlen" \
      -close_fd_mask=3 -fork="${FUZZ_JOBS:-1}" -ignore_crashes=0 -ignore_ooms=0 -ignore_timeouts=0 -artifact_prefix="$out/crash-$h-" \
      -print_final_stats=1 "$corpus" "$seeds" >"$out/fuzz-$h.log" 2>&1)
  r=$?
  set -e
  grep -E 'stat::number_of_executed_units|INFO: fuzzed for|#[0-9]+: cov' "$out/fuzz-$h.log" | tail -2 || true
  if [ $r -ne 0 ]; then
    echo "fuzz: $h FAILED (exit $r): see $out/fuzz-$h.log"; ls "$out"/crash-"$h"-* 2>/dev/null; rc=1
  else
    echo "fuzz: $h: no crash in $secs s ($(ls "$corpus" | wc -l) corpus inputs)"
  fi
done
exit $rc
