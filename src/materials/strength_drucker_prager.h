/* Drucker-Prager strength: pressure-dependent yield Y = Y0 + mu_i P, capped at
 * the von Mises limit Y_M and never negative (Drucker & Prager 1952; in the
 * form of Jutzi 2015, Sec. 2, and Schaefer et al. 2016, Sec. 2.3).  Y is
 * used as the equivalent stress sqrt(3 J2) of the radial return. */
#ifndef BOLIDE_STRENGTH_DRUCKER_PRAGER_H
#define BOLIDE_STRENGTH_DRUCKER_PRAGER_H

#include "src/inline.h"

/** Y = min(Y0 + friction P, Y_M), >= 0, for pressure P. */
BOLIDE_INLINE double strength_drucker_prager_yield(double Y0, double friction, double Y_M,
                                                   double P) {
  double Y = Y0 + friction * P;
  if (Y > Y_M) Y = Y_M;
  return Y > 0.0 ? Y : 0.0;
}

#endif
