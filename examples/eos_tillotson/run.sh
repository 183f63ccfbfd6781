#!/bin/bash
# Tillotson granite and basalt: P and c_s against density for energies in
# the cold, hybrid and expanded regions (theory/validation.md "Tillotson sound
# speed"), drawn with bolide-eos --plot; the number behind the case -- the
# analytic c^2 against a numerical isentropic derivative, 1e-6 relative --
# is asserted by tests/test_eos (make check), whose -v output lists every state.
# Usage: run.sh [BUILD_DIR]   (default: the current directory's build, ../../_build)
set -eu
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-${BOLIDE_BUILDDIR:-$here/../../_build}}"
eos="$build/bolide-eos"
lib="$here/../materials.yml"
[ -x "$eos" ] || { echo "run.sh: error: $eos not found (build first, or give the build folder)" >&2; exit 1; }
export PYTHON="${PYTHON:-$build/.venv/bin/python}"
for m in granite basalt; do
  # 8 energies from 0 to 26 MJ/kg: cold, hybrid (Eiv..Ecv) and expanded states
  "$eos" "$lib" "$m" --rho-min 300 --rho-max 6000 --nrho 200 --u-min 0 --u-max 2.6e7 --nu 8 \
    --plot "$here/tillotson_$m.png" >"$here/tillotson_$m.txt"
  echo "wrote $here/tillotson_$m.png and tillotson_$m.txt"
done
"$build/tests/test_eos" -v | grep -E "Tillotson .* c2 analytic" >"$here/sound_speed_check.txt" || true
echo "analytic vs numerical c^2 (tests/test_eos -v): $here/sound_speed_check.txt"
