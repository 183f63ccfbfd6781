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
 *   drho_i/dt = sum_j m_j v_ij . x_ij / r dW_ij(h_i)   (not with the CSPM option)
 * with Pi_ij = -alpha/2 (B_i + B_j)/2... (see force_iact below), dW = dW/dr.
 *
 * Solids (hp->solids; theory/solids.md, eqs. E8-E12): sigma = -P I + S, the
 * deviatoric stress S adds to the momentum and energy equations
 *   standard:  dv_i^a/dt += sum_j m_j (S_i^{ab}/rho_i^2 d_b W(h_i) + S_j^{ab}/rho_j^2 d_b W(h_j))
 *              du_i/dt   -= sum_j m_j S_i^{ab}/rho_i^2 v_ij^a d_b W(h_i)
 *              (Gray et al. 2001, Sec. 3; Benz & Asphaug 1994, Sec. 2)
 *   symmetric: (sigma_i + sigma_j)/(rho_i rho_j) with the mean kernel
 *              gradient, pressure included (Monaghan 1992, Sec. 3;
 *              Schaefer et al. 2016, Sec. 3)
 * plus the artificial stress m_j f_ij^n (R_i + R_j) . grad W with
 * f_ij = W(r, h_ij) / W(dp, h_ij) (Monaghan 2000, Sec. 4; Gray et al. 2001,
 * Sec. 4) and its energy term, and the XSPH sum
 *   xsph_i = sum_j m_j / rho_ij (v_j - v_i) W_ij   (Monaghan 1989).
 *
 * A pair of a fluid and a solid particle with SPH:fluid_solid_interface
 * (theory/fluids.md F6-F8): the symmetric form whatever SPH:momentum_form,
 * pressures below zero taken as zero (no tension across the interface).
 *
 * Every expression combines i and j terms with commutative operations only,
 * so that the gather form evaluated for (i, j) and for (j, i) gives forces
 * that are exact negatives of each other: momentum is conserved to round-off
 * whether the CPU loop is symmetric or gather. */
#ifndef BOLIDE_FORCE_IACT_H
#define BOLIDE_FORCE_IACT_H

#include <math.h>

#include "tasks/hydro/hydro_props.h"
#include "src/inline.h"
#include "tasks/hydro/kernel.h"

/** What the force loop reads of one particle. */
struct force_in {
  double m;       /**< mass */
  double h_inv;   /**< inverse smoothing length */
  double rho;     /**< density */
  double P;       /**< pressure */
  double cs;      /**< sound speed */
  double cl;      /**< longitudinal wave speed of a solid (= cs for fluids): the time step's */
  double u;       /**< specific internal energy (conduction) */
  double f;       /**< grad-h factor f = 1 / (1 + h/(3 rho) drho/dh) */
  double balsara; /**< Balsara switch value (1 when the switch is off) */
  double h;       /**< smoothing length (artificial stress) */
  double S[6];    /**< predicted deviatoric stress (xx xy xz yy yz zz), 0 for fluids */
  double R[6];    /**< artificial stress R / rho^2 (Monaghan 2000), 0 when off */
  int solid;      /**< 1: a material with strength (PART_SOLID), 0: a fluid */
};

/** Accumulators of the force loop for one particle. */
struct force_acc {
  double a[3];    /**< acceleration */
  double du_dt;   /**< rate of change of specific internal energy */
  double drho_dt; /**< rate of change of density (continuity equation) */
  double v_sig;   /**< largest signal velocity met, with the longitudinal speeds (time step) */
  double xsph[3]; /**< XSPH sum m_j/rho_ij (v_j - v_i) W_ij (Monaghan 1989) */
};

/** Zero force accumulators. */
BOLIDE_INLINE void force_acc_zero(struct force_acc *a) {
  a->a[0] = a->a[1] = a->a[2] = 0.0;
  a->du_dt = a->drho_dt = a->v_sig = 0.0;
  a->xsph[0] = a->xsph[1] = a->xsph[2] = 0.0;
}

/** y = T x for a symmetric tensor T (xx xy xz yy yz zz). */
BOLIDE_INLINE void force_sym_dot(const double T[6], const double x[3], double y[3]) {
  y[0] = T[0] * x[0] + T[1] * x[1] + T[2] * x[2];
  y[1] = T[1] * x[0] + T[3] * x[1] + T[4] * x[2];
  y[2] = T[2] * x[0] + T[4] * x[1] + T[5] * x[2];
}

/** What one interacting pair (i, j) shares between its two sides: the
 *  kernels at h_i (index 0) and h_j (index 1) and every term that is the
 *  same, bit for bit, whichever particle the pair is seen from (each is
 *  combined from i's and j's values with commutative operations only). */
