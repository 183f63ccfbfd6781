/* Porous materials in the time step (theory/porosity.md, "Engine"): the
 * equation of state of a porous particle from its matrix EOS, the partial
 * derivatives of the matrix EOS that the P-alpha rate needs, the rate
 * dalpha/dt of a particle and the return to the crush curve.  The model
 * formulas are in porosity_palpha.h; this header joins them to a material
 * (material.h), which porosity.h cannot include.  Shared by CPU and GPU.
 *
 * A particle carries the distention alpha = rho_s / rho >= 1.  Its pressure
 * is P = P_s(alpha rho, u) / alpha with P_s the material's own EOS (the
 * matrix) and its sound speed c_s(alpha rho, u) h(alpha) (Jutzi et al. 2008
 * eqs. 4 and sect. 2.4; PA1, PA8). */
#ifndef BOLIDE_POROSITY_EOS_H
#define BOLIDE_POROSITY_EOS_H

#include <math.h>

#include "src/inline.h"
#include "src/materials/material.h"

/** Relative step of the centred differences of porosity_matrix_partials. */
#define POROSITY_DIFF_STEP 1e-6
/** Largest number of iterations of the return to the crush curve (PA10;
 *  2-10 are typical, theory/porosity.md). */
#define POROSITY_RETURN_MAX_ITER 60

/** Pressure of the matrix EOS of mat at (rho_s, u) (material_eos without
 *  the sound speed). */
BOLIDE_INLINE double porosity_matrix_pressure(const struct material *mat, double rho_s, double u) {
  double P, cs;
  material_eos(mat, rho_s, u, &P, &cs);
  return P;
}

/** The matrix EOS and its partial derivatives at (rho_s, u): P_s,
 *  dP_s/drho_s at constant u and dP_s/du at constant rho_s, by centred
 *  differences of material_eos (every EOS type, tables included; relative
 *  step 1e-6 in rho_s, and 1e-6 (|u| + c_s^2) in u, forward where u would
 *  turn negative).  cs: the matrix sound speed (floored as material_eos
 *  does). */
BOLIDE_INLINE void porosity_matrix_partials(const struct material *mat, double rho_s, double u,
                                            double *P, double *dP_drho, double *dP_du, double *cs) {
  material_eos(mat, rho_s, u, P, cs);
  const double hr = POROSITY_DIFF_STEP * rho_s;
  *dP_drho = (porosity_matrix_pressure(mat, rho_s + hr, u) -
              porosity_matrix_pressure(mat, rho_s - hr, u)) /
             (2.0 * hr);
  const double hu = POROSITY_DIFF_STEP * (fabs(u) + *cs * *cs) + 1e-300;
  if (u - hu >= 0.0)
    *dP_du = (porosity_matrix_pressure(mat, rho_s, u + hu) -
              porosity_matrix_pressure(mat, rho_s, u - hu)) /
             (2.0 * hu);
  else
    *dP_du = (porosity_matrix_pressure(mat, rho_s, u + hu) - *P) / hu;
}

/** Return a P-alpha state (bulk density rho, u, distention alpha) that lies
 *  above the crush curve to it (PA10: the root of alpha = alpha_cc(P_s(alpha
 *  rho, u)/alpha) in [1, alpha], by porosity_palpha_return_step).  Returns
 *  alpha unchanged for a state on or below the curve. */
BOLIDE_INLINE double porosity_palpha_return(const struct material *mat, double rho, double u,
                                            double alpha) {
  const struct porosity_palpha *pp = &mat->porosity.palpha;
  double Ps = porosity_matrix_pressure(mat, alpha * rho, u);
  if (!porosity_palpha_above_curve(pp, Ps / alpha, alpha)) return alpha;
  double lo = 1.0, hi = alpha;
  for (int k = 0; k < POROSITY_RETURN_MAX_ITER; k++) {
    const double rs = alpha * rho, hr = POROSITY_DIFF_STEP * rs;
    const double dPs =
        (porosity_matrix_pressure(mat, rs + hr, u) - porosity_matrix_pressure(mat, rs - hr, u)) /
        (2.0 * hr);
    const double a = porosity_palpha_return_step(pp, rho, alpha, Ps, dPs, &lo, &hi);
    if (a == alpha) return a;
    if (hi - lo <= 1e-14 * hi) return lo;
    alpha = a;
    Ps = porosity_matrix_pressure(mat, alpha * rho, u);
  }
  return lo;
}

