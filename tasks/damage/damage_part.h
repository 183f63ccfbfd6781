/* The damage task's work on one particle, shared by the CPU task
 * (damage_task.c) and the CUDA kernel (damage_gpu.cu): the Grady-Kipp
 * update of damage_iact.h from the particle's fields, and its time-step
 * limit.  Physics written once (theory/architecture.md, rule 3). */
#ifndef BOLIDE_DAMAGE_PART_H
#define BOLIDE_DAMAGE_PART_H

#include "tasks/damage/damage_iact.h"
#include "src/inline.h"
#include "tasks/hydro/kernel.h"
#include "src/materials/material.h"
#include "src/part.h"

/** Flaw activation and growth of d^(1/3) of particle i over the step dt
 *  just computed, from the pressure and the predicted stress the force loop
 *  used (damage_update_particle, R_s = the kernel support).  eps: the flat
 *  array of flaw thresholds (the particle's slice starts at flaw_first[i]).
 *  Sets dmg_rate[i] (0 for particles without flaws). */
BOLIDE_INLINE void damage_part(struct parts *BOLIDE_RESTRICT p, size_t i,
                               const struct material_table *mats, const double *BOLIDE_RESTRICT eps,
                               double dt) {
  p->dmg_rate[i] = 0.0;
  if (p->n_flaws[i] == 0) return;
  const struct material *mat = material_table_find(mats, p->mat[i]);
  double S[6];
  S[SYM3_XX] = p->Spxx[i];
  S[SYM3_XY] = p->Spxy[i];
  S[SYM3_XZ] = p->Spxz[i];
  S[SYM3_YY] = p->Spyy[i];
  S[SYM3_YZ] = p->Spyz[i];
  S[SYM3_ZZ] = p->Spzz[i];
  int32_t n_act = p->n_act[i];
  p->dmg_rate[i] =
      damage_update_particle(mat, p->rho[i], kernel_gamma * p->h[i], p->P[i], S, eps,
                             p->flaw_first[i], p->n_flaws[i], dt, &p->dcbrt[i], &n_act, &p->dmg[i]);
  p->n_act[i] = n_act;
}

/** Time-step limit of particle i from its damage growth (damage_timestep):
 *  d grows by at most max_change per step. */
BOLIDE_INLINE double damage_part_timestep(const struct parts *BOLIDE_RESTRICT p, size_t i,
                                          double max_change) {
  return damage_timestep(p->dcbrt[i], p->n_act[i], p->n_flaws[i], p->dmg_rate[i], max_change);
}

#endif
