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
    if (PART_IS_NOT_OWNED(p, i)) continue; /* (no kick: drift_mirror.c, src/mpi/halo.c) */
    const double dt = kick2_part(p, i, dt_kick, hp, mats, tp);
    if (dt < dt_min) dt_min = dt;
    if (bins) bins[timeline_bin(tl, dt)]++;
  }
  return dt_min;
}

double kick2_cell_bins_cpu(struct parts *p, const struct cell *c, const struct hydro_props *hp,
                           const struct material_table *mats, const struct timestep_props *tp,
                           const struct timeline *tl, integertime_t ti_new, int first,
                           int64_t *bins, struct timeline_sums *sums) {
  double dt_min = 1e300;
  integertime_t ti_end_min = INT64_MAX;
  int64_t active = 0;
  const size_t end = c->offset + c->count;
  for (int b = 0; b <= TIMELINE_NR_BINS; b++) bins[b] = 0;
  for (size_t i = c->offset; i < end; i++) {
    integertime_t ti_end;
    double dt;
    active += kick2_part_bins(p, i, hp, mats, tp, tl, ti_new, first, &ti_end, &dt);
    if (dt < dt_min) dt_min = dt;
    if (ti_end < ti_end_min) ti_end_min = ti_end;
    bins[p->time_bin[i]]++;
  }
  sums->ti_end_min = ti_end_min;
  sums->active = active;
  return dt_min;
}
