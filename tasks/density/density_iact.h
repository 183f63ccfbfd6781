/* Density loop: the contribution of one neighbour j to particle i.
 *
 * Written once, called by the CPU loops (tasks/density/density_cpu.c) and the
 * CUDA kernels.  The gather form updates only i; the symmetric CPU loop calls
 * it for i and for j.
 *
 * Sums (theory/sph.md, eqs. 1-4):
 *   rho_i    = sum_j m_j W(r_ij, h_i)                 (Monaghan 1992)
 *   n_i      = sum_j W(r_ij, h_i)                     number density, for h
 *   d rho/dh, d n/dh                                  grad-h terms (Springel & Hernquist 2002)
 *   rho_i div v_i  = - sum_j m_j (v_i - v_j) . grad_i W_ij(h_i)
 *   rho_i curl v_i =   sum_j m_j (v_i - v_j) x grad_i W_ij(h_i)
 * The self contribution (j = i) is added by density_self_term. */
#ifndef BOLIDE_DENSITY_IACT_H
#define BOLIDE_DENSITY_IACT_H

#include <math.h>

#include "src/inline.h"
#include "tasks/hydro/kernel.h"

/** Accumulators of the density loop for one particle. */
struct density_acc {
  double rho;       /**< sum m_j W */
  double rho_dh;    /**< sum m_j dW/dh */
  double wcount;    /**< sum W (number density) */
  double wcount_dh; /**< sum dW/dh */
  double div_v;     /**< - sum m_j dv . grad W (divide by rho) */
  double curl_v[3]; /**< sum m_j dv x grad W (divide by rho) */
};

/** Contribution of neighbour j (mass mj) at separation dx = x_i - x_j,
 *  r2 = |dx|^2, relative velocity dv = v_i - v_j, to particle i of inverse
 *  smoothing length hi_inv.  The caller guarantees r2 < (kernel_gamma hi)^2. */
BOLIDE_INLINE void density_iact(double r2, const double dx[3], double hi_inv, double mj,
                                const double dv[3], struct density_acc *acc) {
  const double r = sqrt(r2);
  double w, dw_dr, dw_dh;
  kernel_eval_r(r, hi_inv, &w, &dw_dr, &dw_dh);
  acc->rho += mj * w;
  acc->rho_dh += mj * dw_dh;
  acc->wcount += w;
  acc->wcount_dh += dw_dh;
  if (r > 0.0) {
    /* grad_i W = dW/dr * dx / r */
    const double f = mj * dw_dr / r;
    const double dvdx = dv[0] * dx[0] + dv[1] * dx[1] + dv[2] * dx[2];
    acc->div_v -= f * dvdx;
    acc->curl_v[0] += f * (dv[1] * dx[2] - dv[2] * dx[1]);
    acc->curl_v[1] += f * (dv[2] * dx[0] - dv[0] * dx[2]);
    acc->curl_v[2] += f * (dv[0] * dx[1] - dv[1] * dx[0]);
  }
}

/** The particle's own contribution (r = 0). */
BOLIDE_INLINE void density_self_term(double hi_inv, double mi, struct density_acc *acc) {
  double w, dw_dr, dw_dh;
  kernel_eval_r(0.0, hi_inv, &w, &dw_dr, &dw_dh);
  acc->rho += mi * w;
  acc->rho_dh += mi * dw_dh;
  acc->wcount += w;
  acc->wcount_dh += dw_dh;
}

#endif
