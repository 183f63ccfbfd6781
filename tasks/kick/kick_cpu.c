/* Second half kick and time step of one cell on the CPU. */
#include "kick_cpu.h"

#include "kick.h"

double kick2_cell_cpu(struct parts *p, const struct cell *c, double dt_kick,
                      const struct hydro_props *hp, const struct material_table *mats,
                      const struct timestep_props *tp) {
  double dt_min = 1e300;
  const size_t end = c->offset + c->count;
  for (size_t i = c->offset; i < end; i++) {
    const double dt = kick2_part(p, i, dt_kick, hp, mats, tp);
    if (dt < dt_min) dt_min = dt;
  }
  return dt_min;
}
