/* Damage: Grady-Kipp tensile fracture as Benz & Asphaug (1994, 1995) put it
 * into SPH and Schaefer et al. (2016) describe it, for one particle.
 * Written once for CPU and GPU (compiles as C11 and as CUDA C++).
 *
 * State of a particle (theory/damage.md):
 *   dcbrt   d^(1/3), the integrated variable (BA95; Schaefer et al. 2016)
 *   n_act   number of flaws activated so far (never decreases)
 *   n_tot   number of flaws the particle carries; its thresholds eps_j are a
 *           slice, sorted ascending, of one flat array (flaws.h)
 *
 * One update (damage_grady_kipp_update), once per step after the force task:
 *   1. sigma = -P_d I + (1 - d) S, the damage-reduced stress   (theory/damage.md D5)
 *   2. sigma_max, its largest principal stress (Jacobi, sym3_eigen in sym3.h)
 *   3. local strain eps = sigma_max / ((1 - d) E)          (D3)
 *   4. n_grow = #{j : eps_j < eps}; n_act = max(n_act, n_grow)   (D2)
 *   5. d(d^(1/3))/dt = n_grow c_g / R_s, c_g = 0.4 c_l    (D4)
 *   6. d <= n_act / n_tot, i.e. d^(1/3) <= (n_act/n_tot)^(1/3)   (D6)
 * The rate is constant for fixed n_grow, so step 5 is integrated exactly over
 * the step and step 6 caps it exactly: a particle whose damage has reached
 * its limiter stops changing, and damage does not dictate the time step once
 * it saturates (damage_timestep). */
#ifndef BOLIDE_DAMAGE_IACT_H
#define BOLIDE_DAMAGE_IACT_H

#include <math.h>
#include <stdint.h>

#include "src/inline.h"
#include "src/materials/material.h"
#include "src/sym3.h"

/** Young's modulus from the bulk and shear moduli, E = 9 K mu / (3K + mu)
 *  (Landau & Lifshitz, Theory of Elasticity, Sect. 5). */
BOLIDE_INLINE double damage_young_modulus(double K, double mu) {
  const double den = 3.0 * K + mu;
  return den > 0.0 ? 9.0 * K * mu / den : 0.0;
}

/** Crack growth speed c_g = 0.4 c_l, c_l = sqrt((K + 4/3 mu)/rho) the
 *  longitudinal elastic wave speed (Melosh et al. 1992; BA94;
 *  Schaefer et al. 2016; theory/damage.md D4). */
BOLIDE_INLINE double damage_crack_speed(double K, double mu, double rho) {
  return rho > 0.0 ? 0.4 * sqrt((K + 4.0 / 3.0 * mu) / rho) : 0.0;
}

/** Pressure seen by the material: tensile pressure (P < 0) is carried only by
 *  the intact fraction, P_d = (1 - d) P; compression is unchanged (BA94;
 *  Schaefer et al. 2016; theory/damage.md D5). */
BOLIDE_INLINE double damage_pressure(double d, double P) {
  return P < 0.0 ? (1.0 - d) * P : P;
}

/** Damage-reduced stress sigma = -P_d I + (1 - d) S (BA94; theory/damage.md D5), from the
 *  undamaged pressure P and deviatoric stress S (6 components, enum sym3_comp). */
BOLIDE_INLINE void damage_stress(double d, double P, const double S[6], double sigma[6]) {
  const double f = 1.0 - d, Pd = damage_pressure(d, P);
  sigma[SYM3_XX] = -Pd + f * S[SYM3_XX];
  sigma[SYM3_YY] = -Pd + f * S[SYM3_YY];
  sigma[SYM3_ZZ] = -Pd + f * S[SYM3_ZZ];
  sigma[SYM3_XY] = f * S[SYM3_XY];
  sigma[SYM3_XZ] = f * S[SYM3_XZ];
  sigma[SYM3_YZ] = f * S[SYM3_YZ];
}

/** Number of thresholds of the ascending array eps[0..n-1] strictly below x
 *  (binary search: O(log n)). */
