#!/usr/bin/env bash
# DemoImpact: a slice through the first and the last snapshot
# (tools/plot_snapshot.py).
# Usage: ./plot.sh [SNAPSHOT...]   (default demo_0000 and demo_0004; run.sh first)
set -euo pipefail
cd "$(dirname "$0")"
top=${TOP:-../..}
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
[ $# -gt 0 ] || set -- demo_0000.hdf5 demo_0004.hdf5
for f in "$@"; do
  s=${f%.hdf5}
  "$python" $top/tools/plot_snapshot.py "$s.hdf5" --slice 200 --out "$s.png"
  echo "picture: $(pwd)/$s.png"
done
