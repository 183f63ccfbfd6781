#!/usr/bin/env bash
# Resolution series of the Sod shock tube: L1 errors of density, velocity
# and pressure against the exact solution at t = 0.2 (tools/plot_sod.py) on
# the lattice initial conditions of `bolide-ic sod` and on glass-like ones
# (tools/sod_glass.py: the same tube with each half made of a tiled,
# relaxed periodic glass cube), for NX = 32 64 128 particles along x per unit
# length of the dense gas, and the rate per doubling of NX,
#     rate = ln(L1(NX_prev) / L1(NX)) / ln(NX / NX_prev)
# (1 for first-order convergence).  The run uses params.yml of this folder,
# i.e. Bolide's defaults for the SPH scheme.  The transverse size is 0.25
# (0.5 at NX = 32, where 0.25 is narrower than two kernel supports).
#
# Usage: ./convergence.sh [-n "32 64 128"] [-i "lattice glass"] [-t THREADS]
#                         [-P SECTION:KEY:VALUE]... [-w WORKDIR] [-q]
# -q: no plots (numbers only).
# Environment: BOLIDE_BUILD (default ../../_build), PYTHON (default its venv).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/../.." && pwd)
build=${BOLIDE_BUILD:-$top/_build}
python=${PYTHON:-$build/.venv/bin/python}
sizes="32 64 128"; ics="lattice glass"; threads=2; work=""; over=(); plot=""
while getopts "n:i:t:P:w:q" o; do
  case $o in
    n) sizes=$OPTARG ;;
    i) ics=$OPTARG ;;
    t) threads=$OPTARG ;;
    P) over+=(-P "$OPTARG") ;;
    w) work=$OPTARG ;;
    q) plot=--no-plot ;;
    *) sed -n '2,18p' "$0"; exit 1 ;;
  esac
done
[ -n "$work" ] || work=$here/convergence
mkdir -p "$work"
printf '%-8s %5s %8s %9s %9s %9s %6s %6s %6s %7s %7s %8s %6s\n' ic NX N "L1(rho)" "L1(v)" "L1(P)" \
  "r_rho" "r_v" "r_P" "rho*_L" "P*_L" "dP_c/P" "wall_s"
for ic in $ics; do
  prev=""
  for nx in $sizes; do
    d=$work/$ic-$nx
    mkdir -p "$d"
    ly=0.25; [ "$nx" -ge 64 ] || ly=0.5
    (
      cd "$d"
      "$build/bolide-ic" sod --nx "$nx" --size 2,$ly,$ly -o lattice.hdf5 >ic.log
      if [ "$ic" = glass ]; then
        "$python" "$top/tools/sod_glass.py" lattice.hdf5 sod.hdf5 --cache "${GLASS_CACHE:-$work/glass}" >>ic.log
      else
        mv lattice.hdf5 sod.hdf5
      fi
      cp "$here/params.yml" .
      s=$(date +%s.%N)
      "$build/bolide" -t "$threads" ${over[@]+"${over[@]}"} params.yml >run.log 2>&1 ||
        { tail -5 run.log >&2; exit 1; }
      e=$(date +%s.%N)
      "$python" "$top/tools/plot_sod.py" sod_0002.hdf5 ${plot:---out sod.png} >l1.txt
      awk -v s="$s" -v e="$e" 'BEGIN{printf "wall %.1f\n", e - s}' >>l1.txt
    )
    n=$(awk '/read [0-9]+ particles/ {for (i = 1; i <= NF; i++) if ($i == "read") print $(i + 1)}' \
      "$d/run.log" | head -1)
    row=$(awk -v prev="$prev" -v nx="$nx" '
      $1 == "L1" { l1[$2] = $3 } $1 == "star" { st[$2] = $3 } $1 == "wall" { w = $2 }
      END {
        split(prev, p, " ")
        q[1] = "density"; q[2] = "velocity"; q[3] = "pressure"
        for (k = 1; k <= 3; k++)
          r[k] = (prev == "") ? "-" : sprintf("%.2f", log(p[k + 1] / l1[q[k]]) / log(nx / p[1]))
        printf "%9.5f %9.5f %9.5f %6s %6s %6s %7.4f %7.4f %+8.4f %6.1f|%s %s %s %s\n",
          l1["density"], l1["velocity"], l1["pressure"], r[1], r[2], r[3],
          st["left_density"], st["left_pressure"],
          st["right_pressure"] / st["left_pressure"] - 1, w,
          nx, l1["density"], l1["velocity"], l1["pressure"]
      }' "$d/l1.txt")
    printf '%-8s %5s %8s %s\n' "$ic" "$nx" "$n" "${row%%|*}"
    prev=${row#*|}
  done
done
echo "exact star state: rho*_L 0.4797, P* 0.2939 (dP_c/P: right over left star pressure - 1)"
