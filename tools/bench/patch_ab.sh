#!/usr/bin/env bash
# This tree against the same tree without a change, on a machine that has
# no git history (the lent GPU host receives a copy of the working tree):
# build the tree with PATCH reversed in a scratch folder beside the
# current build, then run a benchmark command with each build in turn,
# new first and last, old in between (new, old, new, old, ..., new), so
# that a machine's drift shows in both.  The command reads BOLIDE_BUILD
# (and BOLIDE_SRCDIR, which an uninstalled build needs to find its data
# files) from the environment, as every tools/bench script does.
#
# Usage: tools/bench/patch_ab.sh [-r ROUNDS] [-c "CONFIGURE OPTIONS"] PATCH -- COMMAND...
#   PATCH     the change, made here with e.g. `git diff OLD NEW -- src tests > x.patch`
#   -r        rounds of old + new after the first new run (default 1)
#   -c        configure options of the old build (default --with-cuda where nvcc is
#             on PATH, else --without-cuda)
# Env: BOLIDE_BUILD (the new build; default _dbuild if present, else _build),
#      PATCH_AB_DIR (scratch folder of the old tree; default /tmp/patch_ab; a
#      later call with the same patch and options reuses the old build there).
# Example (in a tools/bench/device.sh cmd: step, after the build step):
#   tools/bench/patch_ab.sh .bund/old.patch -- tools/bench/gpu.sh -p gravity -n 1.1e6 -m gpu -r 3 -s 30
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
rounds=1
conf=""
while getopts "r:c:" o; do
  case $o in r) rounds=$OPTARG ;; c) conf=$OPTARG ;; *) exit 2 ;; esac
done
shift $((OPTIND - 1))
[ $# -ge 3 ] && [ "$2" = "--" ] || { echo "usage: patch_ab.sh [-r ROUNDS] [-c OPTIONS] PATCH -- COMMAND..." >&2; exit 2; }
patch=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
shift 2
[ -r "$patch" ] || { echo "patch_ab.sh: error: $patch: cannot read the patch" >&2; exit 1; }
new=${BOLIDE_BUILD:-}
if [ -z "$new" ]; then new=$top/_build; [ -x "$top/_dbuild/bolide" ] && new=$top/_dbuild; fi
[ -x "$new/bolide" ] || { echo "patch_ab.sh: error: $new/bolide: no such build (set BOLIDE_BUILD)" >&2; exit 1; }
if [ -z "$conf" ]; then conf=--without-cuda; command -v nvcc >/dev/null && conf=--with-cuda; fi
old=${PATCH_AB_DIR:-/tmp/patch_ab}
if [ -x "$old/_b/bolide" ] && cmp -s "$patch" "$old/.ab.patch" && [ "$(cat "$old/.ab.conf")" = "$conf" ]; then
  # the same change built there by an earlier call (a warm host): kept
  echo "# old tree: $old ($patch reversed, built by an earlier call), configure $conf; new build: $new"
else
  rm -rf "$old" && mkdir -p "$old"
  # the tracked and untracked files of the tree, without build folders or carried kits
  (cd "$top" && tar --exclude='./_*build*' --exclude=./.devkit --exclude=./.bund --exclude=./.git -cf - .) |
    tar -xf - -C "$old"
  (cd "$old" && patch -R -p1 -s <"$patch") || { echo "patch_ab.sh: error: $patch does not reverse on this tree" >&2; exit 1; }
  echo "# old tree: $old ($patch reversed), configure $conf; new build: $new"
  (cd "$old" && { [ -x configure ] || ./autogen.sh >autogen.out 2>&1; } && mkdir -p _b && cd _b &&
    ../configure $conf ${PYTHON:+--with-python="$PYTHON"} >configure.out 2>&1 &&
    make -j"$(nproc)" bolide >make.out 2>&1) || { tail -20 "$old/_b/make.out" "$old/_b/configure.out" 2>/dev/null; exit 1; }
  cp "$patch" "$old/.ab.patch" && printf '%s' "$conf" >"$old/.ab.conf"
fi
run() { # label build srcdir
  local label=$1 build=$2 src=$3
  echo "### $label ($(date -u +%T))"
  BOLIDE_BUILD=$build BOLIDE_SRCDIR=$src "${cmd[@]}"
}
cmd=("$@")
run new "$new" "$top"
for r in $(seq "$rounds"); do
  run "old $r" "$old/_b" "$old"
  run "new $r" "$new" "$top"
done
