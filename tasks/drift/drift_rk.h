/* The stages of the Runge-Kutta and predictor-corrector integrators
 * (TimeIntegration:scheme: rk2 | pc; theory/integrators.md): one
 * particle's state vector and rates, and the state of a stage made from
 * them.  Written once for the CPU loop (drift_cpu.c) and a CUDA kernel. */
#ifndef BOLIDE_DRIFT_RK_H
#define BOLIDE_DRIFT_RK_H

#include <math.h>

#include "src/inline.h"
#include "src/part.h"
#include "tasks/drift/drift.h"
#include "tasks/hydro/hydro_props.h"

/** Entries of a particle's state vector y: x, y, z, vx, vy, vz, u,
 *  Sxx, Sxy, Sxz, Syy, Syz, Szz, the continuity density, the distention
 *  alpha and ln h. */
enum drift_rk_y {
  DRIFT_RK_X = 0,
  DRIFT_RK_V = 3,
  DRIFT_RK_U = 6,
  DRIFT_RK_S = 7,
  DRIFT_RK_RHO = 13,
  DRIFT_RK_ALPHA = 14,
  DRIFT_RK_LNH = 15,
  DRIFT_RK_NY = 16
};

/** Entries of a particle's record of one derivative evaluation r: the
 *  velocity it was evaluated with (vp), the acceleration, du/dt, dS/dt,
 *  drho/dt, dalpha/dt, the XSPH sum, div v and the density.  From it come
 *  the rates of y (drift_rk_rates); restored into the particle arrays
 *  (drift_rk_restore) it is the evaluation again. */
enum drift_rk_r {
  DRIFT_RK_RV = 0,
  DRIFT_RK_RA = 3,
  DRIFT_RK_RU = 6,
  DRIFT_RK_RS = 7,
  DRIFT_RK_RRHO = 13,
  DRIFT_RK_RALPHA = 14,
  DRIFT_RK_RXSPH = 15,
  DRIFT_RK_RDIV = 18,
  DRIFT_RK_RDENS = 19,
  DRIFT_RK_NR = 20
};

/** The largest number of evaluations a stage combines. */
#define DRIFT_RK_MAX_K 3

/** One stage of a step (set by the engine, read by the drift tasks):
 *  y = y0 + dt sum_k coef[k] f(r_k) for k < nk, where r_k is stored
 *  (r[k]) or, when r[k] is NULL, the evaluation now in the particle
 *  arrays.  save: first store the particles' state into y0 (the step's
 *  start); store: where their evaluation goes first; final: the step's
 *  last stage (the energy that the floor on u adds is counted); err: also the error estimate dt
 * sum_k ecoef[k] f(r_k), its largest scaled norm over the cell into the cell's slot. */
struct drift_stage {
  double dt;
  int nk;
  double coef[DRIFT_RK_MAX_K];
  double *y0;                /**< DRIFT_RK_NY per particle */
  double *r[DRIFT_RK_MAX_K]; /**< DRIFT_RK_NR per particle, or NULL: the particle arrays */
  double *store;             /**< where the evaluation in the particle arrays goes first
                                  (DRIFT_RK_NR per particle; NULL: nowhere) */
  int save, final, err;
  double ecoef[DRIFT_RK_MAX_K];
};

/** The state vector of particle i into y. */
BOLIDE_INLINE void drift_rk_state(const struct parts *BOLIDE_RESTRICT p, size_t i, double *y) {
  y[DRIFT_RK_X] = p->x[i];
  y[DRIFT_RK_X + 1] = p->y[i];
  y[DRIFT_RK_X + 2] = p->z[i];
  y[DRIFT_RK_V] = p->vx[i];
  y[DRIFT_RK_V + 1] = p->vy[i];
  y[DRIFT_RK_V + 2] = p->vz[i];
  y[DRIFT_RK_U] = p->u[i];
  y[DRIFT_RK_S] = p->Sxx[i];
  y[DRIFT_RK_S + 1] = p->Sxy[i];
  y[DRIFT_RK_S + 2] = p->Sxz[i];
  y[DRIFT_RK_S + 3] = p->Syy[i];
  y[DRIFT_RK_S + 4] = p->Syz[i];
  y[DRIFT_RK_S + 5] = p->Szz[i];
  y[DRIFT_RK_RHO] = p->rho_full[i];
  y[DRIFT_RK_ALPHA] = p->alpha[i];
  y[DRIFT_RK_LNH] = log(p->h[i]);
}

