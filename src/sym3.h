/* Symmetric 3x3 tensors stored as 6 numbers, in the order of the particle
 * fields and the snapshots (src/part.h: xx xy xz yy yz zz), and their
 * eigen-decomposition.  Written once for CPU and GPU (compiles as C11 and
 * as CUDA C++): the principal stress of the damage model
 * (tasks/damage/damage_iact.h) and the principal frame of the artificial
 * stress (tasks/gradient/gradient_finish.h) both call sym3_eigen. */
#ifndef BOLIDE_SYM3_H
#define BOLIDE_SYM3_H

#include <math.h>

#include "src/inline.h"

/** Components of a symmetric 3x3 tensor stored as 6 numbers. */
enum sym3_comp {
  SYM3_XX = 0,
  SYM3_XY = 1,
  SYM3_XZ = 2,
  SYM3_YY = 3,
  SYM3_YZ = 4,
  SYM3_ZZ = 5,
};

/** Largest number of Jacobi sweeps (convergence is quadratic: 4 to 6 suffice
 *  for doubles; the bound only guards against NaN input). */
#define SYM3_JACOBI_MAX_SWEEPS 32

/** Eigen-decomposition of the symmetric matrix a (6 components, enum
 *  sym3_comp) by cyclic Jacobi rotations (Golub & Van Loan 2013, Sect. 8.5;
 *  Press et al. 2007, Sect. 11.1).  Jacobi is used rather than the
 *  closed-form cubic because it stays accurate to rounding for repeated and
 *  nearly repeated eigenvalues, where the trigonometric formula loses half
 *  the digits.  The matrix is scaled by its largest |entry| so that squares
 *  neither overflow nor underflow; the sweeps stop when the off-diagonal
 *  entries are below 1e-18 of the diagonal (in the 1-norm: below rounding).
 *  lam: eigenvalues in descending order; q (may be NULL): 3x3 row-major,
 *  q[3 r + c] holds component r of the eigenvector of lam[c], so that
 *  a = Q diag(lam) Q^T.  Returns the number of sweeps used. */
BOLIDE_INLINE int sym3_eigen(const double a_in[6], double lam[3], double *q) {
  double a[3][3], v[3][3];
  double scale = 0.0;
  for (int k = 0; k < 6; k++)
    if (fabs(a_in[k]) > scale) scale = fabs(a_in[k]);
  const double inv = scale > 0.0 ? 1.0 / scale : 0.0;
  a[0][0] = a_in[SYM3_XX] * inv;
  a[1][1] = a_in[SYM3_YY] * inv;
  a[2][2] = a_in[SYM3_ZZ] * inv;
  a[0][1] = a[1][0] = a_in[SYM3_XY] * inv;
  a[0][2] = a[2][0] = a_in[SYM3_XZ] * inv;
  a[1][2] = a[2][1] = a_in[SYM3_YZ] * inv;
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) v[r][c] = r == c ? 1.0 : 0.0;

  int sweep = 0;
  for (; sweep < SYM3_JACOBI_MAX_SWEEPS; sweep++) {
    const double off = fabs(a[0][1]) + fabs(a[0][2]) + fabs(a[1][2]);
    const double diag = fabs(a[0][0]) + fabs(a[1][1]) + fabs(a[2][2]);
    if (!(off > 1e-18 * diag) || off == 0.0) break; /* also stops on NaN */
    for (int p = 0; p < 2; p++)
      for (int r = p + 1; r < 3; r++) {
        const double apr = a[p][r];
        if (apr == 0.0) continue;
        /* rotation angle zeroing a[p][r]: theta = cot(2 phi), t = tan(phi),
         * the smaller root (Golub & Van Loan 2013, Alg. 8.5.1) */
        const double theta = (a[r][r] - a[p][p]) / (2.0 * apr);
        const double t = (theta >= 0.0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
        const double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 3; k++) { /* A <- A J (columns p, r) */
          const double akp = a[k][p], akr = a[k][r];
          a[k][p] = c * akp - s * akr;
          a[k][r] = s * akp + c * akr;
        }
        for (int k = 0; k < 3; k++) { /* A <- J^T A (rows p, r) */
          const double apk = a[p][k], ark = a[r][k];
          a[p][k] = c * apk - s * ark;
          a[r][k] = s * apk + c * ark;
        }
        a[p][r] = a[r][p] = 0.0;
        for (int k = 0; k < 3; k++) { /* V <- V J */
          const double vkp = v[k][p], vkr = v[k][r];
          v[k][p] = c * vkp - s * vkr;
          v[k][r] = s * vkp + c * vkr;
        }
      }
  }
  /* sort descending (three elements: bubble by swaps) */
  int idx[3] = {0, 1, 2};
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2 - i; j++)
      if (a[idx[j]][idx[j]] < a[idx[j + 1]][idx[j + 1]]) {
        const int tmp = idx[j];
        idx[j] = idx[j + 1];
        idx[j + 1] = tmp;
      }
  for (int c = 0; c < 3; c++) {
    lam[c] = a[idx[c]][idx[c]] * scale;
    if (q)
      for (int r = 0; r < 3; r++) q[3 * r + c] = v[r][idx[c]];
  }
  return sweep;
}

/** Largest eigenvalue of the symmetric tensor a (6 components). */
BOLIDE_INLINE double sym3_max_eigenvalue(const double a[6]) {
  double lam[3];
  sym3_eigen(a, lam, (double *)0);
  return lam[0];
}

#endif
