#!/usr/bin/env bash
# The README's first command: install what is missing, build Bolide, run a
# small impact of two granite spheres end to end (examples/DemoImpact, about
# 18,000 particles, under a minute on 2 cores) and draw it in demo/demo.png.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
"$top/tools/setup.sh"
rm -rf "$top/demo" && cp -r "$top/examples/DemoImpact" "$top/demo"
cd "$top/demo"
BOLIDE_BUILD="$top/_build" PYTHON="$top/_build/.venv/bin/python" TOP="$top" ./run.sh
cp demo_0004.png demo.png
echo "demo: picture of the collision in $top/demo/demo.png (t = 0: demo_0000.png)"
