/* What the extra ghost does for one solid particle once its gradient sums
 * are complete (theory/solids.md): invert the correction tensor, form the
 * strain rate and rotation rate, bring the stress back to the yield surface,
 * evaluate Hooke's law with the Jaumann rate, and the artificial stress.
 * Plain functions of small arrays, shared by CPU and GPU. */
#ifndef BOLIDE_GRADIENT_FINISH_H
#define BOLIDE_GRADIENT_FINISH_H

#include <math.h>

#include "src/inline.h"
#include "src/sym3.h"

/** Inverse of the symmetric matrix M (xx xy xz yy yz zz) as a full 3x3
 *  row-major Minv.  Returns 0, or -1 (Minv = identity) when M is singular
 *  or badly conditioned: |det M| below 1e-6 of the product of its diagonal
 *  (a particle with too few or coplanar neighbours, where the uncorrected
 *  gradient is the safer choice; Schaefer et al. 2016, Sec. 3.3). */
BOLIDE_INLINE int gradient_invert_sym(const double M[6], double Minv[9]) {
  const double a = M[0], b = M[1], c = M[2], d = M[3], e = M[4], f = M[5];
  const double A = d * f - e * e, B = c * e - b * f, C = b * e - c * d;
  const double det = a * A + b * B + c * C;
  const double diag = fabs(a * d * f);
  if (!(fabs(det) > 1e-6 * diag) || !(diag > 0.0)) {
    for (int k = 0; k < 9; k++) Minv[k] = (k % 4 == 0) ? 1.0 : 0.0;
    return -1;
  }
  const double id = 1.0 / det;
  Minv[0] = A * id;
  Minv[1] = Minv[3] = B * id;
  Minv[2] = Minv[6] = C * id;
  Minv[4] = (a * f - c * c) * id;
  Minv[5] = Minv[7] = (b * c - a * e) * id;
  Minv[8] = (a * d - b * b) * id;
  return 0;
}

/** gv = G Minv (3x3 row-major): the corrected velocity gradient dv^a/dx^b. */
BOLIDE_INLINE void gradient_apply(const double G[9], const double Minv[9], double gv[9]) {
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      gv[3 * a + b] = G[3 * a] * Minv[b] + G[3 * a + 1] * Minv[3 + b] + G[3 * a + 2] * Minv[6 + b];
}

/** CSPM continuity equation (theory/solids.md eq. E14; Chen, Beraun & Carney
 *  1999; Eghtesad & Knezevic 2018): the density rate of a particle from the
 *  divergence of its corrected velocity gradient,
 *    drho_i/dt = -rho_i (G_i M_i^{-1})^{aa},
 *  with the sums M (symmetric, xx xy xz yy yz zz) and G (row-major) of the
 *  gradient loop (gradient_iact.h).  Exact for a linear velocity field on
 *  any particle set where M is invertible; where it is not (gradient_invert_sym
 *  returns -1) the uncorrected divergence tr G is used. */
BOLIDE_INLINE double gradient_cspm_drho_dt(double rho, const double M[6], const double G[9]) {
  double Minv[9];
  gradient_invert_sym(M, Minv);
  /* tr(G Minv) = G^{ac} Minv^{ca} */
  double div = 0.0;
  for (int a = 0; a < 3; a++)
    for (int c = 0; c < 3; c++) div += G[3 * a + c] * Minv[3 * c + a];
  return -rho * div;
}

/** Hooke's law with the Jaumann rate (theory/solids.md eq. E5; Gray et al. 2001,
 *  Sec. 2; Benz & Asphaug 1994, Sec. 2; Schaefer et al. 2016, Sec. 2.2):
 *    dS/dt = 2 mu (e - tr(e)/3 I) + Omega S - S Omega
 *  with e = (gv + gv^T)/2 and Omega = (gv - gv^T)/2, gv^{ab} = dv^a/dx^b.
 *  S and dS are symmetric (xx xy xz yy yz zz).  Returns the equivalent
 *  strain rate sqrt(2/3 e':e'). */
BOLIDE_INLINE double gradient_stress_rate(const double gv[9], const double S[6], double mu,
                                          double dS[6]) {
  double e[9], W[9], Sf[9];
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) {
      e[3 * a + b] = 0.5 * (gv[3 * a + b] + gv[3 * b + a]);
      W[3 * a + b] = 0.5 * (gv[3 * a + b] - gv[3 * b + a]);
    }
  Sf[0] = S[0], Sf[1] = Sf[3] = S[1], Sf[2] = Sf[6] = S[2];
  Sf[4] = S[3], Sf[5] = Sf[7] = S[4], Sf[8] = S[5];
  const double tr3 = (e[0] + e[4] + e[8]) / 3.0;
  const int ia[6] = {0, 0, 0, 1, 1, 2}, ib[6] = {0, 1, 2, 1, 2, 2}; /* no statics: device code */
  double ee = 0.0;
  for (int k = 0; k < 6; k++) {
    const int a = ia[k], b = ib[k];
    const double ed = e[3 * a + b] - (a == b ? tr3 : 0.0);
    ee += (a == b ? 1.0 : 2.0) * ed * ed;
    double rot = 0.0;
    for (int c = 0; c < 3; c++) rot += W[3 * a + c] * Sf[3 * c + b] - Sf[3 * a + c] * W[3 * c + b];
    dS[k] = 2.0 * mu * ed + rot;
  }
  return sqrt(2.0 / 3.0 * ee);
}

/** Artificial stress R/rho^2 of a particle with total stress sigma = -P I + S
 *  (theory/solids.md eq. E10; Monaghan 2000, Sec. 4; Gray et al. 2001, Sec. 4): in the
 *  principal frame (sym3_eigen) R'^{aa} = -eps sigma'^{aa} / rho^2 where sigma'^{aa} > 0
 *  (tension), 0 otherwise; rotated back to the simulation frame. */
BOLIDE_INLINE void gradient_artificial_stress(const double S[6], double P, double rho, double eps,
                                              double R[6]) {
  const double sig[6] = {S[0] - P, S[1], S[2], S[3] - P, S[4], S[5] - P};
  double lam[3], Q[9];
  sym3_eigen(sig, lam, Q);
  double r[3];
  for (int k = 0; k < 3; k++) r[k] = lam[k] > 0.0 ? -eps * lam[k] / (rho * rho) : 0.0;
  const int ia[6] = {0, 0, 0, 1, 1, 2}, ib[6] = {0, 1, 2, 1, 2, 2}; /* no statics: device code */
  for (int k = 0; k < 6; k++) {
    const int a = ia[k], b = ib[k];
    R[k] = Q[3 * a] * r[0] * Q[3 * b] + Q[3 * a + 1] * r[1] * Q[3 * b + 1] +
           Q[3 * a + 2] * r[2] * Q[3 * b + 2];
  }
}

#endif
