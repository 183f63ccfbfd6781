#!/usr/bin/env bash
# Pressure and sound speed against density, one curve per energy, from the
# tables run.sh wrote (tools/plot_eos.py).
# Usage: plot.sh [MATERIAL...]   (default: granite basalt; run.sh first)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${BOLIDE_BUILD:-$here/../../_build}"
python="${PYTHON:-$build/.venv/bin/python}"
[ $# -gt 0 ] || set -- granite basalt
for m in "$@"; do
  "$python" "$here/../../tools/plot_eos.py" "$here/tillotson_$m.txt" "$here/tillotson_$m.png" "Tillotson $m"
  echo "wrote $here/tillotson_$m.png"
done
