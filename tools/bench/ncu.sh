#!/usr/bin/env bash
# A benchmark command with bolide under Nsight Compute (ncu): the hardware
# counters of the GPU kernels whose names match REGEX, COUNT launches
# after the first SKIP, with the sections that say what bounds a kernel
# (speed of light, compute and memory workload, occupancy, scheduler and
# warp state statistics, launch and instruction statistics).  The command
# (a tools/bench script that runs "$BOLIDE_BUILD/bolide") is given a
# folder whose bolide is ncu around the real one; ncu's report of every
# bolide process (also of --version and --check, which launch nothing)
# is printed at the end.  Clocks are left alone (--clock-control none, as
# the GPU host asks); ncu flushes the caches between its passes, so a
# kernel takes longer than in a plain run.
#
# Usage: tools/bench/ncu.sh [-k REGEX] [-c COUNT] [-s SKIP] -- COMMAND...
#   -k  kernels (default: the hydro leaf kernels, density|gradient|force)
#   -c  launches profiled (default 3), -s launches skipped first (default 0)
# Env: BOLIDE_BUILD (the build to profile; default _dbuild if present, else _build).
# Example (in a tools/bench/device.sh cmd: step):
#   tools/bench/ncu.sh -k force_gpu_kernel -c 1 -- tools/bench/gpu.sh -p basalt -n 1e5 -m gpu -r 1 -s 1
set -euo pipefail
top="$(cd "$(dirname "$0")/../.." && pwd)"
regex="density_gpu_kernel|gradient_gpu_kernel|force_gpu_kernel|force_fluid_gpu_kernel"
count=3
skip=0
while getopts "k:c:s:" o; do
  case $o in k) regex=$OPTARG ;; c) count=$OPTARG ;; s) skip=$OPTARG ;; *) exit 2 ;; esac
done
shift $((OPTIND - 1))
[ "${1:-}" = "--" ] && shift
[ $# -ge 1 ] || { echo "usage: tools/bench/ncu.sh [-k REGEX] [-c COUNT] [-s SKIP] -- COMMAND..." >&2; exit 2; }
command -v ncu >/dev/null || { echo "ncu.sh: error: ncu (Nsight Compute) is not on PATH" >&2; exit 1; }
build=${BOLIDE_BUILD:-}
if [ -z "$build" ]; then build=$top/_build; [ -x "$top/_dbuild/bolide" ] && build=$top/_dbuild; fi
build=$(cd "$build" && pwd)
[ -x "$build/bolide" ] || { echo "ncu.sh: error: $build/bolide: no such build (set BOLIDE_BUILD)" >&2; exit 1; }
wrap=$(mktemp -d)
trap 'rm -rf "$wrap"' EXIT
# everything of the build but bolide itself (its other programs, the .venv
# that tools/bench/impact.sh takes Python from)
for f in "$build"/* "$build"/.venv; do
  [ -e "$f" ] && [ "$(basename "$f")" != bolide ] && ln -s "$f" "$wrap/$(basename "$f")"
done
cat >"$wrap/bolide" <<WRAP
#!/usr/bin/env bash
exec ncu --clock-control none -k "regex:$regex" -s $skip -c $count \\
  --section SpeedOfLight --section ComputeWorkloadAnalysis --section MemoryWorkloadAnalysis \\
  --section Occupancy --section SchedulerStats --section WarpStateStats --section LaunchStats \\
  --section InstructionStats --print-details all --log-file "$wrap/ncu.\$\$.txt" "$build/bolide" "\$@"
WRAP
chmod +x "$wrap/bolide"
BOLIDE_BUILD=$wrap BOLIDE_SRCDIR=${BOLIDE_SRCDIR:-$top} "$@"
for f in "$wrap"/ncu.*.txt; do
  [ -f "$f" ] && grep -q "Section:" "$f" && cat "$f"
done
exit 0
