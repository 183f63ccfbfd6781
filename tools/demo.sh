#!/usr/bin/env bash
# The README's first command: install what is missing, build Bolide, run a
# small demonstration end to end and draw a picture of it in demo/.
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
"$top/tools/setup.sh"
build="$top/_build"
python="$build/.venv/bin/python"
rm -rf "$top/demo" && mkdir -p "$top/demo" && cd "$top/demo"
cp "$top/examples/SedovBlast3D/params.yml" .
"$build/bolide-ic" sedov --n 24 --energy 1 --rho 1 -o sedov.hdf5
"$build/bolide" params.yml
PYTHONPATH="$top/tools" "$python" "$top/tools/plot_sedov.py" sedov_0002.hdf5 --initial sedov.hdf5 --out demo.png
echo "demo: picture in $top/demo/demo.png"
