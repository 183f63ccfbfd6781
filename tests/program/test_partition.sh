#!/usr/bin/env bash
# bolide --partition (issue 22 item 2) on a planetary impact: two granite
# spheres (20,000 + 2,000 particles) in a box 17 times the target's
# diameter, nearly all of it empty.  Costs estimated (deterministic).
#  - every method assigns every top-level cell (unassigned 0);
#  - with 64 top-level cells per side METIS balances 2, 4 and 8 ranks within
#    1.03, 1.03 and 1.05 (measured 1.0026, 1.0099, 1.0157: METIS's tolerance
#    is 1.01, the rest is the granularity of the cells, 66 of them
#    non-empty), as well as Morton ranges of equal cost (+0.01; Morton
#    measured 1.0095, 1.0788, 1.2105) and with no larger edge cut (+5%), each
#    rank's cells in at most 6 pieces (measured 1, 1, 2);
#  - slabs of equal width, the naive split, put the bodies on 2 of 8 slabs:
#    imbalance at least 1.9 at 4 ranks and 3.5 at 8 (measured 2.17, 4.34);
#  - with the default 16 cells per side the bodies lie in a few dozen cells,
#    and 8 ranks cannot balance (METIS 1.26): the reason for the finer grid
#    (theory/mpi.md).
# Skips (77) in a build without METIS.
set -u
B=${BOLIDE_BUILDDIR:?}
fail() { echo "FAIL: $*"; exit 1; }
"$B/bolide" --help | grep -q -- "--partition N" || fail "bolide --help does not document --partition"
. "$(cd "$(dirname "$0")/../helpers" && pwd)/small_impact.sh" # small_impact
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
small_impact
if ! "$B/bolide" --partition 2 --partition-method metis -t 1 p.yml >metis.log 2>&1; then
  grep -q "no METIS" metis.log && { echo "no METIS in this build: skip"; exit 77; }
  cat metis.log; fail "bolide --partition 2"
fi
# value KEY METHOD RANKS FILE: the number after KEY on the line of METHOD at RANKS
value() { awk -v k="$1" -v m="$2" -v r="$3" '$2 == "method" && $3 == m && $5 == r {
  for (i = 1; i < NF; i++) if ($i == k) print $(i + 1) }' "$4"; }
check() { awk -v a="$1" -v b="$3" "BEGIN { exit !(a $2 b) }" || fail "$4: $1 $2 $3 does not hold"; }
for top in 16 64; do
  for n in 2 4 8; do
    "$B/bolide" --partition $n --partition-method all -t 1 -P Scheduler:max_top_level_cells:$top \
      p.yml >part_${top}_$n.log 2>&1 || { tail -3 part_${top}_$n.log; fail "bolide --partition $n"; }
    grep "^partition: method" part_${top}_$n.log
    for m in metis morton slabs; do
      u=$(value unassigned $m $n part_${top}_$n.log)
      [ "$u" = 0 ] || fail "$m at $n ranks, $top cells per side: unassigned '$u'"
    done
  done
done
f=part_64
for n in 2 4 8; do
  bound=1.03; [ $n = 8 ] && bound=1.05
  mi=$(value imbalance metis $n ${f}_$n.log)
  check "$mi" "<=" $bound "METIS imbalance at $n ranks"
  check "$mi" "<=" "$(awk -v c="$(value imbalance morton $n ${f}_$n.log)" 'BEGIN {print c + 0.01}')" \
    "METIS against Morton at $n ranks"
  check "$(value edge_cut metis $n ${f}_$n.log)" "<=" \
    "$(awk -v c="$(value edge_cut morton $n ${f}_$n.log)" 'BEGIN {print 1.05 * c}')" "METIS edge cut at $n ranks"
  check "$(value max_pieces metis $n ${f}_$n.log)" "<=" 6 "METIS pieces at $n ranks"
done
check "$(value imbalance slabs 4 ${f}_4.log)" ">=" 1.9 "slabs at 4 ranks"
check "$(value imbalance slabs 8 ${f}_8.log)" ">=" 3.5 "slabs at 8 ranks"
check "$(value imbalance metis 8 part_16_8.log)" ">=" 1.2 "METIS at 8 ranks on the coarse grid"
# the per-rank table of one method: N lines
"$B/bolide" --partition 4 -t 1 -P Scheduler:max_top_level_cells:64 p.yml >table.log 2>&1 || fail "table"
[ "$(grep -c '^ *[0-9]' table.log)" = 4 ] || { cat table.log; fail "no table of 4 ranks"; }
# the measured costs after a step
"$B/bolide" --partition 2 -n 1 -t 1 p.yml >measured.log 2>&1 || { tail -3 measured.log; fail "-n 1"; }
grep -q "costs measured imbalance" measured.log || { cat measured.log; fail "no measured partition"; }
"$B/bolide" --partition 2 --partition-method nonsense p.yml >bad.log 2>&1 && fail "a bad method was accepted"
grep -q "^bolide: error: option --partition-method expects" bad.log || { cat bad.log; fail "bad method message"; }
echo "test_partition: PASS"
