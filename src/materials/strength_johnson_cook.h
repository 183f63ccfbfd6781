/* Johnson & Cook (1983) flow stress:
 *   Y = (A + B eps_p^n) (1 + C ln(eps_rate / eps_rate_0)) (1 - T*^m),
 *   T* = (T - T_ref) / (T_melt - T_ref) clipped to [0, 1]
 * with the equivalent plastic strain eps_p and strain rate eps_rate; the
 * rate factor is not allowed below 1 (rates under the reference rate give
 * the quasi-static stress, as in most hydrocodes). */
#ifndef BOLIDE_STRENGTH_JOHNSON_COOK_H
#define BOLIDE_STRENGTH_JOHNSON_COOK_H

#include <math.h>

#include "inline.h"

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

#endif
