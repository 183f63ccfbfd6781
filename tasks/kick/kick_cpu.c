/* Second half kick and time step of one cell on the CPU. */
#include "tasks/kick/kick_cpu.h"

#include "tasks/kick/kick.h"
#include "src/timeline.h"

double kick2_cell_cpu(struct parts *p, const struct cell *c, double dt_kick,
                      const struct hydro_props *hp, const struct material_table *mats,
                      const struct timestep_props *tp, const struct timeline *tl, int64_t *bins) {
  double dt_min = 1e300;
  const size_t end = c->offset + c->count;
  if (bins)
    for (int b = 0; b <= TIMELINE_NR_BINS; b++) bins[b] = 0;
  for (size_t i = c->offset; i < end; i++) {
    const double dt = kick2_part(p, i, dt_kick, hp, mats, tp);
    if (dt < dt_min) dt_min = dt;
    if (bins) bins[timeline_bin(tl, dt)]++;
  }
  return dt_min;
}