/** The evaluation in the particle arrays of particle i into r (after the
 *  kick's rates, kick2_rates: the acceleration holds gravity's). */
BOLIDE_INLINE void drift_rk_record(const struct parts *BOLIDE_RESTRICT p, size_t i, double *r) {
  r[DRIFT_RK_RV] = p->vpx[i];
  r[DRIFT_RK_RV + 1] = p->vpy[i];
  r[DRIFT_RK_RV + 2] = p->vpz[i];
  r[DRIFT_RK_RA] = p->ax[i];
  r[DRIFT_RK_RA + 1] = p->ay[i];
  r[DRIFT_RK_RA + 2] = p->az[i];
  r[DRIFT_RK_RU] = p->du_dt[i];
  r[DRIFT_RK_RS] = p->dSxx[i];
  r[DRIFT_RK_RS + 1] = p->dSxy[i];
  r[DRIFT_RK_RS + 2] = p->dSxz[i];
  r[DRIFT_RK_RS + 3] = p->dSyy[i];
  r[DRIFT_RK_RS + 4] = p->dSyz[i];
  r[DRIFT_RK_RS + 5] = p->dSzz[i];
  r[DRIFT_RK_RRHO] = p->drho_dt[i];
  r[DRIFT_RK_RALPHA] = p->dalpha_dt[i];
  r[DRIFT_RK_RXSPH] = p->xsphx[i];
  r[DRIFT_RK_RXSPH + 1] = p->xsphy[i];
  r[DRIFT_RK_RXSPH + 2] = p->xsphz[i];
  r[DRIFT_RK_RDIV] = p->div_v[i];
  r[DRIFT_RK_RDENS] = p->rho[i];
}

/** The rates dy/dt of an evaluation r: positions move with the velocity
 *  of the evaluation plus xsph times its XSPH sum; ln h changes as the
 *  drift's h does (drift_h_exponent: div v / 3, or -drho/dt / (3 rho) with
 *  SPH:h_evolution: continuity). */
BOLIDE_INLINE void drift_rk_rates(const double *r, double xsph, int h_continuity, double *f) {
  for (int k = 0; k < 3; k++) {
    f[DRIFT_RK_X + k] = r[DRIFT_RK_RV + k] + xsph * r[DRIFT_RK_RXSPH + k];
    f[DRIFT_RK_V + k] = r[DRIFT_RK_RA + k];
  }
  f[DRIFT_RK_U] = r[DRIFT_RK_RU];
  for (int k = 0; k < 6; k++) f[DRIFT_RK_S + k] = r[DRIFT_RK_RS + k];
  f[DRIFT_RK_RHO] = r[DRIFT_RK_RRHO];
  f[DRIFT_RK_ALPHA] = r[DRIFT_RK_RALPHA];
  f[DRIFT_RK_LNH] =
      h_continuity ? -r[DRIFT_RK_RRHO] / (3.0 * r[DRIFT_RK_RDENS]) : r[DRIFT_RK_RDIV] / 3.0;
}

/** The state y into particle i's arrays, the predicted ones equal to it
 *  (every evaluation of these schemes is of a state, not a prediction):
 *  the continuity density stays above half of y0's, the distention at
 *  least 1, h within a factor exp(+-0.2) of y0's and at most h_max (the
 *  drift's limits), an energy of a material that needs u >= 0 that would
 *  go negative is half of y0's (kick_part's floor; in the final stage the
 *  energy it adds is counted in e_clamp). */
