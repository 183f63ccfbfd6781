#!/usr/bin/env bash
# Is a run reproducible?  The same run twice (same binary, parameters,
# threads), then the largest difference of every particle field of the
# last snapshots, matched by particle id: 0 everywhere means bit for bit.
# The planetary reference impact (make_impact_ic.py) with self-gravity, a
# few Courant steps.
#
# Usage: tools/bench/repeat.sh [-n 1.1e5] [-s 10] [-g "BOLIDE ARGS"]
#   e.g. tools/bench/repeat.sh -g "--gpu -t 16"     (the GPU path)
#        tools/bench/repeat.sh -g "--no-gpu -t 2"   (the CPU path)
# Env: BOLIDE_BUILD (build folder, default _build), BOLIDE_BENCH_IC
# (make_impact_ic.py), PYTHON (with h5py and numpy).
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=$(cd "${BOLIDE_BUILD:-$top/_build}" && pwd)
python=${PYTHON:-$build/.venv/bin/python}
gen=${BOLIDE_BENCH_IC:?"set BOLIDE_BENCH_IC to the reference impact IC generator (make_impact_ic.py)"}
n=1.1e5; steps=10; args=""
while getopts "n:s:g:" o; do
  case $o in n) n=$OPTARG ;; s) steps=$OPTARG ;; g) args=$OPTARG ;; *) exit 2 ;; esac
done
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
nt=$(awk -v n=$n 'BEGIN {printf "%d", n * 10 / 11}'); ni=$(awk -v n=$n 'BEGIN {printf "%d", n / 11}')
"$python" "$gen" "$nt" "$ni" impact.hdf5 >/dev/null
for r in a b; do
  cat >p$r.yml <<YML
InitialConditions:
  file_name: impact.hdf5
TimeIntegration:
  time_end: 1e30
Snapshots:
  subdir: out$r
  delta_time: 1e30
Materials:
  101: {}
Gravity:
  enabled: true
  theta_cr: 0.5
Scheduler:
  max_top_level_cells: 16
YML
  # shellcheck disable=SC2086
  "$build/bolide" $args -n "$steps" p$r.yml >run$r.log 2>&1 || { tail -3 run$r.log >&2; exit 1; }
done
printf "# %s, %s steps of the reference impact with gravity at N = %s, bolide %s\n" \
  "$(git -C "$top" rev-parse --short HEAD)" "$steps" "$n" "$args"
grep -m1 -E "on the GPU|CPU-only|threads" runa.log || true
"$python" - <<'PY'
import glob, h5py, numpy as np
fa, fb = sorted(glob.glob("outa/snapshot_*.hdf5"))[-1], sorted(glob.glob("outb/snapshot_*.hdf5"))[-1]
a, b = h5py.File(fa, "r")["PartType0"], h5py.File(fb, "r")["PartType0"]
ia, ib = np.argsort(a["ParticleIDs"][:]), np.argsort(b["ParticleIDs"][:])
worst = 0.0
for k in sorted(a.keys()):
    x, y = a[k][:][ia], b[k][:][ib]
    if x.dtype.kind == "f":
        scale = np.max(np.abs(x)) or 1.0
        d = float(np.max(np.abs(x - y))) / scale
        worst = max(worst, d)
        print(f"  {k:20s} largest difference / largest value {d:.3e}")
    else:
        print(f"  {k:20s} {int((x != y).sum())} differ")
print("bit for bit" if worst == 0.0 else f"not bit for bit: worst {worst:.3e}")
PY
