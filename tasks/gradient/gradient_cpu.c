/* Gradient loops on the CPU: the loop skeleton (tasks/iact_loop.h) around
 * gradient_iact.h, and the extra ghost that finishes each solid particle
 * (gradient_finish.h, src/materials/strength.h).  theory/solids.md. */
#include "gradient_cpu.h"

#include "gradient_finish.h"
#include "hydro_parts.h"
#include "material.h"
#include "strength.h"

/** Symmetric form: i gets j's contribution if r < H_i, j gets i's if r < H_j. */
static inline void gradient_sym(struct parts *p, size_t i, size_t j, double r2, const double dx[3],
                                double hi, double hj) {
  const double Hi = kernel_gamma * hi, Hj = kernel_gamma * hj;
  if (r2 < Hi * Hi) hydro_gradient_gather(p, i, j, r2, dx, 1.0 / hi);
  if (r2 < Hj * Hj) {
    const double mdx[3] = {-dx[0], -dx[1], -dx[2]};
    hydro_gradient_gather(p, j, i, r2, mdx, 1.0 / hj);
  }
}

#define IACT_LOOP_NAME gradient
#define IACT_LOOP_SYM(p, i, j, r2, dx, hi, hj) gradient_sym(p, i, j, r2, dx, hi, hj)
#define IACT_LOOP_NONSYM(p, i, j, r2, dx, hi, hj) hydro_gradient_gather(p, i, j, r2, dx, 1.0 / (hi))
#include "iact_loop.h"

void gradient_self_cpu(struct parts *p, const struct cell *c) {
  loop_gradient_self(p, c);
}

void gradient_pair_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                       const double shift[3]) {
  loop_gradient_pair(p, ci, cj, shift);
}

void gradient_gather_cpu(struct parts *p, const struct cell *ci, const struct cell *cj,
                         const double shift[3]) {
  if (ci == cj && shift[0] == 0.0 && shift[1] == 0.0 && shift[2] == 0.0)
    loop_gradient_self_gather(p, ci);
  else
    loop_gradient_pair_gather(p, ci, cj, shift);
}

/** Read the six components of a symmetric tensor field into T. */
#define GRADIENT_GET6(T, p, pre, i)                                               \
  do {                                                                            \
    (T)[0] = (p)->pre##xx[i], (T)[1] = (p)->pre##xy[i], (T)[2] = (p)->pre##xz[i]; \
    (T)[3] = (p)->pre##yy[i], (T)[4] = (p)->pre##yz[i], (T)[5] = (p)->pre##zz[i]; \
  } while (0)
/** Write T into the six components of a symmetric tensor field. */
#define GRADIENT_PUT6(T, p, pre, i)                                               \
  do {                                                                            \
    (p)->pre##xx[i] = (T)[0], (p)->pre##xy[i] = (T)[1], (p)->pre##xz[i] = (T)[2]; \
    (p)->pre##yy[i] = (T)[3], (p)->pre##yz[i] = (T)[4], (p)->pre##zz[i] = (T)[5]; \
  } while (0)

void extra_ghost_part_cpu(struct parts *p, size_t i, const struct hydro_props *hp,
                          const struct material_table *mats) {
  const struct material *mat = material_table_find(mats, p->mat[i]);
  const double zero[6] = {0, 0, 0, 0, 0, 0};
  if (hp->continuity_cspm) {
    /* CSPM continuity (every particle, fluids included): the force loop adds
     * no density rate of its own (force_iact.h) */
    double M6[6];
    GRADIENT_GET6(M6, p, gm, i);
    const double G9[9] = {p->gvxx[i], p->gvxy[i], p->gvxz[i], p->gvyx[i], p->gvyy[i],
                          p->gvyz[i], p->gvzx[i], p->gvzy[i], p->gvzz[i]};
    p->drho_dt[i] = gradient_cspm_drho_dt(p->rho[i], M6, G9);
  }
  if (!mat || mat->strength == STRENGTH_NONE || !(mat->shear_modulus > 0.0)) {
    GRADIENT_PUT6(zero, p, S, i);
    GRADIENT_PUT6(zero, p, Sp, i);
    GRADIENT_PUT6(zero, p, dS, i);
    GRADIENT_PUT6(zero, p, R, i);
    return;
  }
  /* corrected velocity gradient (Randles & Libersky 1996) */
  double M[6], Minv[9], gv[9];
  GRADIENT_GET6(M, p, gm, i);
  const double G[9] = {p->gvxx[i], p->gvxy[i], p->gvxz[i], p->gvyx[i], p->gvyy[i],
                       p->gvyz[i], p->gvzx[i], p->gvzy[i], p->gvzz[i]};
  if (hp->gradient_correction)
    gradient_invert_sym(M, Minv);
  else
    for (int k = 0; k < 9; k++) Minv[k] = (k % 4 == 0) ? 1.0 : 0.0;
  gradient_apply(G, Minv, gv);
  p->gvxx[i] = gv[0], p->gvxy[i] = gv[1], p->gvxz[i] = gv[2];
  p->gvyx[i] = gv[3], p->gvyy[i] = gv[4], p->gvyz[i] = gv[5];
  p->gvzx[i] = gv[6], p->gvzy[i] = gv[7], p->gvzz[i] = gv[8];

  /* plasticity: the radial return of the integrated and the predicted stress */
  double S[6], Sp[6], dS[6];
  GRADIENT_GET6(S, p, S, i);
  GRADIENT_GET6(Sp, p, Sp, i);
  const double mu = mat->shear_modulus;
  const double eps_rate = gradient_stress_rate(gv, Sp, mu, dS);
  if (mat->strength != STRENGTH_ELASTIC) {
    const struct strength_state st = {p->P[i], p->rho[i], p->up[i], p->eps_p[i], eps_rate, 0.0};
    const double Y = strength_yield(mat, &st);
    p->eps_p[i] += strength_radial_return(S, Y, mu);
    strength_radial_return(Sp, Y, mu);
    GRADIENT_PUT6(S, p, S, i);
    GRADIENT_PUT6(Sp, p, Sp, i);
    gradient_stress_rate(gv, Sp, mu, dS);
  }
  GRADIENT_PUT6(dS, p, dS, i);

  /* artificial stress against the tensile instability (Monaghan 2000) */
  double R[6] = {0, 0, 0, 0, 0, 0};
  if (hp->as_eps > 0.0) gradient_artificial_stress(Sp, p->P[i], p->rho[i], hp->as_eps, R);
  GRADIENT_PUT6(R, p, R, i);
}

void extra_ghost_cell_cpu(struct parts *p, const struct cell *c, const struct hydro_props *hp,
                          const struct material_table *mats) {
  const size_t end = c->offset + c->count;
  for (size_t i = c->offset; i < end; i++) extra_ghost_part_cpu(p, i, hp, mats);
}
