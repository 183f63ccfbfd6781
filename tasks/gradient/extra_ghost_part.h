/* The extra ghost's work on one particle once its gradient sums are
 * complete (theory/solids.md): the corrected velocity gradient, the radial
 * return of the integrated and the predicted stress onto the yield surface,
 * dS/dt by Hooke's law with the Jaumann rate, and the artificial stress.
 * Shared by the CPU task (gradient_cpu.c) and the CUDA kernel
 * (gradient_gpu.cu): physics written once (theory/architecture.md, rule 3). */
#ifndef BOLIDE_EXTRA_GHOST_PART_H
#define BOLIDE_EXTRA_GHOST_PART_H

#include "tasks/damage/damage_iact.h"
#include "tasks/gradient/gradient_finish.h"
#include "tasks/hydro/hydro_props.h"
#include "src/inline.h"
#include "tasks/hydro/kernel.h"
#include "src/materials/material.h"
#include "src/part.h"
#include "src/materials/strength.h"
#include "src/materials/viscosity.h"

/** Read the six components of a symmetric tensor field into T. */
#define EXTRA_GHOST_GET6(T, p, pre, i)                                            \
  do {                                                                            \
    (T)[0] = (p)->pre##xx[i], (T)[1] = (p)->pre##xy[i], (T)[2] = (p)->pre##xz[i]; \
    (T)[3] = (p)->pre##yy[i], (T)[4] = (p)->pre##yz[i], (T)[5] = (p)->pre##zz[i]; \
  } while (0)
/** Write T into the six components of a symmetric tensor field. */
#define EXTRA_GHOST_PUT6(T, p, pre, i)                                            \
  do {                                                                            \
    (p)->pre##xx[i] = (T)[0], (p)->pre##xy[i] = (T)[1], (p)->pre##xz[i] = (T)[2]; \
    (p)->pre##yy[i] = (T)[3], (p)->pre##yz[i] = (T)[4], (p)->pre##zz[i] = (T)[5]; \
  } while (0)

/** The radial return of particle i's stress S (the integrated or the
 *  kicked one, 6 components) onto the yield surface of material mat (not
 *  elastic), with eps_rate the equivalent strain rate of its velocity
 *  gradient: the yield stress of the damaged material (Collins et al. 2004:
 *  tensile and shear damage together, min(1, d + D_s)), the plastic strain
 *  of the return added to eps_p, its plastic work Y d eps_p / rho to
 *  w_plastic (the statistics' W_plastic: already in u, which receives the
 *  whole stress power S:eps'/rho), and the Johnson & Cook (1985) fracture
 *  (theory/solids.md E6f) or else the shear damage (Collins et al. 2004),
 *  both growing with the plastic strain.  Called by the extra ghost and,
 *  so that every kicked state a snapshot or the statistics see lies on the
 *  yield surface, by the second kick (kick.h).  Returns the yield stress
 *  (of the state before the return's updates). */
BOLIDE_INLINE double extra_ghost_plastic_return(struct parts *BOLIDE_RESTRICT p, size_t i,
                                                const struct material *mat, double S[6],
                                                double eps_rate) {
  const double mu = mat->shear_modulus;
  const struct strength_state st = {p->P[i],  p->rho[i],
                                    p->up[i], p->eps_p[i],
                                    eps_rate, damage_total(p->dmg[i], p->dmg_shear[i])};
  const double Y = strength_yield(mat, &st);
  const double seq = sqrt(3.0 * strength_J2(S)); /* trial stress: triaxiality of E6f */
  const double deps_p = strength_radial_return(S, Y, mu);
  if (!(deps_p > 0.0)) return Y;
  p->eps_p[i] += deps_p;
  if (p->rho[i] > 0.0) p->w_plastic[i] += Y * deps_p / p->rho[i];
  if (strength_jc_fracture(mat))
    p->dmg_shear[i] = strength_jc_damage_update(mat, p->dmg_shear[i], deps_p, seq, p->P[i],
                                                p->rho[i], p->up[i], eps_rate);
  else if (mat->shear_failure_strain > 0.0)
    p->dmg_shear[i] =
        damage_shear_update(p->dmg_shear[i], deps_p, p->P[i], mat->shear_failure_strain,
                            mat->shear_failure_slope, mat->shear_failure_pressure);
  return Y;
}

