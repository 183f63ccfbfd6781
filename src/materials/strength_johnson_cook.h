/* Johnson & Cook (1983) flow stress:
 *   Y = (A + B eps_p^n) (1 + C ln(eps_rate / eps_rate_0)) (1 - T*^m),
 *   T* = (T - T_ref) / (T_melt - T_ref) clipped to [0, 1]
 * with the equivalent plastic strain eps_p and strain rate eps_rate; the
 * rate factor is not allowed below 1 (rates under the reference rate give
 * the quasi-static stress, as in most hydrocodes).
 *
 * Johnson & Cook (1985) fracture: the damage D = sum d eps_p / eps_f grows
 * with the plastic strain; the strain at fracture is
 *   eps_f = [D1 + D2 exp(D3 s*)] [1 + D4 ln(eps_rate / eps_rate_0)] [1 + D5 T*],
 * s* = sigma_m / sigma_eq = -P / sqrt(3 J2) the stress triaxiality, the rate
 * factor again not below 1; the material fractures when D reaches 1
 * (theory/solids.md E6f). */
#ifndef BOLIDE_STRENGTH_JOHNSON_COOK_H
#define BOLIDE_STRENGTH_JOHNSON_COOK_H

#include <math.h>

#include "src/inline.h"

/** Flow stress for plastic strain eps_p, strain rate eps_rate, temperature T. */
BOLIDE_INLINE double strength_johnson_cook_yield(double A, double B, double C, double m, double n,
                                                 double rate0, double T_ref, double T_melt,
                                                 double eps_p, double eps_rate, double T) {
  const double hard = A + (eps_p > 0.0 ? B * pow(eps_p, n) : 0.0);
  const double x = eps_rate / rate0;
  const double rate = x > 1.0 ? 1.0 + C * log(x) : 1.0;
  double Ts = (T - T_ref) / (T_melt - T_ref);
  if (Ts < 0.0) Ts = 0.0;
  if (Ts > 1.0) Ts = 1.0;
  const double therm = 1.0 - pow(Ts, m);
  return hard * rate * therm;
}

/** Johnson & Cook (1985) equivalent plastic strain at fracture for the
 *  stress triaxiality s_star = -P / sigma_eq, strain rate eps_rate and
 *  homologous temperature T_star (clipped to [0, 1]).  Returns a value
 *  >= 1e-6 (an eps_f <= 0 from a fit with D1 < 0 means immediate fracture
 *  within a step's plastic strain of 1e-6). */
BOLIDE_INLINE double strength_johnson_cook_failure_strain(double D1, double D2, double D3,
                                                          double D4, double D5, double rate0,
                                                          double s_star, double eps_rate,
                                                          double T_star) {
  const double x = eps_rate / rate0;
  const double rate = x > 1.0 ? 1.0 + D4 * log(x) : 1.0;
  if (T_star < 0.0) T_star = 0.0;
  if (T_star > 1.0) T_star = 1.0;
  const double eps_f = (D1 + D2 * exp(D3 * s_star)) * rate * (1.0 + D5 * T_star);
  return eps_f > 1e-6 ? eps_f : 1e-6;
}

/** Damage after a plastic strain increment deps_p at failure strain eps_f
 *  (Johnson & Cook 1985, D = sum deps_p / eps_f), capped at 1. */
BOLIDE_INLINE double strength_johnson_cook_damage(double D, double deps_p, double eps_f) {
  if (!(deps_p > 0.0)) return D;
  D += deps_p / eps_f;
  return D < 1.0 ? D : 1.0;
}

#endif
