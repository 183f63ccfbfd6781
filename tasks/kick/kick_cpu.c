/* Second half kick and time step of one cell on the CPU. */
#include "kick_cpu.h"

#include <math.h>

#include "drift/drift.h"
#include "timestep/timestep.h"

double kick2_cell_cpu(struct parts *p, const struct cell *c, double dt_kick,
                      const struct hydro_props *hp) {
  double dt_min = 1e300;
  const size_t end = c->offset + c->count;
  for (size_t i = c->offset; i < end; i++) {
    kick_part(p, i, dt_kick);
    p->vpx[i] = p->vx[i];
    p->vpy[i] = p->vy[i];
    p->vpz[i] = p->vz[i];
    p->up[i] = p->u[i];
    const double a = sqrt(p->ax[i] * p->ax[i] + p->ay[i] * p->ay[i] + p->az[i] * p->az[i]);
    const double dt = timestep_hydro(hp, p->h[i], p->v_sig[i], a, p->div_v[i]);
    if (dt < dt_min) dt_min = dt;
  }
  return dt_min;
}
