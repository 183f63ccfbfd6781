/* Gradient loop: the contribution of one neighbour j to the velocity-gradient
 * sums of particle i (solids).  Written once for the CPU loops and the CUDA
 * kernels; the symmetric CPU loop calls it for i and for j.
 *
 * With V_j = m_j / rho_j and grad_i W_ij = dW/dr (x_i - x_j) / r at h_i
 * (theory/solids.md, eqs. E1-E3; Randles & Libersky 1996, Sec. 3;
 * Schaefer et al. 2016, Sec. 3):
 *   M_i^{ab} = sum_j V_j (x_j - x_i)^a d_b W_ij        (symmetric)
 *   G_i^{ab} = sum_j V_j (v_j - v_i)^a d_b W_ij
 * and the corrected gradient dv^a/dx^b = G_i^{ac} (M_i^{-1})^{cb}
 * (gradient_finish.h), exact for a linear velocity field; and the kernel
 * sum of the free-surface detection (theory/fluids.md)
 *   Z_i = sum_j V_j W_ij(h_i)   (the self term added by the extra ghost). */
#ifndef BOLIDE_GRADIENT_IACT_H
#define BOLIDE_GRADIENT_IACT_H

#include <math.h>

#include "src/inline.h"
#include "tasks/hydro/kernel.h"

/** Accumulators of the gradient loop for one particle. */
struct gradient_acc {
  double M[6]; /**< correction-tensor sum, components xx xy xz yy yz zz */
  double G[9]; /**< velocity-difference sum, row-major (a = velocity component) */
  double Z;    /**< kernel sum sum_j V_j W_ij (free-surface detection), without the self term */
};

/** Contribution of j (volume Vj = m_j / rho_j) at dx = x_i - x_j,
 *  r2 = |dx|^2 < H_i^2, dv = v_i - v_j, to particle i (inverse smoothing
 *  length hi_inv). */
BOLIDE_INLINE void gradient_iact(double r2, const double dx[3], double hi_inv, double Vj,
                                 const double dv[3], struct gradient_acc *acc) {
  if (!(r2 > 0.0)) return;
  const double r = sqrt(r2);
  double w, dw_dr, dw_dh;
  kernel_eval_r(r, hi_inv, &w, &dw_dr, &dw_dh);
  /* V_j (x_j - x_i)^a d_b W = -V_j dW/dr / r dx^a dx^b, likewise for v */
  const double f = -Vj * dw_dr / r;
  acc->M[0] += f * dx[0] * dx[0];
  acc->M[1] += f * dx[0] * dx[1];
  acc->M[2] += f * dx[0] * dx[2];
  acc->M[3] += f * dx[1] * dx[1];
  acc->M[4] += f * dx[1] * dx[2];
  acc->M[5] += f * dx[2] * dx[2];
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) acc->G[3 * a + b] += f * dv[a] * dx[b];
  acc->Z += Vj * w;
}

#endif
