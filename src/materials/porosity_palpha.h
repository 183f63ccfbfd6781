/* P-alpha porosity model (Herrmann 1969, J. Appl. Phys. 40, 2490; Carroll &
 * Holt 1972, J. Appl. Phys. 43, 759; in SPH: Jutzi, Benz & Michel 2008,
 * Icarus 198, 242, "JBM08"; Jutzi et al. 2009, Icarus 201, 802; Schaefer et
 * al. 2016, A&A 590, A19, sect. 2.6).  Equations are numbered as in
 * theory/porosity.md (PA1-PA9).
 *
 * The distention alpha = rho_s / rho >= 1 (matrix over bulk density) is a
 * state variable.  The matrix (solid) EOS gives P_s(rho_s, u) and the bulk
 * pressure is (JBM08 eq. 4; PA1)
 *   P = P_s(alpha rho, u) / alpha.
 *
 * Crush curve alpha_cc(P) (the "steep" curve of Jutzi et al. 2009, eq. 1,
 * and Schaefer et al. 2016; PA2), passing through alpha_e at p_e:
 *   P <= p_e:        alpha_e                                  (elastic)
 *   p_e < P < p_t:   1 + (alpha_e - alpha_t) ((p_t - P)/(p_t - p_e))^n1
 *                      + (alpha_t - 1) ((p_s - P)/(p_s - p_e))^n2
 *   p_t <= P < p_s:  1 + (alpha_t - 1) ((p_s - P)/(p_s - p_e))^n2
 *   P >= p_s:        1                                        (compacted)
 * With p_t = p_e, alpha_t = alpha_e, n2 = 2 (the defaults) it is the
 * quadratic curve of JBM08 eq. 8:  1 + (alpha_e - 1) ((p_s - P)/(p_s - p_e))^2.
 * This is the unscaled form: miluphcuda multiplies the bracket by
 * (alpha_0 - 1)/(alpha_e - 1) so that the curve passes through alpha_0; here
 * alpha_0 (the initial distention) and alpha_e (the distention at p_e) are
 * separate, 1 <= alpha_e <= alpha_0, and the elastic branch connects them.
 *
 * Evolution (JBM08 eqs. 9-10; PA4-PA6): dalpha/dt = (dalpha/dP) dP/dt with
 * dP/dt taken from P = P_s(alpha rho, u)/alpha itself, which gives
 *   dalpha/dt = s (alpha drho/dt dP_s/drho_s + du/dt dP_s/du)
 *                 / (alpha + s (P - rho dP_s/drho_s))                 (PA6)
 * where s = dalpha/dP is the slope of the branch the particle is on:
 *   - plastic (p_e <= P < p_s and the state on the crush curve,
 *     alpha >= alpha_cc(P)): s = alpha_cc'(P)                         (PA3)
 *   - elastic (P < p_e, c_e and c_s given): s = alpha^2/K_s (1 - 1/h^2),
 *     h = 1 + (alpha - 1)(c_e - c_s)/(c_s (alpha_e - 1)) (JBM08 eq. 11;
 *     PA7), K_s = rho_s dP_s/drho_s the current matrix bulk modulus;
 *   - otherwise (below the crush curve after unloading, fully compacted):
 *     s = 0.
 * Compaction is irreversible: dalpha/dt > 0 is set to 0 (as in miluphcuda;
 * the elastic re-expansion of the pores on unloading is neglected), so
 * alpha never increases, and the caller keeps 1 <= alpha <= alpha_0
 * (porosity_clamp_alpha).
 *
 * Return to the curve (PA10): the rate PA6 only follows the curve; a state
 * above it (a shock that crosses p_e within one step, alpha_0 > alpha_e)
 * stays above it.  After each update the caller tests
 * porosity_palpha_above_curve and, if so, solves alpha = alpha_cc(P_s(alpha
 * rho, u)/alpha) at fixed rho, u with porosity_palpha_return_step (a
 * bracketed Newton iteration, the return mapping of plasticity).  The rate
 * alone lags the curve by one step's elastic pressure rise, |alpha_cc'| K_s
 * dt |div v| (first order); the return alone is exact on the curve.
 *
 * Sound speed (JBM08 sect. 2.4; PA8): c = c_matrix(rho_s, u) h(alpha), h
 * linear in alpha from 1 at alpha = 1 to c_e/c_s at alpha_e (constant above);
 * without c_e/c_s, h = 1: at fixed alpha the porous EOS has exactly the
 * matrix sound speed at (alpha rho, u) (theory/porosity.md PA9). */
#ifndef BOLIDE_POROSITY_PALPHA_H
#define BOLIDE_POROSITY_PALPHA_H

#include "src/materials/eos_common.h"

