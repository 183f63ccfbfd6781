#!/usr/bin/env bash
# No file of the repository cites a document that the repository does not
# hold (theory/architecture.md, rule 12).  The project's design, style and
# validation notes once lived beside the checkout, where users never see
# them; their content is now theory/architecture.md and theory/validation.md,
# and a comment, README or script must point there (or to a published
# source), never to the old names or to a folder outside the checkout.
#
# Reads the files git tracks (git ls-files) or, outside a git checkout (a
# release tarball), every file under the source tree but build folders.
# Fails with one line per hit.
set -u
S=${BOLIDE_SRCDIR:-$(cd "$(dirname "$0")/../.." && pwd)}
cd "$S" || exit 1
# the names are built from pieces so that this file does not match itself
names="VALIDATION|DESIGN|STYLE"
pattern="(^|[^A-Za-z_/.])($names)\\.md|\\.\\./shared([/ ]|\$)|(^|[^A-Za-z_])shared/(bench|VALIDATION|DESIGN|STYLE|hooks|tools)"
if git -C "$S" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  list() { git -C "$S" ls-files -z; }
else
  list() { find . -path './_build*' -prune -o -path './autom4te.cache' -prune -o -type f -print0 | sed -z 's#^\./##'; }
fi
hits=$(list | grep -zv '^tests/repo/test_no_external_refs\.sh$' \
  | xargs -0 grep -I -n -E "$pattern" -- 2>/dev/null)
if [ -n "$hits" ]; then
  printf '%s\n' "$hits" | sed 's/^/FAIL: /'
  echo "FAIL: $(printf '%s\n' "$hits" | wc -l) line(s) cite a document outside the repository:"
  echo "      point them at theory/architecture.md or theory/validation.md"
  exit 1
fi
echo "PASS: no tracked file cites a document outside the repository"