BOLIDE_INLINE void drift_rk_put(struct parts *BOLIDE_RESTRICT p, size_t i, const double *y,
                                const double *y0, double h_max, int final) {
  p->x[i] = y[DRIFT_RK_X];
  p->y[i] = y[DRIFT_RK_X + 1];
  p->z[i] = y[DRIFT_RK_X + 2];
  p->vx[i] = y[DRIFT_RK_V];
  p->vy[i] = y[DRIFT_RK_V + 1];
  p->vz[i] = y[DRIFT_RK_V + 2];
  double u = y[DRIFT_RK_U];
  if (u < 0.0 && (p->flags[i] & PART_U_FLOOR)) {
    const double uh = 0.5 * y0[DRIFT_RK_U];
    if (final) p->e_clamp[i] += uh - u;
    u = uh;
  }
  p->u[i] = u;
  p->Sxx[i] = y[DRIFT_RK_S];
  p->Sxy[i] = y[DRIFT_RK_S + 1];
  p->Sxz[i] = y[DRIFT_RK_S + 2];
  p->Syy[i] = y[DRIFT_RK_S + 3];
  p->Syz[i] = y[DRIFT_RK_S + 4];
  p->Szz[i] = y[DRIFT_RK_S + 5];
  p->rho_full[i] = y[DRIFT_RK_RHO] > 0.0 ? y[DRIFT_RK_RHO] : 0.5 * y0[DRIFT_RK_RHO];
  p->alpha[i] = y[DRIFT_RK_ALPHA] > 1.0 ? y[DRIFT_RK_ALPHA] : 1.0;
  double w = y[DRIFT_RK_LNH] - y0[DRIFT_RK_LNH];
  if (w > 0.2) w = 0.2;
  if (w < -0.2) w = -0.2;
  const double h = exp(y0[DRIFT_RK_LNH] + w);
  p->h[i] = h < h_max ? h : h_max;
  kick_sync_predicted(p, i);
}

/** The evaluation r back into particle i's arrays (a step started again
 *  after a rebuild: the rebuild reorders the arrays, and the step's first
 *  stage records them again). */
BOLIDE_INLINE void drift_rk_restore(struct parts *BOLIDE_RESTRICT p, size_t i, const double *y0,
                                    const double *r) {
  p->x[i] = y0[DRIFT_RK_X];
  p->y[i] = y0[DRIFT_RK_X + 1];
  p->z[i] = y0[DRIFT_RK_X + 2];
  p->vx[i] = y0[DRIFT_RK_V];
  p->vy[i] = y0[DRIFT_RK_V + 1];
  p->vz[i] = y0[DRIFT_RK_V + 2];
  p->u[i] = y0[DRIFT_RK_U];
  p->Sxx[i] = y0[DRIFT_RK_S];
  p->Sxy[i] = y0[DRIFT_RK_S + 1];
  p->Sxz[i] = y0[DRIFT_RK_S + 2];
  p->Syy[i] = y0[DRIFT_RK_S + 3];
  p->Syz[i] = y0[DRIFT_RK_S + 4];
  p->Szz[i] = y0[DRIFT_RK_S + 5];
  p->rho_full[i] = y0[DRIFT_RK_RHO];
  p->alpha[i] = y0[DRIFT_RK_ALPHA];
  p->h[i] = exp(y0[DRIFT_RK_LNH]);
  kick_sync_predicted(p, i);
  p->ax[i] = r[DRIFT_RK_RA];
  p->ay[i] = r[DRIFT_RK_RA + 1];
  p->az[i] = r[DRIFT_RK_RA + 2];
  p->du_dt[i] = r[DRIFT_RK_RU];
  p->dSxx[i] = r[DRIFT_RK_RS];
  p->dSxy[i] = r[DRIFT_RK_RS + 1];
  p->dSxz[i] = r[DRIFT_RK_RS + 2];
  p->dSyy[i] = r[DRIFT_RK_RS + 3];
  p->dSyz[i] = r[DRIFT_RK_RS + 4];
  p->dSzz[i] = r[DRIFT_RK_RS + 5];
  p->drho_dt[i] = r[DRIFT_RK_RRHO];
  p->dalpha_dt[i] = r[DRIFT_RK_RALPHA];
  p->xsphx[i] = r[DRIFT_RK_RXSPH];
  p->xsphy[i] = r[DRIFT_RK_RXSPH + 1];
  p->xsphz[i] = r[DRIFT_RK_RXSPH + 2];
  p->div_v[i] = r[DRIFT_RK_RDIV];
  p->rho[i] = r[DRIFT_RK_RDENS];
}