/* clang-format off */
#define POROSITY_PALPHA_PARAMS(X)                                                                      \
  X(porosity_palpha, alpha_0, "alpha_0", NAN, 1.0, 0, 100.0, MATERIAL_UNIT_NONE,                       \
    "initial distention alpha_0 = rho_s/rho (>= alpha_e)")                                             \
  X(porosity_palpha, alpha_e, "alpha_e", 0.0, 0.0, 0, 100.0, MATERIAL_UNIT_NONE,                       \
    "distention at the elastic limit p_e (0: alpha_0)")                                                \
  X(porosity_palpha, alpha_t, "alpha_t", 0.0, 0.0, 0, 100.0, MATERIAL_UNIT_NONE,                       \
    "distention parameter of the transition (0: alpha_e, the quadratic curve)")                        \
  X(porosity_palpha, p_e, "p_e", NAN, 0.0, 0, INFINITY, MATERIAL_UNIT_PRESSURE,                        \
    "elastic limit: compaction starts above p_e")                                                      \
  X(porosity_palpha, p_t, "p_t", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_PRESSURE,                        \
    "transition pressure between the two branches (0: p_e)")                                          \
  X(porosity_palpha, p_s, "p_s", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_PRESSURE,                        \
    "pressure of full compaction (alpha = 1)")                                                         \
  X(porosity_palpha, n1, "n1", 2.0, 0.0, 1, 100.0, MATERIAL_UNIT_NONE,                                 \
    "exponent of the branch p_e < P < p_t")                                                            \
  X(porosity_palpha, n2, "n2", 2.0, 0.0, 1, 100.0, MATERIAL_UNIT_NONE,                                 \
    "exponent of the (p_s - P) term (2: quadratic)")                                                   \
  X(porosity_palpha, c_s, "c_s", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_SPEED,                           \
    "sound speed of the solid matrix (0: no elastic compaction, c = c_matrix)")                       \
  X(porosity_palpha, c_e, "c_e", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_SPEED,                           \
    "elastic sound speed of the porous material at alpha_e (with c_s)")
/* clang-format on */

/** P-alpha parameters (members: see POROSITY_PALPHA_PARAMS; after
 *  porosity_finalize the 0 = "derived" defaults are filled in). */
struct porosity_palpha {
  POROSITY_PALPHA_PARAMS(EOS_PARAM_FIELD)
};

/** Crush curve alpha_cc(P) (PA2; Jutzi et al. 2009 eq. 1). */
BOLIDE_INLINE double porosity_palpha_crush_alpha(const struct porosity_palpha *p, double P) {
  if (P <= p->p_e) return p->alpha_e;
  if (P >= p->p_s) return 1.0;
  double a = 1.0 + (p->alpha_t - 1.0) * pow((p->p_s - P) / (p->p_s - p->p_e), p->n2);
  if (P < p->p_t) a += (p->alpha_e - p->alpha_t) * pow((p->p_t - P) / (p->p_t - p->p_e), p->n1);
  return a;
}

/** Slope dalpha_cc/dP of the crush curve (PA3); 0 outside (p_e, p_s). */
BOLIDE_INLINE double porosity_palpha_crush_slope(const struct porosity_palpha *p, double P) {
  if (P <= p->p_e || P >= p->p_s) return 0.0;
  const double ds = p->p_s - p->p_e;
  double s = -(p->alpha_t - 1.0) * p->n2 * pow((p->p_s - P) / ds, p->n2 - 1.0) / ds;
  if (P < p->p_t) {
    const double dt = p->p_t - p->p_e;
    s -= (p->alpha_e - p->alpha_t) * p->n1 * pow((p->p_t - P) / dt, p->n1 - 1.0) / dt;
  }
  return s;
}

/** Sound-speed ratio h(alpha) = c(alpha)/c_matrix (JBM08 sect. 2.4; PA8):
 *  linear from 1 at alpha = 1 to c_e/c_s at alpha_e, c_e/c_s above; 1
 *  without c_e, c_s. */
BOLIDE_INLINE double porosity_palpha_sound_ratio(const struct porosity_palpha *p, double alpha) {
  if (!(p->c_s > 0.0) || !(p->c_e > 0.0) || !(p->alpha_e > 1.0)) return 1.0;
  const double a = alpha < p->alpha_e ? (alpha > 1.0 ? alpha : 1.0) : p->alpha_e;
  return 1.0 + (a - 1.0) * (p->c_e - p->c_s) / (p->c_s * (p->alpha_e - 1.0));
}

/** Porous sound speed from the matrix sound speed at (alpha rho, u). */
BOLIDE_INLINE double porosity_palpha_sound_speed(const struct porosity_palpha *p, double alpha,
                                                 double cs_matrix) {
  return cs_matrix * porosity_palpha_sound_ratio(p, alpha);
}

/** Slope dalpha/dP of the elastic branch (JBM08 eq. 11; PA7):
 *  alpha^2 / K_s (1 - 1/h^2), <= 0 when c_e < c_s; K_s: matrix bulk modulus. */
BOLIDE_INLINE double porosity_palpha_elastic_slope(const struct porosity_palpha *p, double alpha,
                                                   double K_s) {
  const double h = porosity_palpha_sound_ratio(p, alpha);
  if (h == 1.0 || !(K_s > 0.0)) return 0.0;
  return alpha * alpha / K_s * (1.0 - 1.0 / (h * h));
}