struct force_pair {
  double r, r_inv;      /**< separation and its inverse */
  double dvdr;          /**< v_ij . x_ij */
  double w[2], w_dr[2]; /**< W and dW/dr at h_i and at h_j */
  double w_mean_dr;     /**< (dW/dr(h_i) + dW/dr(h_j)) / 2 */
  double mu_ij;         /**< min(v_ij . x_ij, 0) / r */
  double rho_ij;        /**< mean density */
  double visc;          /**< the viscous term Pi_ij */
  double P[2];     /**< the pressures the pair uses (no tension across a fluid-solid interface) */
  double Prho2[2]; /**< f P / rho^2 of each side (the asymmetric form's pressure terms) */
  double rr_inv;   /**< 1 / (rho_i rho_j) */
  double acc_term; /**< the radial acceleration term: i gets -m_j acc_term x_ij, j its opposite */
  double v_sig_dt; /**< the time step's signal velocity (longitudinal speeds) */
  int sym;         /**< the symmetric momentum form applies to this pair */
};

/** The shared terms of the pair (i, j): dx = x_i - x_j, dv = v_i - v_j,
 *  r2 = |dx|^2 > 0, and r < max(H_i, H_j).  hp: viscosity constants. */
BOLIDE_INLINE void force_pair_eval(double r2, const double dx[3], const double dv[3],
                                   const struct force_in *pi, const struct force_in *pj,
                                   const struct hydro_props *hp, struct force_pair *pr) {
  const double r = sqrt(r2);
  const double r_inv = 1.0 / r;
  pr->r = r;
  pr->r_inv = r_inv;

  double wi_dh, wj_dh;
  kernel_eval_r(r, pi->h_inv, &pr->w[0], &pr->w_dr[0], &wi_dh);
  kernel_eval_r(r, pj->h_inv, &pr->w[1], &pr->w_dr[1], &wj_dh);
  (void)wi_dh;
  (void)wj_dh;

  const double dvdr = dv[0] * dx[0] + dv[1] * dx[1] + dv[2] * dx[2];
  pr->dvdr = dvdr;

  /* Monaghan (1997) viscosity with signal velocity; only approaching pairs */
  const double mu_ij = (dvdr < 0.0 ? dvdr : 0.0) * r_inv;
  pr->mu_ij = mu_ij;
  const double v_sig = pi->cs + pj->cs - hp->beta * mu_ij;
  pr->rho_ij = 0.5 * (pi->rho + pj->rho);
  pr->visc = -0.25 * hp->alpha * v_sig * mu_ij * (pi->balsara + pj->balsara) / pr->rho_ij;
  pr->w_mean_dr = 0.5 * (pr->w_dr[0] + pr->w_dr[1]);

  /* fluid-solid interface (SPH:fluid_solid_interface; theory/fluids.md
   * F6-F8): a pair of a fluid and a solid particle, met only by particles
   * whose kernel holds both phases, takes the solid's pressure and
   * deviatoric stress against the fluid's pressure and viscous stress in
   * the form (sigma_i + sigma_j)/(rho_i rho_j), which a uniform stress
   * leaves without force across the density jump, and carries no tension
   * across the unbonded interface (P at least 0 on both sides) */
  const int cross = hp->fluid_solid_interface && pi->solid != pj->solid;
  pr->P[0] = cross && pi->P < 0.0 ? 0.0 : pi->P;
  pr->P[1] = cross && pj->P < 0.0 ? 0.0 : pj->P;
  pr->sym = hp->momentum_form == HYDRO_MOMENTUM_SYMMETRIC || cross;

  if (pr->sym) {
    /* (P_i + P_j) / (rho_i rho_j) with the mean kernel gradient */
    pr->rr_inv = 1.0 / (pi->rho * pj->rho);
    pr->acc_term = ((pr->P[0] + pr->P[1]) * pr->rr_inv + pr->visc) * pr->w_mean_dr * r_inv;
  } else {
    /* pressure terms with grad-h corrections (Springel & Hernquist 2002) */
    pr->Prho2[0] = pi->f * pi->P / (pi->rho * pi->rho);
    pr->Prho2[1] = pj->f * pj->P / (pj->rho * pj->rho);
    pr->acc_term =
        (pr->Prho2[0] * pr->w_dr[0] + pr->Prho2[1] * pr->w_dr[1] + pr->visc * pr->w_mean_dr) *
        r_inv;
  }

  /* the time step's signal velocity: with the longitudinal wave speeds of
   * solids (equal to v_sig for fluids) */
  pr->v_sig_dt = pi->cl + pj->cl - hp->beta * mu_ij;
}

/** The contribution of the pair to one of its particles, a (side 0: i,
 *  side 1: j), from the other, b: dx = x_a - x_b, dv = v_a - v_b.  Side 1
 *  with (j, i, -dx, -dv) gives bit for bit what side 0 of the pair (j, i)
 *  would: force_iact for (i, j) and for (j, i) and the symmetric loop's
 *  two sides of one force_pair_eval are the same sums. */
