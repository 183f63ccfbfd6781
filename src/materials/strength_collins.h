/* Collins, Melosh & Ivanov (2004, MAPS 39, 217) rock strength:
 *   intact  Y_i = Y0 + mu_i P / (1 + mu_i P / (Y_M - Y0))      (Lundborg 1968 form)
 *   damaged Y_d = c_d + mu_d P, with Y_d <= Y_i                 (damaged curve)
 *   Y = (1 - D) Y_i + D Y_d                                     (blend)
 * In tension (P < 0) the intact curve is continued linearly, Y_i = Y0 + mu_i P
 * (its slope at P = 0), and both curves are clipped at zero. */
#ifndef BOLIDE_STRENGTH_COLLINS_H
#define BOLIDE_STRENGTH_COLLINS_H

#include "src/inline.h"

/** Yield stress at pressure P and damage D (0: intact, 1: fully damaged). */
BOLIDE_INLINE double strength_collins_yield(double Y0, double mu_i, double Y_M, double c_d,
                                            double mu_d, double P, double D) {
  double Yi;
  if (P > 0.0 && Y_M > Y0)
    Yi = Y0 + mu_i * P / (1.0 + mu_i * P / (Y_M - Y0));
  else
    Yi = Y0 + mu_i * P;
  if (Yi < 0.0) Yi = 0.0;
  double Yd = c_d + mu_d * P;
  if (Yd > Yi) Yd = Yi;
  if (Yd < 0.0) Yd = 0.0;
  return (1.0 - D) * Yi + D * Yd;
}

#endif
