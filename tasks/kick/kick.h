/* Second half kick and new time step of one particle, shared by the CPU task
 * (kick_cpu.c) and the CUDA kernel (kick_gpu.cu). */
#ifndef BOLIDE_KICK_H
#define BOLIDE_KICK_H

#include <math.h>

#include "drift/drift.h"
#include "ghost/continuity_floor.h"
#include "hydro_props.h"
#include "inline.h"
#include "part.h"
#include "timestep/timestep.h"

/** Kick particle i by dt_kick, make the predicted state the kicked one
 *  (kick_sync_predicted), and return its new time step (timestep_hydro and,
 *  with SPH:max_relative_change, the relative-change limits).  With the
 *  continuity equation a particle on its density floor does not expand
 *  further (continuity_floor.h). */
BOLIDE_INLINE double kick2_part(struct parts *BOLIDE_RESTRICT p, size_t i, double dt_kick,
                                const struct hydro_props *hp) {
  if (hp->continuity) continuity_floor_rate(p, i);
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
  return dt;
}

#endif
