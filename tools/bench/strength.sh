#!/usr/bin/env bash
# Solid-body reference problem (theory/validation.md, "Benchmarks", on the CPU):
# the Nakamura basalt sphere (6 cm basalt, Tillotson + strength + Grady-Kipp
# damage with Weibull flaws m 8, k 5e34 m^-3; 0.2 g lucite bullet at
# 3.2 km/s, 30 degrees) built by examples/NakamuraBasalt's set-up with
# bolide-ic, every particle active: seconds per step (median of REPEAT runs
# of STEPS steps, the initial force computation excluded), particle updates
# per second per core, and peak resident memory per particle (flaws
# included).  SWIFT's strength branch: 3.30 / 1.71 s per step at 1 / 2
# threads and 680 MiB for 113,198 particles (theory/validation.md, "Benchmarks");
# compare as ratios measured on the same machine.
#
# Usage: tools/bench/strength.sh [-n "113000"] [-t "1 2"] [-r 3] [-s 3] [-P KEY:VALUE]...
#   -n  target particles (the bullet adds 0.149%)
#   -P  extra bolide -P overrides (repeatable)
# Environment: BOLIDE_BUILD (default _build), PYTHON (default the build's venv).
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
build=$(cd "${BOLIDE_BUILD:-$top/_build}" && pwd)
python=${PYTHON:-$build/.venv/bin/python}
sizes="113000"; threads="1 $(nproc)"; repeat=3; steps=3; extra=()
while getopts "n:t:r:s:P:" o; do
  case $o in n) sizes=$OPTARG ;; t) threads=$OPTARG ;; r) repeat=$OPTARG ;; s) steps=$OPTARG ;;
             P) extra+=(-P "$OPTARG") ;;
             *) echo "usage: $0 [-n SIZES] [-t THREADS] [-r REPEAT] [-s STEPS] [-P KEY:VALUE]" >&2; exit 2 ;; esac
done
[ -x /usr/bin/time ] || { echo "strength.sh: error: /usr/bin/time not found (apt-get install time)" >&2; exit 1; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
printf "# %s on %s (%s)\n" "$("$build/bolide" --version | head -1)" "$(uname -n)" \
  "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
printf "# NakamuraBasalt set-up, median of %d runs of %d steps, every particle active %s\n" \
  "$repeat" "$steps" "${extra[*]:-}"
printf "%-10s %8s %12s %16s %12s %10s\n" N threads s/step updates/s/core peak_MiB B/particle
for n in $sizes; do
  ni=$(( (n * 149 + 50000) / 100000 )); [ "$ni" -ge 8 ] || ni=8
  "$build/bolide-ic" impact \
    --target "sphere,material=basalt,radius=0.03,n=$n" \
    --impactor "sphere,material=lucite,mass=2e-4,n=$ni" \
    --v-contact 3200 --angle 30 --time 1e-6 -o nakamura_ic.hdf5 >/dev/null
  N=$("$python" -c "import h5py; print(len(h5py.File('nakamura_ic.hdf5', 'r')['PartType0/Masses']))")
  sed -e 's/^  delta_time: 1.0e-5.*/  delta_time: 1.0e30/' "$top/examples/NakamuraBasalt/params.yml" >p.yml
  for t in $threads; do
    rm -f times.txt
    for r in $(seq "$repeat"); do
      /usr/bin/time -f "%M" -o rss.txt "$build/bolide" -n "$steps" -t "$t" "${extra[@]}" \
        -P Snapshots:subdir:out p.yml >run.log 2>&1 || { tail -3 run.log >&2; exit 1; }
      s=$(awk '$1 ~ /^[0-9]+$/ && NF == 6 {s += $5; n++} END {if (n) printf "%.6f\n", s / n}' run.log)
      [ -n "$s" ] || { echo "strength.sh: error: no step lines in the bolide log" >&2; tail -5 run.log >&2; exit 1; }
      echo "$s $(tail -1 rss.txt)" >>times.txt
    done
    read -r s kib < <(sort -g times.txt | awk '{a[NR] = $0} END {print a[int((NR + 1) / 2)]}')
    printf "%-10d %8d %12.4f %16.3e %12.1f %10.0f\n" "$N" "$t" "$s" \
      "$(awk -v n="$N" -v s="$s" -v t="$t" 'BEGIN {print n / s / t}')" \
      "$(awk -v k="$kib" 'BEGIN {print k / 1024}')" "$(awk -v k="$kib" -v n="$N" 'BEGIN {print k * 1024 / n}')"
  done
done