BOLIDE_INLINE int32_t damage_count_below(const double *eps, int32_t n, double x) {
  int32_t lo = 0, hi = n; /* invariant: eps[<lo] < x, eps[>=hi] >= x */
  while (lo < hi) {
    const int32_t mid = lo + (hi - lo) / 2;
    if (eps[mid] < x)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

/** Limiter of d^(1/3): d <= n_act/n_tot (BA95; Schaefer et al. 2016;
 *  theory/damage.md D6), so that a particle with few active flaws cannot be
 *  fully damaged. */
BOLIDE_INLINE double damage_cbrt_max(int32_t n_act, int32_t n_tot) {
  if (n_tot <= 0) return 0.0;
  if (n_act >= n_tot) return 1.0;
  return cbrt((double)n_act / (double)n_tot);
}

/** Radius of the sphere of a particle's volume, (3 m / (4 pi rho))^(1/3):
 *  one choice of the crack-growth radius R_s of D4.  Schaefer et al. (2016)
 *  (miluphcuda) use the kernel support instead, a factor of about 2 to 3
 *  larger (growth correspondingly slower); the default recommended in
 *  theory/damage.md is the kernel support, to compare with their Nakamura
 *  results.  damage_grady_kipp_update takes R_s as an argument. */
BOLIDE_INLINE double damage_radius_volume(double m, double rho) {
  return rho > 0.0 ? cbrt(3.0 * m / (4.0 * M_PI * rho)) : 0.0;
}

/** One Grady-Kipp update of a particle over a step dt (see the header).
 *  P, S: undamaged pressure and deviatoric stress (6 components); E: Young's
 *  modulus; c_g: crack speed; R_s: crack-growth radius (D4); eps: the particle's
 *  n_tot flaw thresholds, ascending.  Updates *dcbrt (d^(1/3)) and *n_act.
 *  Returns the growth rate d(d^(1/3))/dt used in this step (0 when saturated
 *  or not in tension), for the time-step criterion. */
BOLIDE_INLINE double damage_grady_kipp_update(double P, const double S[6], double E, double c_g,
                                              double R_s, const double *BOLIDE_RESTRICT eps,
                                              int32_t n_tot, double dt, double *dcbrt,
                                              int32_t *n_act) {
  double x = *dcbrt;
  if (n_tot <= 0 || !(E > 0.0) || !(R_s > 0.0) || x >= 1.0) return 0.0;
  const double d = x * x * x;
  double sigma[6];
  damage_stress(d, P, S, sigma);
  const double smax = sym3_max_eigenvalue(sigma);
  if (!(smax > 0.0)) return 0.0;                /* no tension: no activation, no growth */
  const double strain = smax / ((1.0 - d) * E); /* D3 */
  const int32_t n_grow = damage_count_below(eps, n_tot, strain);
  if (n_grow > *n_act) *n_act = n_grow;
  const double xmax = damage_cbrt_max(*n_act, n_tot);
  if (n_grow == 0 || x >= xmax) return 0.0;
  const double rate = (double)n_grow * c_g / R_s; /* D4 */
  x += rate * dt;                                 /* exact: the rate is constant over the step */
  *dcbrt = x < xmax ? x : xmax;
  return rate;
}

/** The damage task's work for one particle of material mat: the update of
 *  damage_grady_kipp_update with E and c_g from the material's bulk and
 *  shear moduli and the particle's density, and R_s = H (the kernel
 *  support, theory/damage.md D4).  eps_all: the flat threshold array;
 *  first, n_tot: the particle's slice.  Updates *dcbrt, *n_act and *d
 *  (= dcbrt^3, the damage the force loop uses); returns the growth rate for
 *  damage_timestep.  Materials without Weibull parameters (weibull_k = 0)
 *  or without shear modulus take no damage. */
BOLIDE_INLINE double damage_update_particle(const struct material *mat, double rho, double H,
                                            double P, const double S[6],
                                            const double *BOLIDE_RESTRICT eps_all, int64_t first,
                                            int32_t n_tot, double dt, double *dcbrt, int32_t *n_act,
                                            double *d) {
  if (!(mat->weibull_k > 0.0) || !(mat->shear_modulus > 0.0)) return 0.0;
  const double K = mat->bulk_modulus, mu = mat->shear_modulus;
  const double rate =
      damage_grady_kipp_update(P, S, damage_young_modulus(K, mu), damage_crack_speed(K, mu, rho), H,
                               eps_all + first, n_tot, dt, dcbrt, n_act);
  *d = *dcbrt * *dcbrt * *dcbrt;
  return rate;
}

/** Time-step limit from damage: the step in which d grows by at most f (an
 *  absolute change: the damaged stress (1 - d) S then changes by at most f
 *  times the intact stress).  No limit (INFINITY) when the limiter is
 *  reached within that change (the growth of d^(1/3) is integrated exactly
 *  and capped there), when the rate is 0, or when d = 1, so that a particle
 *  saturates in at most about 1/f steps and is never pinned.  (A limit on
 *  the change relative to (1 - d) would shrink the step geometrically as d
 *  approaches 1: the pinning the issue reports of SWIFT's strength branch.) */
BOLIDE_INLINE double damage_timestep(double dcbrt, int32_t n_act, int32_t n_tot, double rate,
                                     double f) {
  if (!(rate > 0.0) || dcbrt >= 1.0) return INFINITY;
  const double d = dcbrt * dcbrt * dcbrt;
  const double xmax = damage_cbrt_max(n_act, n_tot);
  const double dmax = xmax * xmax * xmax;
  const double d_target = d + f;
  if (d_target >= dmax) return INFINITY;
  return (cbrt(d_target) - dcbrt) / rate;
}

/** Shear (compressive) damage of Collins et al. (2004) (theory/damage.md D8):
 *  damage accumulates with the plastic strain, dD_s = d eps_p / eps_f, where
 *  the strain at failure grows with pressure, eps_f = max(eps_fb, B (P - P_c))
 *  (Ivanov et al. 1997; Collins et al. 2004: eps_fb = 1e-4, B = 1e-11 Pa^-1,
 *  P_c = 3e8 Pa for rock).  Returns the new D_s (<= 1, never decreasing). */
BOLIDE_INLINE double damage_shear_update(double Ds, double deps_p, double P, double eps_fb,
                                         double B, double P_c) {
  if (!(deps_p > 0.0)) return Ds;
  double eps_f = B * (P - P_c);
  if (eps_f < eps_fb) eps_f = eps_fb;
  Ds += deps_p / eps_f;
  return Ds < 1.0 ? Ds : 1.0;
}

/** Total damage used to reduce the stress, min(1, d_tensile + D_shear)
 *  (Collins et al. 2004 combine the two; miluphcuda adds them likewise). */
BOLIDE_INLINE double damage_total(double d_tensile, double D_shear) {
  const double t = d_tensile + D_shear;
  return t < 1.0 ? t : 1.0;
}

#endif
