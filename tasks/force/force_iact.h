/* Force loop: the contribution of neighbour j to the accelerations, energy
 * and density rates of particle i (density-energy SPH with grad-h terms,
 * Monaghan 1997 viscosity with the Balsara 1995 switch, Price 2008
 * conduction).  Written once for the CPU loops and the CUDA kernels.
 *
 * theory/sph.md, eqs. 7-12:
 *   dv_i/dt = - sum_j m_j [ f_i P_i/rho_i^2 dW_ij(h_i) + f_j P_j/rho_j^2 dW_ij(h_j)
 *                           + Pi_ij (dW_ij(h_i) + dW_ij(h_j))/2 ] x_ij / r
 *   du_i/dt =   sum_j m_j [ f_i P_i/rho_i^2 v_ij.x_ij/r dW_ij(h_i)
 *                           + Pi_ij/2 v_ij.x_ij/r (dW_ij(h_i) + dW_ij(h_j))/2 ]
 *             + conduction
 *   drho_i/dt = sum_j m_j v_ij . x_ij / r dW_ij(h_i)
 * with Pi_ij = -alpha/2 (B_i + B_j)/2... (see force_iact below), dW = dW/dr.
 *
 * Every expression combines i and j terms with commutative operations only,
 * so that the gather form evaluated for (i, j) and for (j, i) gives forces
 * that are exact negatives of each other: momentum is conserved to round-off
 * whether the CPU loop is symmetric or gather. */
#ifndef BOLIDE_FORCE_IACT_H
#define BOLIDE_FORCE_IACT_H

#include <math.h>

#include "hydro_props.h"
#include "inline.h"
#include "kernel.h"

/** What the force loop reads of one particle. */
struct force_in {
  double m;       /**< mass */
  double h_inv;   /**< inverse smoothing length */
  double rho;     /**< density */
  double P;       /**< pressure */
  double cs;      /**< sound speed */
  double u;       /**< specific internal energy (conduction) */
  double f;       /**< grad-h factor f = 1 / (1 + h/(3 rho) drho/dh) */
  double balsara; /**< Balsara switch value (1 when the switch is off) */
};

/** Accumulators of the force loop for one particle. */
struct force_acc {
  double a[3];    /**< acceleration */
  double du_dt;   /**< rate of change of specific internal energy */
  double drho_dt; /**< rate of change of density (continuity equation) */
  double v_sig;   /**< largest signal velocity met */
};

/** Contribution of j to i.  dx = x_i - x_j, dv = v_i - v_j, r2 = |dx|^2 > 0,
 *  and r < max(H_i, H_j).  hp: viscosity and conduction constants. */
BOLIDE_INLINE void force_iact(double r2, const double dx[3], const double dv[3],
                              const struct force_in *pi, const struct force_in *pj,
                              const struct hydro_props *hp, struct force_acc *acc) {
  const double r = sqrt(r2);
  const double r_inv = 1.0 / r;

  double wi, wi_dr, wi_dh, wj, wj_dr, wj_dh;
  kernel_eval_r(r, pi->h_inv, &wi, &wi_dr, &wi_dh);
  kernel_eval_r(r, pj->h_inv, &wj, &wj_dr, &wj_dh);

  const double dvdr = dv[0] * dx[0] + dv[1] * dx[1] + dv[2] * dx[2];

  /* Monaghan (1997) viscosity with signal velocity; only approaching pairs */
  const double mu_ij = (dvdr < 0.0 ? dvdr : 0.0) * r_inv;
  const double v_sig = pi->cs + pj->cs - hp->beta * mu_ij;
  const double rho_ij = 0.5 * (pi->rho + pj->rho);
  const double visc = -0.25 * hp->alpha * v_sig * mu_ij * (pi->balsara + pj->balsara) / rho_ij;
  const double w_mean_dr = 0.5 * (wi_dr + wj_dr);

  /* pressure terms with grad-h corrections (Springel & Hernquist 2002) */
  const double Pi_rho2 = pi->f * pi->P / (pi->rho * pi->rho);
  const double Pj_rho2 = pj->f * pj->P / (pj->rho * pj->rho);
  const double acc_term = (Pi_rho2 * wi_dr + Pj_rho2 * wj_dr + visc * w_mean_dr) * r_inv;

  acc->a[0] -= pj->m * acc_term * dx[0];
  acc->a[1] -= pj->m * acc_term * dx[1];
  acc->a[2] -= pj->m * acc_term * dx[2];

  /* energy: PdV work of i plus half the viscous heating */
  const double du = (Pi_rho2 * wi_dr + 0.5 * visc * w_mean_dr) * dvdr * r_inv;
  acc->du_dt += pj->m * du;

  /* artificial conduction (Price 2008, eq. 28) with v_sig^u = sqrt(|dP|/rho_ij) */
  if (hp->alpha_u > 0.0) {
    const double vsig_u = sqrt(fabs(pi->P - pj->P) / rho_ij);
    acc->du_dt += pj->m * hp->alpha_u * vsig_u * (pi->u - pj->u) / rho_ij * w_mean_dr;
  }

  /* continuity equation, grad W at h_i */
  acc->drho_dt += pj->m * dvdr * r_inv * wi_dr;

  if (v_sig > acc->v_sig) acc->v_sig = v_sig;
}

#endif
