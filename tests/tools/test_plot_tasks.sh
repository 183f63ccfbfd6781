#!/usr/bin/env bash
# The task timers and dump of a small run, drawn by tools/plot_tasks.py.
set -eu
"$PYTHON" -c 'import numpy, matplotlib' 2>/dev/null || { echo "no numpy/matplotlib: skip"; exit 77; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"$BOLIDE_BUILDDIR/tests/unit/test_scheduler" --dump "$tmp/tasks.txt" >"$tmp/timers.txt"
cat "$tmp/timers.txt"
# the timer table names the task kinds that ran
grep -q '^  self *density ' "$tmp/timers.txt"
grep -q '^  pair *force ' "$tmp/timers.txt"
"$PYTHON" "$BOLIDE_SRCDIR/tools/plot_tasks.py" --help >/dev/null
"$PYTHON" "$BOLIDE_SRCDIR/tools/plot_tasks.py" "$tmp/tasks.txt" -o "$tmp/tasks.png"
# a PNG file starts with \x89 P N G
[ "$(head -c 4 "$tmp/tasks.png" | od -An -tx1 | tr -d ' \n')" = "89504e47" ]
echo "PNG of $(stat -c %s "$tmp/tasks.png") bytes"
