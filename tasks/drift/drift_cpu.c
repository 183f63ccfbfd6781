/* Kick1 + drift of the particles of one cell on the CPU; the density
 * accumulators are zeroed here, before any density task of the step. */
#include "tasks/drift/drift_cpu.h"

#include "tasks/drift/drift.h"
#include "tasks/hydro_parts.h"

void drift_cell_cpu(struct parts *p, struct cell *c, double dt_kick, double dt, double xsph,
                    double h_max, int h_continuity) {
  const size_t end = c->offset + c->count;
  for (size_t i = c->offset; i < end; i++) {
    kick_part(p, i, dt_kick);
    drift_part(p, i, dt, xsph, h_max, h_continuity);
    hydro_density_reset(p, i);
  }
  cell_update_bounds(p, c);
}

void drift_cell_bins_cpu(struct parts *p, struct cell *c, const struct timeline *tl,
                         integertime_t ti_old, integertime_t ti_new, double xsph, double h_max,
                         int h_continuity) {
  const size_t end = c->offset + c->count;
  const double dt = (double)(ti_new - ti_old) * tl->time_base;
  for (size_t i = c->offset; i < end; i++) {
    const integertime_t step = timeline_step_of_bin(p->time_bin[i] > 0 ? p->time_bin[i] : 1);
    const integertime_t since = ti_old % step; /* 0: its step begins at ti_old */
    if (since == 0) kick_part(p, i, 0.5 * (double)step * tl->time_base);
    const integertime_t ti_mid = ti_old - since + step / 2;
    drift_part_to(p, i, dt, (double)(ti_new - ti_mid) * tl->time_base, xsph, h_max, h_continuity);
    hydro_density_reset(p, i);
  }
  cell_update_bounds(p, c);
}