/** dalpha/dP of the branch the state (P, alpha) is on: the crush curve when
 *  p_e <= P < p_s and alpha >= alpha_cc(P) (relative slack 1e-12), the
 *  elastic branch below p_e, 0 otherwise (PA3, PA7). */
BOLIDE_INLINE double porosity_palpha_slope(const struct porosity_palpha *p, double P, double alpha,
                                           double K_s) {
  if (!(alpha > 1.0)) return 0.0;
  if (P < p->p_e) return porosity_palpha_elastic_slope(p, alpha, K_s);
  if (P >= p->p_s) return 0.0;
  if (alpha < porosity_palpha_crush_alpha(p, P) * (1.0 - 1e-12)) return 0.0;
  return porosity_palpha_crush_slope(p, P);
}

/** dalpha/dt of the P-alpha model (JBM08 eq. 9-10; PA6).
 *  rho: bulk density, drho_dt: its rate (continuity equation), du_dt: rate
 *  of the specific internal energy, alpha: distention; P_s, dPs_drho_s,
 *  dPs_du: the matrix EOS and its partial derivatives at (rho_s = alpha rho,
 *  u), computed by the caller (no function pointers on the GPU).  Returns
 *  <= 0 (compaction is irreversible); 0 if the denominator of PA6 is not
 *  positive (a softening matrix EOS, outside the model's validity). */
BOLIDE_INLINE double porosity_palpha_dalpha_dt(const struct porosity_palpha *p, double rho,
                                               double drho_dt, double du_dt, double alpha,
                                               double P_s, double dPs_drho_s, double dPs_du) {
  const double P = P_s / alpha; /* PA1 */
  const double s = porosity_palpha_slope(p, P, alpha, alpha * rho * dPs_drho_s);
  if (s == 0.0) return 0.0;
  const double den = alpha + s * (P - rho * dPs_drho_s);
  if (!(den > 0.0)) return 0.0;
  const double r = s * (alpha * drho_dt * dPs_drho_s + du_dt * dPs_du) / den; /* PA6 */
  return r < 0.0 ? r : 0.0;
}

/** Whether the state (P, alpha) lies above the crush curve (P > p_e and
 *  alpha > alpha_cc(P)), which the rate PA6 cannot undo (a shock that
 *  crosses p_e within one step): then the caller returns it to the curve
 *  with porosity_palpha_return_step (PA10). */
BOLIDE_INLINE int porosity_palpha_above_curve(const struct porosity_palpha *p, double P,
                                              double alpha) {
  return P > p->p_e && alpha > 1.0 && alpha > porosity_palpha_crush_alpha(p, P);
}

/** One safeguarded Newton step of the return to the crush curve (PA10):
 *  the root of f(alpha) = alpha - alpha_cc(P_s(alpha rho, u)/alpha) at
 *  fixed rho, u.  f increases with alpha (f' = 1 - alpha_cc'(P) (rho
 *  dP_s/drho_s - P)/alpha >= 1 where the matrix stiffens), f(1) <= 0 and
 *  f(alpha_trial) > 0 for a state above the curve, so the root is bracketed
 *  by [*lo, *hi] = [1, alpha_trial] at the start.  f changes from alpha -
 *  alpha_e to alpha - 1 within a window of alpha of width about (p_s -
 *  p_e)/K_s, where plain Newton steps overshoot: the bracket is narrowed at
 *  every step and a step that leaves it is replaced by bisection.  P_s and
 *  dPs_drho_s at (alpha rho, u) from the caller.  Returns the next iterate,
 *  alpha itself once converged (Newton step below 1e-14 alpha); the caller
 *  re-evaluates the matrix EOS and repeats until the iterate stops changing
 *  or *hi - *lo < 1e-14 *hi (then *lo), typically 2-10 times and at most
 *  about 50 (theory/porosity.md). */
BOLIDE_INLINE double porosity_palpha_return_step(const struct porosity_palpha *p, double rho,
                                                 double alpha, double P_s, double dPs_drho_s,
                                                 double *lo, double *hi) {
  const double P = P_s / alpha;
  const double f = alpha - porosity_palpha_crush_alpha(p, P);
  if (f > 0.0)
    *hi = alpha;
  else
    *lo = alpha;
  if (f == 0.0) return alpha;
  double df = 1.0 - porosity_palpha_crush_slope(p, P) * (rho * dPs_drho_s - P) / alpha;
  if (!(df >= 1.0)) df = 1.0; /* softening matrix: the plain step alpha_cc(P) */
  const double a = alpha - f / df;
  if (fabs(a - alpha) <= 1e-14 * alpha) return alpha;    /* converged */
  if (a > *lo && a < *hi) return a;                      /* Newton */
  if (a <= 1.0 && *lo == 1.0 && alpha > 1.0) return 1.0; /* try full compaction */
  return 0.5 * (*lo + *hi);                              /* bisection */
}

#endif