/** The scaled norm of an error estimate d of the state y of particle i
 *  (TimeIntegration:rk2_tolerance): the largest of |dx| / h, |dv| /
 *  max(|v|, c_s), |du| / (|u| + 1e-2 c_s^2), |drho| / rho, |dS| / (|S| +
 *  1e-3 rho c_s^2) (tensor norms sqrt(S:S), the scales of the relative
 *  change limit, timestep.h) and |dalpha| / alpha. */
BOLIDE_INLINE double drift_rk_error(const struct parts *BOLIDE_RESTRICT p, size_t i,
                                    const double *y, const double *d) {
  const double cs = p->cs[i];
  const double h = exp(y[DRIFT_RK_LNH]);
  double e = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / h;
  const double v = sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5]);
  const double vs = v > cs ? v : cs;
  const double dv = sqrt(d[3] * d[3] + d[4] * d[4] + d[5] * d[5]);
  if (vs > 0.0 && dv / vs > e) e = dv / vs;
  const double us = fabs(y[DRIFT_RK_U]) + 1e-2 * cs * cs;
  if (us > 0.0 && fabs(d[DRIFT_RK_U]) / us > e) e = fabs(d[DRIFT_RK_U]) / us;
  const double rho = y[DRIFT_RK_RHO];
  if (rho > 0.0 && fabs(d[DRIFT_RK_RHO]) / rho > e) e = fabs(d[DRIFT_RK_RHO]) / rho;
  const double *S = y + DRIFT_RK_S, *dS = d + DRIFT_RK_S;
  const double ns = sqrt(S[0] * S[0] + S[3] * S[3] + S[5] * S[5] +
                         2.0 * (S[1] * S[1] + S[2] * S[2] + S[4] * S[4]));
  const double nds = sqrt(dS[0] * dS[0] + dS[3] * dS[3] + dS[5] * dS[5] +
                          2.0 * (dS[1] * dS[1] + dS[2] * dS[2] + dS[4] * dS[4]));
  const double ss = ns + 1e-3 * p->rho[i] * cs * cs;
  if (ss > 0.0 && nds / ss > e) e = nds / ss;
  if (fabs(d[DRIFT_RK_ALPHA]) / y[DRIFT_RK_ALPHA] > e)
    e = fabs(d[DRIFT_RK_ALPHA]) / y[DRIFT_RK_ALPHA];
  return e;
}

/** One stage for particle i (struct drift_stage st): record its state and
 *  evaluation first if st->save, then put the stage's state; the
 *  error estimate's scaled norm is returned (0 without st->err).  A
 *  fixed boundary particle's acceleration and XSPH sum are 0 (kick2_rates):
 *  it stays where it is. */
BOLIDE_INLINE double drift_rk_stage(struct parts *BOLIDE_RESTRICT p, size_t i,
                                    const struct drift_stage *st, const struct hydro_props *hp) {
  double now[DRIFT_RK_NR], f[DRIFT_RK_NY], y[DRIFT_RK_NY], d[DRIFT_RK_NY];
  double *y0 = st->y0 + (size_t)DRIFT_RK_NY * i;
  if (st->save) drift_rk_state(p, i, y0);
  drift_rk_record(p, i, now);
  if (st->store)
    for (int k = 0; k < DRIFT_RK_NR; k++) st->store[(size_t)DRIFT_RK_NR * i + k] = now[k];
  for (int k = 0; k < DRIFT_RK_NY; k++) {
    y[k] = y0[k];
    d[k] = 0.0;
  }
  for (int j = 0; j < st->nk; j++) {
    const double *r = st->r[j] ? st->r[j] + (size_t)DRIFT_RK_NR * i : now;
    drift_rk_rates(r, hp->xsph, hp->h_continuity, f);
    for (int k = 0; k < DRIFT_RK_NY; k++) {
      y[k] += st->dt * st->coef[j] * f[k];
      d[k] += st->dt * st->ecoef[j] * f[k];
    }
  }
  drift_rk_put(p, i, y, y0, hp->h_max, st->final);
  return st->err ? drift_rk_error(p, i, y, d) : 0.0;
}

#endif
