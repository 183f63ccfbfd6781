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
    kick_sync_predicted(p, i);
    const double a = sqrt(p->ax[i] * p->ax[i] + p->ay[i] * p->ay[i] + p->az[i] * p->az[i]);
    double dt = timestep_hydro(hp, p->h[i], p->v_sig[i], a, p->div_v[i]);
    if (hp->max_rel_change > 0.0) {
      const double S[6] = {p->Sxx[i], p->Sxy[i], p->Sxz[i], p->Syy[i], p->Syz[i], p->Szz[i]};
      const double dS[6] = {p->dSxx[i], p->dSxy[i], p->dSxz[i], p->dSyy[i], p->dSyz[i], p->dSzz[i]};
      const double dtr = timestep_relative_change(hp, p->rho[i], p->drho_dt[i], p->u[i], p->du_dt[i],
                                                  p->cs[i], S, dS);
      if (dtr < dt) dt = dtr;
    }
    if (dt < dt_min) dt_min = dt;
  }
  return dt_min;
}
