#!/usr/bin/env bash
# The scripts of tools/ and examples/ read Bolide's outputs through the
# bolide Python package (python/bolide; issue 23 item 5: "the tools in
# tools/ call it instead of duplicating it"):
#   1. no snapshot opened for reading with h5py (bolide.snapshot.load, with
#      si=True for SI whatever the run's units, or bolide.load_snapshot);
#      writing initial conditions (modes w, r+, a) is theirs;
#   2. no parser of '#'-headed tables of their own (bolide.snapshot.read_stats
#      for statistics files, read_fragments for bolide-fof tables);
#   3. tools/plot_{impact,fragments,profile,tasks}.py run the package's
#      main and hold no code of their own (a few lines).
# Reads the files git tracks (or every file outside a git checkout).
set -u
S=${BOLIDE_SRCDIR:-$(cd "$(dirname "$0")/../.." && pwd)}
cd "$S" || exit 1
if git -C "$S" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  files=$(git -C "$S" ls-files 'tools/*.py' 'examples/*.py')
else
  files=$(find tools examples -name '*.py' | sort)
fi
fail=0
n=0
for f in $files; do
  n=$((n + 1))
  while IFS= read -r hit; do
    [ -n "$hit" ] || continue
    echo "FAIL: $f:$hit: reads an HDF5 file with h5py (use bolide.snapshot.load)"
    fail=1
  done < <(grep -n -E 'h5py\.File\(' "$f" | grep -v -E "h5py\.File\([^)]*,[[:space:]]*(mode=)?[\"'](w|w-|x|a|r\+)[\"']")
  while IFS= read -r hit; do
    [ -n "$hit" ] || continue
    echo "FAIL: $f:$hit: parses a '#'-headed table itself (use bolide.snapshot.read_stats or read_fragments)"
    fail=1
  done < <(grep -n -E "lstrip\([\"']#[\"']\)|startswith\([\"']# (rank|step|time|total mass)" "$f")
done
for p in impact fragments profile tasks; do
  f=tools/plot_$p.py
  [ -f "$f" ] || { echo "FAIL: $f missing"; fail=1; continue; }
  grep -q -E "^[[:space:]]*from bolide\.plot_$p import main" "$f" || { echo "FAIL: $f does not run bolide.plot_$p's main"; fail=1; }
  # statements outside the docstring (python3 of PATH: only its ast module)
  code=$(python3 -c '
import ast, sys
body = ast.parse(open(sys.argv[1]).read()).body
if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
    body = body[1:]
print(sum(isinstance(n, ast.stmt) for b in body for n in ast.walk(b)))' "$f")
  [ "$code" -le 8 ] || { echo "FAIL: $f has $code statements (a wrapper of bolide.plot_$p has no code of its own)"; fail=1; }
done
[ "$n" -gt 10 ] || { echo "FAIL: only $n scripts found under tools/ and examples/"; fail=1; }
[ $fail -eq 0 ] && echo "ok: $n scripts of tools/ and examples/ read outputs through the bolide package"
exit $fail