/** With time bins, the predicted stress Sp of particle i, asleep in the
 *  middle of its step (PART_INACTIVE), radially returned onto the yield
 *  surface of its predicted state (pressure and energy of the drift's
 *  prediction, its plastic strain and damage of its step's start, the strain
 *  rate of its step's start gradients): the prediction S + dS/dt (t - t_mid)
 *  extrapolates the elastic rate and leaves the surface when the particle
 *  flows.  Only the prediction that snapshots, the statistics and the
 *  neighbours' force loops read is returned: the plastic strain, plastic
 *  work and shear damage of the return are the kick's, at the end of the
 *  particle's own step (kick2_plastic_return), and counted once there.
 *  mat: a material with strength (not elastic) and a shear modulus. */
BOLIDE_INLINE void extra_ghost_predicted_return(struct parts *BOLIDE_RESTRICT p, size_t i,
                                                const struct material *mat) {
  const double mu = mat->shear_modulus;
  double Sp[6], dS[6];
  EXTRA_GHOST_GET6(Sp, p, Sp, i);
  const double gv[9] = {p->gvxx[i], p->gvxy[i], p->gvxz[i], p->gvyx[i], p->gvyy[i],
                        p->gvyz[i], p->gvzx[i], p->gvzy[i], p->gvzz[i]};
  const double eps_rate = gradient_stress_rate(gv, Sp, mu, dS);
  const struct strength_state st = {p->P[i],  p->rho[i],
                                    p->up[i], p->eps_p[i],
                                    eps_rate, damage_total(p->dmg[i], p->dmg_shear[i])};
  if (strength_radial_return(Sp, strength_yield(mat, &st), mu) > 0.0)
    EXTRA_GHOST_PUT6(Sp, p, Sp, i);
}

/** The corrected velocity gradient gv = G M^-1 of particle i (Randles &
 *  Libersky 1996; G alone without SPH:velocity_gradient_correction), from
 *  its gradient sums; stored back into the gv fields. */
BOLIDE_INLINE void extra_ghost_velocity_gradient(struct parts *BOLIDE_RESTRICT p, size_t i,
                                                 const struct hydro_props *hp, double gv[9]) {
  double M[6], Minv[9];
  EXTRA_GHOST_GET6(M, p, gm, i);
  const double G[9] = {p->gvxx[i], p->gvxy[i], p->gvxz[i], p->gvyx[i], p->gvyy[i],
                       p->gvyz[i], p->gvzx[i], p->gvzy[i], p->gvzz[i]};
  if (hp->gradient_correction)
    gradient_invert_sym(M, Minv);
  else
    for (int k = 0; k < 9; k++) Minv[k] = (k % 4 == 0) ? 1.0 : 0.0;
  gradient_apply(G, Minv, gv);
  p->gvxx[i] = gv[0], p->gvxy[i] = gv[1], p->gvxz[i] = gv[2];
  p->gvyx[i] = gv[3], p->gvyy[i] = gv[4], p->gvyz[i] = gv[5];
  p->gvzx[i] = gv[6], p->gvzy[i] = gv[7], p->gvzz[i] = gv[8];
}

/** Free-surface detection of fluid particle i (theory/fluids.md F5): with the self term V_i W(0,
 * h_i) added, its kernel sum Z_i = sum_j m_j/rho_j W_ij is about 1 inside the fluid and about 1/2
 * on a flat surface; below hp->free_surface_threshold the particle is on the free surface: flagged
 * PART_FREE_SURFACE, pressure 0 for the force loop. Particles of materials with strength are never
 * flagged. */
BOLIDE_INLINE void extra_ghost_free_surface(struct parts *BOLIDE_RESTRICT p, size_t i,
                                            const struct hydro_props *hp,
                                            const struct material *mat) {
  p->wvol[i] += p->m[i] / p->rho[i] * kernel_W(0.0, p->h[i]);
  if (hp->free_surface && mat && mat->strength == STRENGTH_NONE &&
      p->wvol[i] < hp->free_surface_threshold) {
    p->flags[i] |= PART_FREE_SURFACE;
    p->P[i] = 0.0;
  } else {
    p->flags[i] &= ~PART_FREE_SURFACE;
  }
}

