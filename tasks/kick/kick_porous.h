/* Porous materials around the second half kick (P-alpha, theory/porosity.md
 * PA6 and PA10), shared by the CPU kick task (kick_task.c) and the
 * CUDA kick kernel (kick_gpu.cu). */
#ifndef BOLIDE_KICK_POROUS_H
#define BOLIDE_KICK_POROUS_H

#include "src/inline.h"
#include "src/materials/material.h"
#include "src/part.h"
#include "src/materials/porosity_eos.h"

/** Before the kick: dalpha/dt of particle i from the rates of this force
 *  loop (PA6; 0 for materials that are not P-alpha porous). */
BOLIDE_INLINE void kick2_porous_rate(struct parts *BOLIDE_RESTRICT p, size_t i,
                                     const struct material_table *mats) {
  const struct material *mat = material_table_find(mats, p->mat[i]);
  p->dalpha_dt[i] =
      porosity_rate(mat, p->rho[i], p->drho_dt[i], p->up[i], p->du_dt[i], p->alpha_p[i]);
}

/** After the kick (not after the first force computation): the kicked state
 *  of a P-alpha particle back on the crush curve (PA10), the distention of
 *  an epsilon-alpha particle to that of its strain (EA6); rho is the
 *  integrated density with the continuity equation, the summed one else. */
BOLIDE_INLINE void kick2_porous_return(struct parts *BOLIDE_RESTRICT p, size_t i,
                                       const struct material_table *mats, int continuity) {
  const struct material *mat = material_table_find(mats, p->mat[i]);
  if (mat->porosity.model == POROSITY_NONE) return;
  const double rho = continuity ? p->rho_full[i] : p->rho[i];
  p->alpha[i] = p->alpha_p[i] = mat->porosity.model == POROSITY_PALPHA
                                    ? porosity_palpha_return(mat, rho, p->u[i], p->alpha[i])
                                    : porosity_epsalpha_update(mat, rho, p->alpha[i]);
}

#endif
