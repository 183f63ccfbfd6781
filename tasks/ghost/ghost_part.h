/* The ghost's work on one particle, shared by the CPU task (ghost_cpu.c) and
 * the CUDA kernels (ghost_gpu.cu): add the self term, take one step of the
 * smoothing-length iteration, and finish the density-derived quantities and
 * the equation of state.  Physics written once (theory/architecture.md,
 * rule 3). */
#ifndef BOLIDE_GHOST_PART_H
#define BOLIDE_GHOST_PART_H

#include <math.h>

#include "tasks/ghost/continuity_floor.h"
#include "tasks/damage/damage_iact.h"
#include "tasks/ghost/ghost_iact.h"
#include "tasks/hydro_parts.h"
#include "tasks/hydro/hydro_props.h"
#include "src/inline.h"
#include "src/materials/material.h"
#include "src/part.h"
#include "src/materials/porosity_eos.h"
#include "src/materials/strength.h"

/** Add particle i's own contribution to its density sums. */
BOLIDE_INLINE void ghost_part_add_self(struct parts *BOLIDE_RESTRICT p, size_t i) {
  struct density_acc a = {0, 0, 0, 0, 0, {0, 0, 0}};
  density_self_term(1.0 / p->h[i], p->m[i], &a);
  hydro_density_add(p, i, &a);
}

/** A particle held but not owned (PART_IS_NOT_OWNED: a mirror ghost, a
 *  foreign copy of several MPI ranks) keeps its source's or owner's h: its
 *  iteration ends at once (returns 1, converged); 0 for the others. */
BOLIDE_INLINE int ghost_part_keeps_h(struct parts *BOLIDE_RESTRICT p, size_t i) {
  if (!PART_IS_NOT_OWNED(p, i)) return 0;
  p->flags[i] |= PART_H_CONVERGED;
  return 1;
}

/** Start the iteration of particle i: clear its converged bit and bracket. */
BOLIDE_INLINE void ghost_part_start(struct parts *BOLIDE_RESTRICT p, size_t i) {
  p->flags[i] &= ~PART_H_CONVERGED;
  p->h_lo[i] = 0.0;
  p->h_hi[i] = 1e300;
}

/** One iteration step for particle i (its sums complete, self term
 *  included); sets PART_H_CONVERGED when done, else stores the new h.
 *  A converged particle keeps the h of its sums; the ratio of the root's
 *  estimate from those sums to it goes into h_lo (no longer a bracket):
 *  the drift at the start of the particle's next step applies it
 *  (drift_h_root), so that the next iteration starts from the root and
 *  not from an h up to the tolerance away from it.
 *  h_cap: the largest h the cells allow.  Returns 1 if the particle was
 *  capped at h_cap below SPH:h_max (the cells must be rebuilt).  With
 *  SPH:h_evolution: continuity the h the drift integrated is kept (one
 *  pass of the sums), unless it is above the cap: then the sums are redone
 *  at the cap. */
BOLIDE_INLINE int ghost_part_step(struct parts *BOLIDE_RESTRICT p, size_t i,
                                  const struct hydro_props *hp, double h_cap) {
  double h = p->h[i];
  const double hmax = hp->h_max < h_cap ? hp->h_max : h_cap;
  if (hp->h_continuity) {
    if (h > hmax) {
      p->h[i] = hmax;
      return 0;
    }
    p->flags[i] |= PART_H_CONVERGED;
    return (h >= h_cap && h_cap < hp->h_max) ? 1 : 0;
  }
  const int r = ghost_h_iterate(&h, &p->h_lo[i], &p->h_hi[i], p->wcount[i], p->wcount_dh[i],
                                hp->eta, hp->h_tolerance, hp->h_taylor, hmax);
  int capped = 0;
  if (r == GHOST_H_TAYLOR) {
    /* the sums at the new h to first order in the step (SPH:h_taylor); the
     * velocity sums (div v, curl v) keep the old h's, a relative
     * difference of the step's order in the viscosity switch alone */
    const double dh = h - p->h[i];
    p->rho[i] += p->rho_dh[i] * dh;
    p->wcount[i] += p->wcount_dh[i] * dh;
    p->h[i] = h;
    p->flags[i] |= PART_H_CONVERGED;
    p->h_lo[i] = 1.0;
    if (h >= h_cap && h_cap < hp->h_max) capped = 1;
  } else if (r == GHOST_H_CONVERGED) {
    p->flags[i] |= PART_H_CONVERGED;
    if (h >= h_cap && h_cap < hp->h_max) capped = 1;
    /* keep the h the sums were computed with; h is the root's estimate
     * (at most the cells' cap) */
    p->h_lo[i] = h / p->h[i];
  } else {
    p->h[i] = h;
  }
  return capped;
}