/** Finish solid particle i: gv = G M^-1 (Randles & Libersky 1996; the
 *  identity without SPH:gradient_correction), plasticity, dS/dt and R.
 *  A viscous fluid (material key viscosity) gets the Newtonian stress
 *  S = 2 eta e' of its corrected gradient (viscosity.h) and dS/dt = 0;
 *  other particles of materials without strength get zero stress, rates
 *  and R.  With SPH:continuity_correction, drho/dt of every particle (E14);
 *  with SPH:free_surface, the free-surface detection of fluid particles. */
BOLIDE_INLINE void extra_ghost_part(struct parts *BOLIDE_RESTRICT p, size_t i,
                                    const struct hydro_props *hp,
                                    const struct material_table *mats) {
  const struct material *mat = material_table_find(mats, p->mat[i]);
  const double zero[6] = {0, 0, 0, 0, 0, 0};
  /* the phase the force loop's fluid-solid interface reads (force_iact.h) */
  if (mat && mat->strength != STRENGTH_NONE)
    p->flags[i] |= PART_SOLID;
  else
    p->flags[i] &= ~PART_SOLID;
  extra_ghost_free_surface(p, i, hp, mat);
  if (hp->continuity_cspm) {
    /* CSPM continuity (theory/solids.md E14), every particle, fluids
     * included: the force loop adds no density rate of its own (force_iact.h) */
    double M6[6];
    EXTRA_GHOST_GET6(M6, p, gm, i);
    const double G9[9] = {p->gvxx[i], p->gvxy[i], p->gvxz[i], p->gvyx[i], p->gvyy[i],
                          p->gvyz[i], p->gvzx[i], p->gvzy[i], p->gvzz[i]};
    p->drho_dt[i] = gradient_cspm_drho_dt(p->rho[i], M6, G9);
  }
  double gv[9];
  if (mat && mat->strength == STRENGTH_NONE && mat->viscosity > 0.0) {
    /* Newtonian fluid: S = 2 eta e', the same in the integrated and the
     * predicted stress, no rate of its own */
    double S[6];
    extra_ghost_velocity_gradient(p, i, hp, gv);
    viscosity_stress(gv, mat->viscosity, S);
    EXTRA_GHOST_PUT6(S, p, S, i);
    EXTRA_GHOST_PUT6(S, p, Sp, i);
    EXTRA_GHOST_PUT6(zero, p, dS, i);
    EXTRA_GHOST_PUT6(zero, p, R, i);
    return;
  }
  if (!mat || mat->strength == STRENGTH_NONE || !(mat->shear_modulus > 0.0)) {
    EXTRA_GHOST_PUT6(zero, p, S, i);
    EXTRA_GHOST_PUT6(zero, p, Sp, i);
    EXTRA_GHOST_PUT6(zero, p, dS, i);
    EXTRA_GHOST_PUT6(zero, p, R, i);
    return;
  }
  /* corrected velocity gradient (Randles & Libersky 1996) */
  extra_ghost_velocity_gradient(p, i, hp, gv);

  /* plasticity: the radial return of the integrated and the predicted stress */
  double S[6], Sp[6], dS[6];
  EXTRA_GHOST_GET6(S, p, S, i);
  EXTRA_GHOST_GET6(Sp, p, Sp, i);
  const double mu = mat->shear_modulus;
  const double eps_rate = gradient_stress_rate(gv, Sp, mu, dS);
  if (mat->strength != STRENGTH_ELASTIC) {
    const double Y = extra_ghost_plastic_return(p, i, mat, S, eps_rate);
    /* the predicted stress onto the same yield surface (its plastic strain
     * is that of S, counted once) */
    strength_radial_return(Sp, Y, mu);
    EXTRA_GHOST_PUT6(S, p, S, i);
    EXTRA_GHOST_PUT6(Sp, p, Sp, i);
    gradient_stress_rate(gv, Sp, mu, dS);
  }
  EXTRA_GHOST_PUT6(dS, p, dS, i);

  /* artificial stress against the tensile instability (Monaghan 2000) */
  double R[6] = {0, 0, 0, 0, 0, 0};
  if (hp->as_eps > 0.0) gradient_artificial_stress(Sp, p->P[i], p->rho[i], hp->as_eps, R);
  EXTRA_GHOST_PUT6(R, p, R, i);
}

#endif
