/* Second half kick and new time step of one particle, shared by the CPU task
 * (kick_cpu.c) and the CUDA kernel (kick_gpu.cu). */
#ifndef BOLIDE_KICK_H
#define BOLIDE_KICK_H

#include <math.h>

#include "drift/drift.h"
#include "ghost/continuity_floor.h"
#include "gradient/extra_ghost_part.h"
#include "hydro_props.h"
#include "inline.h"
#include "material.h"
#include "part.h"
#include "kick/timestep.h"
#include "viscosity.h"

/** The kicked stress of a plastic particle back onto its yield surface
 *  (extra_ghost_plastic_return, with the yield stress of this step's
 *  state and the velocity gradient of this step's extra ghost), so that
 *  the state after the kick, which snapshots, statistics and restart files
 *  hold, never lies outside the yield surface. */
BOLIDE_INLINE void kick2_plastic_return(struct parts *BOLIDE_RESTRICT p, size_t i,
                                        const struct material_table *mats) {
  const struct material *mat = material_table_find(mats, p->mat[i]);
  if (!mat || mat->strength == STRENGTH_NONE || mat->strength == STRENGTH_ELASTIC ||
      !(mat->shear_modulus > 0.0))
    return;
  double S[6], dS[6];
  EXTRA_GHOST_GET6(S, p, S, i);
  const double gv[9] = {p->gvxx[i], p->gvxy[i], p->gvxz[i], p->gvyx[i], p->gvyy[i],
                        p->gvyz[i], p->gvzx[i], p->gvzy[i], p->gvzz[i]};
  const double eps_rate = gradient_stress_rate(gv, S, mat->shear_modulus, dS);
  extra_ghost_plastic_return(p, i, mat, S, eps_rate);
  EXTRA_GHOST_PUT6(S, p, S, i);
}

/** Kick particle i by dt_kick, bring a plastic particle's stress back onto
 *  its yield surface (kick2_plastic_return), make the predicted state the
 *  kicked one (kick_sync_predicted), and return its new time step
 *  (timestep_hydro, the viscous diffusion limit of a viscous fluid and,
 *  with SPH:max_relative_change, the relative-change limits).  With the
 *  continuity equation a particle on its density floor does not expand
 *  further (continuity_floor.h). */
BOLIDE_INLINE double kick2_part(struct parts *BOLIDE_RESTRICT p, size_t i, double dt_kick,
                                const struct hydro_props *hp, const struct material_table *mats) {
  if (hp->continuity) continuity_floor_rate(p, i);
  kick_part(p, i, dt_kick);
  if (hp->solids) kick2_plastic_return(p, i, mats);
  kick_sync_predicted(p, i);
  const double a = sqrt(p->ax[i] * p->ax[i] + p->ay[i] * p->ay[i] + p->az[i] * p->az[i]);
  double dt = timestep_hydro(hp, p->h[i], p->v_sig[i], a, p->div_v[i]);
  if (hp->solids) {
    /* viscous diffusion of a Newtonian fluid (viscosity.h) */
    const struct material *mat = material_table_find(mats, p->mat[i]);
    if (mat && mat->viscosity > 0.0) {
      const double dtv = viscosity_timestep(kernel_gamma * p->h[i], p->rho[i], mat->viscosity);
      if (dtv < dt) dt = dtv;
    }
  }
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
