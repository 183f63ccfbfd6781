/* Strength: the yield stress of a material (one switch on the strength
 * model, each model in its own file strength_*.h) and the J2 radial return
 * that brings the deviatoric stress back onto the yield surface (Wilkins
 * 1964; Benz & Asphaug 1994, Sec. 2; Schaefer et al. 2016, Sec. 2.3; theory/solids.md eq. E7).
 * Shared by CPU and GPU.  theory/solids.md, "Plasticity". */
#ifndef BOLIDE_STRENGTH_H
#define BOLIDE_STRENGTH_H

#include <math.h>

#include "src/inline.h"
#include "src/materials/material.h"
#include "src/materials/strength_collins.h"
#include "src/materials/strength_drucker_prager.h"
#include "src/materials/strength_johnson_cook.h"
#include "src/materials/strength_mohr_coulomb.h"
#include "src/materials/strength_von_mises.h"

/** What the yield stress of a particle depends on. */
struct strength_state {
  double P;        /**< pressure */
  double rho;      /**< density */
  double u;        /**< specific internal energy */
  double eps_p;    /**< equivalent plastic strain */
  double eps_rate; /**< equivalent strain rate sqrt(2/3 e':e') */
  double damage;   /**< damage D in [0, 1] (0 until the damage module sets it) */
};

/** Temperature for Johnson-Cook: T_ref + u / c_v with the material's
 *  specific_heat, else the EOS's temperature. */
BOLIDE_INLINE double strength_temperature(const struct material *mat, double rho, double u) {
  if (mat->specific_heat > 0.0) return mat->T_ref + u / mat->specific_heat;
  return material_temperature(mat, rho, u);
}

/** Whether material mat fractures by Johnson & Cook (1985): Johnson-Cook
 *  strength with D1 or D2 set (theory/solids.md E6f). */
BOLIDE_INLINE int strength_jc_fracture(const struct material *mat) {
  return mat->strength == STRENGTH_JOHNSON_COOK && (mat->jc_D1 != 0.0 || mat->jc_D2 != 0.0);
}

/** Yield stress Y (as the equivalent stress sqrt(3 J2)) of material mat in
 *  state st; INFINITY for purely elastic materials, 0 for fluids.  Thermal
 *  softening: Y falls linearly to zero at melt_energy when it is set
 *  (Benz & Asphaug 1999; Schaefer et al. 2016). */
BOLIDE_INLINE double strength_yield(const struct material *mat, const struct strength_state *st) {
  double melt = 1.0;
  if (mat->melt_energy > 0.0) {
    melt = 1.0 - st->u / mat->melt_energy;
    if (melt < 0.0) melt = 0.0;
  }
  switch (mat->strength) {
    case STRENGTH_NONE:
      return 0.0;
    case STRENGTH_ELASTIC:
      return INFINITY;
    case STRENGTH_VON_MISES:
      return strength_von_mises_yield(mat->yield_stress, melt);
    case STRENGTH_DRUCKER_PRAGER:
      return melt * strength_drucker_prager_yield(mat->yield_stress, mat->friction_intact,
                                                  mat->yield_stress_max, st->P);
    case STRENGTH_MOHR_COULOMB:
      return melt * strength_mohr_coulomb_yield(mat->yield_stress, mat->friction_intact,
                                                mat->yield_stress_max, st->P);
    case STRENGTH_COLLINS:
      return melt * strength_collins_yield(mat->yield_stress, mat->friction_intact,
                                           mat->yield_stress_max, mat->cohesion_damaged,
                                           mat->friction_damaged, st->P, st->damage);
    case STRENGTH_JOHNSON_COOK:
      /* fractured (Johnson & Cook 1985: D = 1): no strength */
      if (st->damage >= 1.0 && strength_jc_fracture(mat)) return 0.0;
      return strength_johnson_cook_yield(mat->jc_A, mat->jc_B, mat->jc_C, mat->jc_m, mat->jc_n,
                                         mat->jc_strain_rate_ref, mat->T_ref, mat->T_melt,
                                         st->eps_p, st->eps_rate,
                                         strength_temperature(mat, st->rho, st->u));
    default:
      return 0.0;
  }
}

/** Johnson & Cook (1985) fracture damage D after a radial return that gave
 *  the plastic strain increment deps_p; seq: the equivalent stress
 *  sqrt(3 J2) of the trial (elastic predictor) stress, which with the
 *  pressure P gives the triaxiality s* = -P / seq; rho, u, eps_rate as for
 *  the yield stress.  D is stored in the ShearDamage field; at D = 1 the
 *  particle has fractured: no strength (strength_yield) and no tension
 *  (ghost_part.h). */
BOLIDE_INLINE double strength_jc_damage_update(const struct material *mat, double D, double deps_p,
                                               double seq, double P, double rho, double u,
                                               double eps_rate) {
  if (!(deps_p > 0.0) || D >= 1.0) return D;
  const double s_star = seq > 0.0 ? -P / seq : 0.0;
  const double T = strength_temperature(mat, rho, u);
  const double T_star = (T - mat->T_ref) / (mat->T_melt - mat->T_ref);
  const double eps_f = strength_johnson_cook_failure_strain(
      mat->jc_D1, mat->jc_D2, mat->jc_D3, mat->jc_D4, mat->jc_D5, mat->jc_strain_rate_ref, s_star,
      eps_rate, T_star);
  return strength_johnson_cook_damage(D, deps_p, eps_f);
}

/** Second invariant J2 = S:S / 2 of a deviatoric stress (xx xy xz yy yz zz). */
BOLIDE_INLINE double strength_J2(const double S[6]) {
  return 0.5 * (S[0] * S[0] + S[3] * S[3] + S[5] * S[5]) + S[1] * S[1] + S[2] * S[2] + S[4] * S[4];
}

/** J2 radial return: if the equivalent stress sqrt(3 J2) exceeds Y, scale S
 *  by Y / sqrt(3 J2) (Wilkins 1964).  Returns the equivalent plastic strain
 *  of the return, (sqrt(3 J2) - Y) / (3 mu), or 0 in the elastic range. */
BOLIDE_INLINE double strength_radial_return(double S[6], double Y, double mu) {
  const double seq = sqrt(3.0 * strength_J2(S));
  if (!(seq > Y)) return 0.0;
  const double f = Y / seq;
  for (int k = 0; k < 6; k++) S[k] *= f;
  return mu > 0.0 ? (seq - Y) / (3.0 * mu) : 0.0;
}

#endif
