#!/usr/bin/env bash
# Every folder of examples/ (but common/, the shared helpers) holds README.md,
# params.yml, a run.sh that takes the build folder from BOLIDE_BUILD, and a
# plot script (plot.sh, plot*.py, or a Python script of the folder that
# saves a figure); and no file under an example's results/ or run_*/ is
# committed (what a run writes stays out of git; examples/README.md).
# Reads the tracked files (git ls-files) in a git checkout, the tree otherwise.
set -u
S=${BOLIDE_SRCDIR:-$(cd "$(dirname "$0")/../.." && pwd)}
cd "$S/examples" || exit 1
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
n=0
for d in */; do
  d=${d%/}
  [ "$d" = common ] && continue
  n=$((n + 1))
  for f in README.md params.yml run.sh; do
    [ -f "$d/$f" ] || fail "examples/$d has no $f"
  done
  [ -f "$d/run.sh" ] && ! grep -q 'BOLIDE_BUILD\b' "$d/run.sh" && fail "examples/$d/run.sh does not read BOLIDE_BUILD"
  plot=$(ls "$d"/plot*.sh "$d"/plot*.py 2>/dev/null; grep -l 'savefig' "$d"/*.py 2>/dev/null)
  [ -n "$plot" ] || fail "examples/$d has no plot script (plot.sh, plot_*.py or a script that saves a figure)"
done
if git -C "$S" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  committed=$(git -C "$S" ls-files -- 'examples/*/results/*' 'examples/*/run_*/*')
  [ -z "$committed" ] || fail "results of runs are committed: $(echo $committed)"
fi
[ $fails = 0 ] || exit 1
echo "PASS: $n example folders with README.md, params.yml, run.sh (BOLIDE_BUILD) and a plot script; no run output committed"
