/* Second half kick and new time step of one particle, shared by the CPU task
 * (kick_cpu.c) and the CUDA kernel (kick_gpu.cu). */
#ifndef BOLIDE_KICK_H
#define BOLIDE_KICK_H

#include <math.h>

#include "drift/drift.h"
#include "hydro_props.h"
#include "inline.h"
#include "part.h"
#include "timestep/timestep.h"

/** Kick particle i by dt_kick, make the predicted velocity and energy the
 *  kicked ones, and return its new time step (timestep_hydro). */
BOLIDE_INLINE double kick2_part(struct parts *BOLIDE_RESTRICT p, size_t i, double dt_kick,
                                const struct hydro_props *hp) {
  kick_part(p, i, dt_kick);
  p->vpx[i] = p->vx[i];
  p->vpy[i] = p->vy[i];
  p->vpz[i] = p->vz[i];
  p->up[i] = p->u[i];
  const double a = sqrt(p->ax[i] * p->ax[i] + p->ay[i] * p->ay[i] + p->az[i] * p->az[i]);
  return timestep_hydro(hp, p->h[i], p->v_sig[i], a, p->div_v[i]);
}

#endif
