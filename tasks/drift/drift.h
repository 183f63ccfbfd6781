/* Kick and drift of one particle (kick-drift-kick leapfrog, theory/sph.md
 * section "Time integration").  Written once for CPU and GPU. */
#ifndef BOLIDE_DRIFT_H
#define BOLIDE_DRIFT_H

#include <math.h>

#include "inline.h"
#include "part.h"

/** Half kick of particle i by dt_kick: v += a dt, u += du/dt dt (u kept
 *  non-negative: an energy that would go negative is halved instead, as
 *  SWIFT's planetary scheme does). */
BOLIDE_INLINE void kick_part(struct parts *BOLIDE_RESTRICT p, size_t i, double dt_kick) {
  p->vx[i] += p->ax[i] * dt_kick;
  p->vy[i] += p->ay[i] * dt_kick;
  p->vz[i] += p->az[i] * dt_kick;
  const double u1 = p->u[i] + p->du_dt[i] * dt_kick;
  p->u[i] = (u1 >= 0.0) ? u1 : 0.5 * p->u[i];
}

/** Drift of particle i by dt after its first half kick: positions move with
 *  the half-step velocity; the velocity and energy used by the next force
 *  computation are predicted to the end of the step; h follows the
 *  velocity divergence (dh/dt = h div v / 3) as a first guess for the
 *  iteration. */
BOLIDE_INLINE void drift_part(struct parts *BOLIDE_RESTRICT p, size_t i, double dt) {
  p->x[i] += p->vx[i] * dt;
  p->y[i] += p->vy[i] * dt;
  p->z[i] += p->vz[i] * dt;
  const double half = 0.5 * dt;
  p->vpx[i] = p->vx[i] + p->ax[i] * half;
  p->vpy[i] = p->vy[i] + p->ay[i] * half;
  p->vpz[i] = p->vz[i] + p->az[i] * half;
  const double up = p->u[i] + p->du_dt[i] * half;
  p->up[i] = (up >= 0.0) ? up : 0.5 * p->u[i];
  double w = p->div_v[i] * dt / 3.0;
  if (w > 0.2) w = 0.2;
  if (w < -0.2) w = -0.2;
  p->h[i] *= exp(w);
}

#endif
