/* Mohr-Coulomb strength in its J2 (Drucker-Prager-cone) form: Y = c + mu P
 * with the cohesion c and the coefficient of internal friction mu = tan(phi),
 * without the von Mises cap of Drucker-Prager unless Y_M > 0, never negative
 * (Coulomb 1776; Collins et al. 2004, damaged material;
 * Schaefer et al. 2016, Sec. 2.3). */
#ifndef BOLIDE_STRENGTH_MOHR_COULOMB_H
#define BOLIDE_STRENGTH_MOHR_COULOMB_H

#include "src/inline.h"

/** Y = max(0, c + friction P), capped at Y_M when Y_M > 0. */
BOLIDE_INLINE double strength_mohr_coulomb_yield(double c, double friction, double Y_M, double P) {
  double Y = c + friction * P;
  if (Y_M > 0.0 && Y > Y_M) Y = Y_M;
  return Y > 0.0 ? Y : 0.0;
}

#endif