BOLIDE_INLINE void force_pair_side(const struct force_pair *pr, int side, const double dx[3],
                                   const double dv[3], const struct force_in *pa,
                                   const struct force_in *pb, const struct hydro_props *hp,
                                   struct force_acc *acc) {
  const int a = side, b = 1 - side;
  const double r_inv = pr->r_inv, dvdr = pr->dvdr, w_mean_dr = pr->w_mean_dr;
  const double wa_dr = pr->w_dr[a], wb_dr = pr->w_dr[b];

  double du;
  if (pr->sym)
    du = (pr->P[a] * pr->rr_inv + 0.5 * pr->visc) * w_mean_dr * dvdr * r_inv;
  else /* energy: PdV work of a plus half the viscous heating */
    du = (pr->Prho2[a] * wa_dr + 0.5 * pr->visc * w_mean_dr) * dvdr * r_inv;

  acc->a[0] -= pb->m * pr->acc_term * dx[0];
  acc->a[1] -= pb->m * pr->acc_term * dx[1];
  acc->a[2] -= pb->m * pr->acc_term * dx[2];
  acc->du_dt += pb->m * du;

  if (hp->solids) {
    /* deviatoric stress: S.dx of each side, combined commutatively */
    double Sa_dx[3], Sb_dx[3], t[3];
    force_sym_dot(pa->S, dx, Sa_dx);
    force_sym_dot(pb->S, dx, Sb_dx);
    double ca;
    if (pr->sym) {
      ca = w_mean_dr * r_inv / (pa->rho * pb->rho);
      for (int k = 0; k < 3; k++) t[k] = (Sa_dx[k] + Sb_dx[k]) * ca;
    } else {
      ca = wa_dr * r_inv / (pa->rho * pa->rho);
      const double cb = wb_dr * r_inv / (pb->rho * pb->rho);
      for (int k = 0; k < 3; k++) t[k] = Sa_dx[k] * ca + Sb_dx[k] * cb;
    }
    double du_s = -(dv[0] * Sa_dx[0] + dv[1] * Sa_dx[1] + dv[2] * Sa_dx[2]) * ca;
    if (hp->as_eps > 0.0) {
      /* artificial stress (Monaghan 2000, Sec. 4) with f = W(r)/W(dp) */
      const double h_ab = 0.5 * (pa->h + pb->h);
      double w_ab, w_ab_dr, w_ab_dh;
      kernel_eval_r(pr->r, 1.0 / h_ab, &w_ab, &w_ab_dr, &w_ab_dh);
      const double fr = w_ab * h_ab * h_ab * h_ab * hp->as_wdp_inv;
      const double cr = pow(fr, hp->as_n) * w_mean_dr * r_inv;
      double Ra_dx[3], Rb_dx[3];
      force_sym_dot(pa->R, dx, Ra_dx);
      force_sym_dot(pb->R, dx, Rb_dx);
      double dvR = 0.0;
      for (int k = 0; k < 3; k++) {
        const double rs = (Ra_dx[k] + Rb_dx[k]) * cr;
        t[k] += rs;
        dvR += dv[k] * rs;
      }
      du_s -= 0.5 * dvR;
    }
    acc->a[0] += pb->m * t[0];
    acc->a[1] += pb->m * t[1];
    acc->a[2] += pb->m * t[2];
    acc->du_dt += pb->m * du_s;
  }

  if (hp->xsph > 0.0) {
    /* XSPH (Monaghan 1989): mean of the two kernels and densities */
    const double c = pb->m * 0.5 * (pr->w[a] + pr->w[b]) / pr->rho_ij;
    acc->xsph[0] -= c * dv[0];
    acc->xsph[1] -= c * dv[1];
    acc->xsph[2] -= c * dv[2];
  }

  /* artificial conduction (Price 2008, eq. 28) with v_sig^u = sqrt(|dP|/rho_ij) */
  if (hp->alpha_u > 0.0) {
    const double vsig_u = sqrt(fabs(pa->P - pb->P) / pr->rho_ij);
    acc->du_dt += pb->m * hp->alpha_u * vsig_u * (pa->u - pb->u) / pr->rho_ij * w_mean_dr;
  }

  /* continuity equation, grad W at h_a (with SPH:continuity_correction the
   * extra ghost sets drho/dt from the corrected gradient instead:
   * gradient_cspm_drho_dt in gradient_finish.h) */
  if (!hp->continuity_cspm) acc->drho_dt += pb->m * dvdr * r_inv * wa_dr;

  if (pr->v_sig_dt > acc->v_sig) acc->v_sig = pr->v_sig_dt;
}

/** Contribution of j to i (the gather form: the GPU's kernels).  dx = x_i
 *  - x_j, dv = v_i - v_j, r2 = |dx|^2 > 0, and r < max(H_i, H_j).  hp:
 *  viscosity and conduction constants. */
BOLIDE_INLINE void force_iact(double r2, const double dx[3], const double dv[3],
                              const struct force_in *pi, const struct force_in *pj,
                              const struct hydro_props *hp, struct force_acc *acc) {
  struct force_pair pr;
  force_pair_eval(r2, dx, dv, pi, pj, hp, &pr);
  force_pair_side(&pr, 0, dx, dv, pi, pj, hp, acc);
}

#endif
