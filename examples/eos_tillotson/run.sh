#!/usr/bin/env bash
# Tillotson granite and basalt: P and c_s against density for energies in
# the cold, hybrid and expanded regions (theory/validation.md "Tillotson sound
# speed"), tabulated by bolide-eos on the grid of params.yml and drawn by
# plot.sh; the number behind the case -- the analytic c^2 against a
# numerical isentropic derivative, 1e-6 relative -- is asserted by
# tests/unit/test_eos (make check), whose -v output lists every state.
# Usage: run.sh [BUILD_DIR]   (default: $BOLIDE_BUILD, else ../../_build)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-${BOLIDE_BUILD:-${BOLIDE_BUILDDIR:-$here/../../_build}}}"
eos="$build/bolide-eos"
lib="$here/../materials.yml"
[ -x "$eos" ] || { echo "run.sh: error: $eos not found (build first, or give the build folder)" >&2; exit 1; }
export BOLIDE_BUILD="$build" PYTHON="${PYTHON:-$build/.venv/bin/python}"
# params.yml: "key: value" lines; materials is a list, every other key an option
materials=$(sed -n 's/^materials: *//p' "$here/params.yml")
opts=$(sed -n '/^materials:/d; s/^\([a-z-]*\): *\([^ #]*\).*/--\1 \2/p' "$here/params.yml")
for m in $materials; do
  # shellcheck disable=SC2086
  "$eos" "$lib" "$m" $opts >"$here/tillotson_$m.txt"
  echo "wrote $here/tillotson_$m.txt"
done
"$here/plot.sh" $materials
"$build/tests/unit/test_eos" -v | grep -E "Tillotson .* c2 analytic" >"$here/sound_speed_check.txt" || true
echo "analytic vs numerical c^2 (tests/unit/test_eos -v): $here/sound_speed_check.txt"
