/* Kick1 + drift of the particles of one cell on the CPU; the density
 * accumulators are zeroed here, before any density task of the step. */
#include "tasks/drift/drift_cpu.h"

#include "tasks/drift/drift.h"
#include "tasks/drift/drift_rk.h"
#include "tasks/hydro_parts.h"

void drift_cell_cpu(struct parts *p, struct cell *c, double dt_kick, double dt, double xsph,
                    double h_max, int h_continuity) {
  const size_t end = c->offset + c->count;
  for (size_t i = c->offset; i < end; i++) {
    /* (several MPI ranks: a foreign copy in a cell of owned particles, where
     * the top-level grid is no longer the decomposition's, takes its state
     * from its owner's refreshes, not from forces of its own: src/mpi/halo.c) */
    if (!(p->flags[i] & PART_FOREIGN)) {
      kick_part(p, i, dt_kick);
      drift_part(p, i, dt, xsph, h_max, h_continuity);
    }
    hydro_density_reset(p, i);
  }
  cell_update_bounds(p, c);
}

void drift_cell_bins_cpu(struct parts *p, struct cell *c, const struct timeline *tl,
                         integertime_t ti_old, integertime_t ti_new, const struct hydro_props *hp,
                         const struct material_table *mats) {
  const size_t end = c->offset + c->count;
  int active = 0;
  for (size_t i = c->offset; i < end; i++) {
    if (drift_part_bins(p, i, tl->time_base, ti_old, ti_new, hp, mats)) {
      hydro_density_reset(p, i);
      active++;
    }
  }
  c->active = active;
  cell_update_bounds(p, c);
}

double drift_cell_stage_cpu(struct parts *p, struct cell *c, const struct drift_stage *st,
                            const struct hydro_props *hp) {
  const size_t end = c->offset + c->count;
  double err = 0.0;
  for (size_t i = c->offset; i < end; i++) {
    const double e = drift_rk_stage(p, i, st, hp);
    if (e > err) err = e;
    hydro_density_reset(p, i);
  }
  cell_update_bounds(p, c);
  return err;
}
