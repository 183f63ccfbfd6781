#!/usr/bin/env bash
# Aluminium sphere on a plate (Hiermaier et al. 1997): initial conditions,
# run, hole diameter and debris-cloud length/width, picture plate.png.
# Usage: ./run.sh [DX] [THREADS]  (lattice spacing in m, default 0.0008:
# 5 layers through the plate, 52,069 particles, to 20 us: about 80 s on 2 cores)
# The smoothing length is capped at 2.5 DX (SPH:h_max): the debris shell's
# particles would otherwise grow h to 15 DX and reach thousands of plate
# particles; the cap changes none of the measured numbers (README.md).
# BOLIDE_ARGS (optional): more bolide options, e.g. BOLIDE_ARGS="-P Scheduler:gpu:all";
# PARAMS (optional): another parameter file, e.g. PARAMS=variants/spall.yml.
set -euo pipefail
cd "$(dirname "$0")"
top=../..
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
dx=${1:-0.0008}
threads=${2:-2}
h_max=$("$python" -c "print(2.5 * float('$dx'))")
"$python" make_ic.py --dx "$dx" -o plate.hdf5
# shellcheck disable=SC2086
"$build/bolide" -t "$threads" -P SPH:h_max:"$h_max" ${BOLIDE_ARGS:-} "${PARAMS:-params.yml}"
"$python" analyse.py --dx "$dx" --out plate.png output