/** The equation of state of particle i at its density p->rho and
 *  predicted energy p->up (and distention p->alpha_p, which a porous
 *  material returns to its crush curve): P, cs, with solids c_l, and the
 *  PART_U_FLOOR flag of its material.  Fractured material (Johnson & Cook
 *  1985; theory/solids.md E6f) carries no tension; with spall_pressure, a
 *  tension beyond it fractures (E6g): the ghost (predict = 0) records the
 *  fracture in dmg_shear, the prediction of a sleeping particle's state
 *  (predict = 1, drift_predict_hydro) only takes P = 0 and changes no
 *  damage.  A fluid particle on the free surface (PART_FREE_SURFACE, flagged
 *  by its last extra ghost) keeps P = 0 in the prediction. */
BOLIDE_INLINE void ghost_part_eos(struct parts *BOLIDE_RESTRICT p, size_t i,
                                  const struct hydro_props *hp, const struct material *mat,
                                  int predict) {
  double P, cs;
  if (mat->porosity.model != POROSITY_NONE)
    porosity_eos(mat, p->rho[i], p->up[i], &p->alpha_p[i], &P,
                 &cs); /* P = P_s(alpha rho, u)/alpha */
  else
    material_eos(mat, p->rho[i], p->up[i], &P, &cs);
  if (hp->solids && P < 0.0 && strength_jc_fracture(mat)) {
    const int spall = mat->spall_pressure > 0.0 && P < -mat->spall_pressure;
    if (spall && !predict) p->dmg_shear[i] = 1.0;
    if (spall || p->dmg_shear[i] >= 1.0) P = 0.0;
  }
  if (predict && (p->flags[i] & PART_FREE_SURFACE)) P = 0.0;
  p->P[i] = P;
  p->cs[i] = cs;
  if (mat->u_floor)
    p->flags[i] |= PART_U_FLOOR;
  else
    p->flags[i] &= ~PART_U_FLOOR;
  if (hp->solids) {
    /* the time step of a solid follows its fastest wave, the longitudinal
     * one: c_l^2 = (K + 4 G / 3) / rho = c_s^2 + 4 G / (3 rho), with the
     * shear modulus of the damaged material (1 - D) G (theory/solids.md,
     * "Time step"); c_s alone would give an effective Courant number
     * c_l / c_s times the one asked for (1.46 for basalt) */
    double G = 0.0;
    if (mat->strength != STRENGTH_NONE && mat->shear_modulus > 0.0)
      G = (1.0 - damage_total(p->dmg[i], p->dmg_shear[i])) * mat->shear_modulus;
    p->cl[i] = sqrt(cs * cs + 4.0 * G / (3.0 * p->rho[i]));
  }
}

/** Density-derived quantities and the equation of state of particle i
 *  (grad-h factor, Springel & Hernquist 2002 eq. 8; div v and curl v
 *  normalised by rho; Balsara 1995 switch); zeroes its force sums. */
BOLIDE_INLINE void ghost_part_finish(struct parts *BOLIDE_RESTRICT p, size_t i,
                                     const struct hydro_props *hp,
                                     const struct material_table *mats) {
  const double rho = p->rho[i];
  const double h = p->h[i];
  /* at SPH:h_max the h of a particle no longer follows its neighbours, and
   * one alone within its support has rho_dh = -3 rho / h (the self term):
   * the factor 1 / (1 + h rho_dh / (3 rho)) would be infinite.  No grad-h
   * correction there (f = 1), as SWIFT does at its h_max. */
  const double gradh_den = 1.0 + h * p->rho_dh[i] / (3.0 * rho);
  p->f_gradh[i] = (h >= hp->h_max || !(gradh_den > 1e-3)) ? 1.0 : 1.0 / gradh_den;
  const double rho_inv = 1.0 / rho;
  p->div_v[i] *= rho_inv;
  p->curl_vx[i] *= rho_inv;
  p->curl_vy[i] *= rho_inv;
  p->curl_vz[i] *= rho_inv;
  /* continuity equation: the summed density served the h iteration and the
   * grad-h factor; the EOS and the force loop use the integrated density
   * (started from the summation where the initial conditions had none) */
  const struct material *mat = material_table_find(mats, p->mat[i]);
  if (hp->continuity) {
    if (!(p->rho_full[i] > 0.0)) p->rho_full[i] = p->rho_fp[i] = rho;
    continuity_floor_part(p, i, continuity_rho_floor(hp, mat));
    p->rho[i] = p->rho_fp[i];
  }
  ghost_part_eos(p, i, hp, mat, 0);
  const double curl = sqrt(p->curl_vx[i] * p->curl_vx[i] + p->curl_vy[i] * p->curl_vy[i] +
                           p->curl_vz[i] * p->curl_vz[i]);
  p->balsara[i] = hp->balsara ? ghost_balsara(p->div_v[i], curl, p->cs[i], h) : 1.0;
  /* zero the force sums here: every force task of the cell runs after its ghost */
  hydro_force_reset(p, i);
  if (hp->solids) hydro_gradient_reset(p, i);
}

#endif
