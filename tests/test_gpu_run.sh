#!/usr/bin/env bash
# Sedov blast on the CPU (--no-gpu) and on the GPU (--gpu), 40 steps of
# 32,768 particles: the conservation budgets of the two statistics files
# (mass, momentum, angular momentum, kinetic, internal and total energy) must
# agree.  The runs differ only by the order of the SPH sums (round-off,
# ~1e-15 relative per step, amplified along the run), so every column must
# agree to 1e-8 relative to its scale (mass, E_tot, or sum m|v| for momenta).
# Part of `make check-gpu` (needs a GPU); exits 77 without one.
set -euo pipefail
B=${BOLIDE_BUILDDIR:?}; S=${BOLIDE_SRCDIR:?}
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$B/bolide-ic" sedov --n 32 --energy 1 --rho 1 -o sedov.hdf5 >/dev/null
for mode in cpu gpu; do
  mkdir $mode; cp "$S/examples/SedovBlast3D/params.yml" $mode/; cp sedov.hdf5 $mode/
  flag=--no-gpu; [ $mode = gpu ] && flag=--gpu
  (cd $mode && "$B/bolide" $flag -n 40 params.yml >run.log 2>&1) || { tail -5 $mode/run.log; exit 1; }
done
grep -h "GPU" gpu/run.log | head -3
paste <(grep -v '^#' cpu/statistics.txt) <(grep -v '^#' gpu/statistics.txt) | awk '
  { n = NF / 2; for (k = 1; k <= n; k++) { c[k] = $k; g[k] = $(k + n) } rows++
    # columns: step time dt mass px py pz Lx Ly Lz E_kin E_int E_pot E_tot n n_removed
    scale_p = sqrt(2 * c[4] * (c[11] > 0 ? c[11] : 1e-300))
    for (k = 4; k <= 14; k++) {
      s = (k >= 5 && k <= 10) ? scale_p : ((k == 4) ? c[4] : (c[14] != 0 ? (c[14] < 0 ? -c[14] : c[14]) : 1))
      d = c[k] - g[k]; if (d < 0) d = -d; e = d / s
      if (e > worst[k]) worst[k] = e }
  }
  END { split("step time dt mass px py pz Lx Ly Lz E_kin E_int E_pot E_tot", name, " ")
        fail = 0
        for (k = 4; k <= 14; k++) { printf "%-6s CPU vs GPU worst relative difference %.3e\n", name[k], worst[k]
                                     if (worst[k] > 1e-8) fail = 1 }
        printf "%d statistics rows compared\n", rows
        if (rows < 2) fail = 1
        exit fail }'