/** Volumetric strain of an epsilon-alpha particle of bulk density rho
 *  (EA7): eps_v = ln(rho_00 / rho), rho_00 = rho0 / alpha_0 the bulk
 *  density of the unstressed porous material (negative in compression;
 *  d eps_v/dt = -drho/dt / rho = div v as in EA5). */
BOLIDE_INLINE double porosity_epsalpha_strain(const struct material *mat, double rho) {
  return log(mat->rho0 / (mat->porosity.epsalpha.alpha_0 * rho));
}

/** The distention of an epsilon-alpha particle of bulk density rho that
 *  had alpha: min(alpha, alpha(eps_v)) (EA6: alpha is a function of the
 *  strain, compaction is irreversible). */
BOLIDE_INLINE double porosity_epsalpha_update(const struct material *mat, double rho,
                                              double alpha) {
  const double a =
      porosity_epsalpha_alpha(&mat->porosity.epsalpha, porosity_epsalpha_strain(mat, rho));
  return a < alpha ? a : alpha;
}

/** Equation of state of a particle of material mat with bulk density rho,
 *  specific energy u and distention *alpha: for a P-alpha material the
 *  state is first returned to the crush curve (PA10, *alpha updated), then
 *  P = P_s(alpha rho, u)/alpha (PA1) and cs = c_s(alpha rho, u) h(alpha)
 *  (PA8); for an epsilon-alpha material alpha follows the strain first
 *  (EA6), then P = P_s(alpha rho, u)/alpha and cs = c_s(alpha rho, u), the
 *  matrix's (EA8).  A material without porosity: material_eos (alpha
 *  untouched). */
BOLIDE_INLINE void porosity_eos(const struct material *mat, double rho, double u, double *alpha,
                                double *P, double *cs) {
  if (mat->porosity.model == POROSITY_EPSALPHA) {
    const double a = porosity_epsalpha_update(mat, rho, *alpha);
    double Ps;
    material_eos(mat, a * rho, u, &Ps, cs);
    *alpha = a;
    *P = porosity_pressure(a, Ps);
    return;
  }
  if (mat->porosity.model != POROSITY_PALPHA) {
    material_eos(mat, rho, u, P, cs);
    return;
  }
  const struct porosity_palpha *pp = &mat->porosity.palpha;
  const double a = porosity_palpha_return(mat, rho, u, *alpha);
  double Ps, cs_s;
  material_eos(mat, a * rho, u, &Ps, &cs_s);
  *alpha = a;
  *P = porosity_pressure(a, Ps);
  *cs = porosity_palpha_sound_speed(pp, a, cs_s);
}

/** dalpha/dt of a P-alpha particle on its elastic branch (PA6 with the
 *  slope PA7, P < p_e, when the material has c_e and c_s), from its bulk
 *  density rho and rate drho_dt (continuity equation of the force loop),
 *  its u and du_dt, and alpha; 0 on the crush curve and for other
 *  materials.  Never positive.
 *
 *  On the crush curve (p_e <= P < p_s) alpha is a function of the state,
 *  and porosity_palpha_return (PA10) puts it there exactly at the predicted
 *  state (ghost) and at the kicked state (end of the step).  Integrating
 *  PA6 there as well, which is tangent to the curve, adds nothing exact: the
 *  tangent extrapolation of alpha together with that of rho over a step
 *  undershoots the convex curve by O((drho/rho)^2), and with a stiff matrix
 *  (K ~ 1e10 Pa against crush pressures ~ 1e6 Pa) a relative error of 1e-3
 *  in alpha rho is a pressure error of tens of MPa, even tension in a
 *  body being compacted (theory/porosity.md, "Engine"). */
BOLIDE_INLINE double porosity_rate(const struct material *mat, double rho, double drho_dt, double u,
                                   double du_dt, double alpha) {
  if (mat->porosity.model != POROSITY_PALPHA || !(alpha > 1.0)) return 0.0;
  const struct porosity_palpha *pp = &mat->porosity.palpha;
  if (!(pp->c_s > 0.0 && pp->c_e > 0.0)) return 0.0; /* no elastic branch */
  double Ps, dr, du, cs;
  porosity_matrix_partials(mat, alpha * rho, u, &Ps, &dr, &du, &cs);
  if (!(Ps / alpha < pp->p_e)) return 0.0; /* crush curve: PA10 */
  return porosity_palpha_dalpha_dt(pp, rho, drho_dt, du_dt, alpha, Ps, dr, du);
}

#endif
