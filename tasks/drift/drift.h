/* Kick and drift of one particle (kick-drift-kick leapfrog, theory/sph.md
 * section "Time integration").  Written once for CPU and GPU. */
#ifndef BOLIDE_DRIFT_H
#define BOLIDE_DRIFT_H

#include <math.h>

#include "src/inline.h"
#include "src/part.h"
#include "src/timeline.h"
#include "tasks/ghost/continuity_floor.h"
#include "tasks/ghost/ghost_part.h"
#include "tasks/gradient/extra_ghost_part.h"
#include "tasks/hydro/hydro_props.h"
#include "src/materials/material.h"

/** Half kick of particle i by dt_kick: v += a dt, u += du/dt dt; the
 *  deviatoric stress and the continuity density are integrated like u
 *  (theory/solids.md, "Time integration").  u may undershoot below 0 (a
 *  cold body's elastic oscillation in one step; the EOS take it as u = 0)
 *  and energy stays exactly conserved; for materials whose EOS needs
 *  u >= 0 (PART_U_FLOOR: ideal gas, tables) an energy that would go
 *  negative is halved instead, as SWIFT's planetary scheme does, and the
 *  energy this adds, exchanged with no neighbour, is counted in e_clamp
 *  (the statistics' E_clamp; theory/sph.md, "Conservation budget"). */
BOLIDE_INLINE void kick_part(struct parts *BOLIDE_RESTRICT p, size_t i, double dt_kick) {
  p->vx[i] += p->ax[i] * dt_kick;
  p->vy[i] += p->ay[i] * dt_kick;
  p->vz[i] += p->az[i] * dt_kick;
  const double u1 = p->u[i] + p->du_dt[i] * dt_kick;
  if (u1 >= 0.0 || !(p->flags[i] & PART_U_FLOOR)) {
    p->u[i] = u1;
  } else {
    const double uh = 0.5 * p->u[i];
    p->e_clamp[i] += uh - u1;
    p->u[i] = uh;
  }
  /* (a GPU run without stress does not hold the stress arrays: gpu_set_absent) */
  if (p->Sxx) {
    p->Sxx[i] += p->dSxx[i] * dt_kick;
    p->Sxy[i] += p->dSxy[i] * dt_kick;
    p->Sxz[i] += p->dSxz[i] * dt_kick;
    p->Syy[i] += p->dSyy[i] * dt_kick;
    p->Syz[i] += p->dSyz[i] * dt_kick;
    p->Szz[i] += p->dSzz[i] * dt_kick;
  }
  const double r1 = p->rho_full[i] + p->drho_dt[i] * dt_kick;
  p->rho_full[i] = (r1 > 0.0) ? r1 : 0.5 * p->rho_full[i];
  /* distention of porous materials: dalpha/dt <= 0 (compaction is
   * irreversible), alpha >= 1 */
  const double a1 = p->alpha[i] + p->dalpha_dt[i] * dt_kick;
  p->alpha[i] = a1 > 1.0 ? a1 : 1.0;
}

/** After the second kick the predicted values are the integrated ones. */
BOLIDE_INLINE void kick_sync_predicted(struct parts *BOLIDE_RESTRICT p, size_t i) {
  p->vpx[i] = p->vx[i];
  p->vpy[i] = p->vy[i];
  p->vpz[i] = p->vz[i];
  p->up[i] = p->u[i];
  if (p->Sxx) {
    p->Spxx[i] = p->Sxx[i];
    p->Spxy[i] = p->Sxy[i];
    p->Spxz[i] = p->Sxz[i];
    p->Spyy[i] = p->Syy[i];
    p->Spyz[i] = p->Syz[i];
    p->Spzz[i] = p->Szz[i];
  }
  p->rho_fp[i] = p->rho_full[i];
  p->alpha_p[i] = p->alpha[i];
}

/** The exponent w of the smoothing length's change over a drift by dt,
 *  h -> h exp(w): dh/dt = f h div v / 3 with f the grad-h factor, or with
 *  h_continuity dh/dt = -h/(3 rho) drho/dt (drift_part_to), within +-0.2.
 *  f: the h that keeps n h^3 fixed while the particles move changes at
 *  -h (dn/dt at fixed h) / (3 n + h dn/dh) = f h div v / 3, and the
 *  summed density at d ln rho / dt = -f div v (theory/sph.md section 2);
 *  f = 1 where no ghost has set it. */
BOLIDE_INLINE double drift_h_exponent(const struct parts *BOLIDE_RESTRICT p, size_t i, double dt,
                                      int h_continuity) {
  const double f = p->f_gradh[i] > 0.0 ? p->f_gradh[i] : 1.0;
  double w = h_continuity ? -p->drho_dt[i] * dt / (3.0 * p->rho[i]) : f * p->div_v[i] * dt / 3.0;
  if (w > 0.2) w = 0.2;
  if (w < -0.2) w = -0.2;
  return w;
}

/** At the start of particle i's step (its first half kick): its h becomes
 *  the estimate of the root that its last ghost made from its sums
 *  (ghost_part_step: the ratio in h_lo, 0 where there is none), so that
 *  the drift predicts from the root and not from an h up to the
 *  iteration's tolerance away from it; h_lo is cleared. */
BOLIDE_INLINE void drift_h_root(struct parts *BOLIDE_RESTRICT p, size_t i) {
  const double r = p->h_lo[i];
  if (r > 0.5 && r < 2.0) p->h[i] *= r;
  p->h_lo[i] = 0.0;
}

/** Drift of particle i by dt after its first half kick: positions move with
 *  the half-step velocity; the velocity and energy used by the next force
 *  computation are predicted to the new time, half after the middle of the
 *  particle's step (the state is that of the middle after the first half
 *  kick: predicted = state + rate * half; with time bins a particle's step
 *  spans several drifts, src/timeline.h); h follows the
 *  velocity divergence (dh/dt = h div v / 3) as a first guess for the
 *  iteration, or, with h_continuity (SPH:h_evolution: continuity), the
 *  density rate of the last force loop, dh/dt = -h/(3 rho) drho/dt, as
 *  the h itself (theory/sph.md section 2); h = h exp(dt dh/dt / h), the
 *  exponent within +-0.2, never above h_max (SPH:h_max; a larger guess
 *  would widen the cells' reach at the next rebuild check).  With XSPH
 *  (xsph > 0) positions move with v + xsph * sum m_j/rho_ij (v_j - v_i) W_ij
 *  (Monaghan 1989; theory/sph.md eq. S15), the sum from the last force
 *  loop. */
BOLIDE_INLINE void drift_part_to(struct parts *BOLIDE_RESTRICT p, size_t i, double dt, double half,
                                 double xsph, double h_max, int h_continuity) {
  p->x[i] += (p->vx[i] + xsph * p->xsphx[i]) * dt;
  p->y[i] += (p->vy[i] + xsph * p->xsphy[i]) * dt;
  p->z[i] += (p->vz[i] + xsph * p->xsphz[i]) * dt;
  if (p->Sxx) {
    p->Spxx[i] = p->Sxx[i] + p->dSxx[i] * half;
    p->Spxy[i] = p->Sxy[i] + p->dSxy[i] * half;
    p->Spxz[i] = p->Sxz[i] + p->dSxz[i] * half;
    p->Spyy[i] = p->Syy[i] + p->dSyy[i] * half;
    p->Spyz[i] = p->Syz[i] + p->dSyz[i] * half;
    p->Spzz[i] = p->Szz[i] + p->dSzz[i] * half;
  }
  const double rp = p->rho_full[i] + p->drho_dt[i] * half;
  p->rho_fp[i] = (rp > 0.0) ? rp : 0.5 * p->rho_full[i];
  const double ap = p->alpha[i] + p->dalpha_dt[i] * half;
  p->alpha_p[i] = ap > 1.0 ? ap : 1.0;
  p->vpx[i] = p->vx[i] + p->ax[i] * half;
  p->vpy[i] = p->vy[i] + p->ay[i] * half;
  p->vpz[i] = p->vz[i] + p->az[i] * half;
  const double up = p->u[i] + p->du_dt[i] * half;
  p->up[i] = (up >= 0.0 || !(p->flags[i] & PART_U_FLOOR)) ? up : 0.5 * p->u[i];
  const double h = p->h[i] * exp(drift_h_exponent(p, i, dt, h_continuity));
  p->h[i] = h < h_max ? h : h_max;
}

/** Drift of particle i by a whole step dt after its first half kick by dt/2
 *  (the global step: the new time is the end of its step). */
BOLIDE_INLINE void drift_part(struct parts *BOLIDE_RESTRICT p, size_t i, double dt, double xsph,
                              double h_max, int h_continuity) {
  drift_h_root(p, i);
  drift_part_to(p, i, dt, 0.5 * dt, xsph, h_max, h_continuity);
}

/** With individual time steps: the state that the neighbours of particle
 *  i, asleep in the middle of its step, read in the FORCE phase, predicted
 *  at the end of its drift from the rates of its step's start (its sums,
 *  equation of state and rates are not recomputed: PART_INACTIVE).  Its
 *  position, velocity, energy, stress, continuity density and distention
 *  are predicted by drift_part_to, its h by dh/dt = h div v / 3 (exponent
 *  w, drift_h_exponent); here its density follows the same compression,
 *  rho -> rho exp(-3 w) (rho h^3 constant: d ln rho/dt = -div v), or with
 *  the continuity equation is the predicted continuity density (at least
 *  its floor), and its pressure, sound speed and (solids) longitudinal
 *  sound speed are its material's equation of state at the predicted
 *  density and energy (ghost_part_eos, the ghost's; theory/sph.md, "Time
 *  integration"); a plastic particle's predicted stress is returned onto
 *  the yield surface of that state (extra_ghost_predicted_return).  The
 *  grad-h factor, the Balsara switch and the velocity gradients stay those
 *  of its step's start. */
BOLIDE_INLINE void drift_predict_hydro(struct parts *BOLIDE_RESTRICT p, size_t i, double w,
                                       const struct hydro_props *hp,
                                       const struct material_table *mats) {
  if (!hp->enabled) return;
  const struct material *mat = material_table_find(mats, p->mat[i]);
  if (!mat) return;
  if (hp->continuity) {
    const double floor = continuity_rho_floor(hp, mat);
    p->rho[i] = p->rho_fp[i] > floor ? p->rho_fp[i] : floor;
  } else {
    p->rho[i] *= exp(-3.0 * w);
  }
  ghost_part_eos(p, i, hp, mat, 1);
  if (hp->solids && p->Sxx && mat->strength != STRENGTH_NONE && mat->strength != STRENGTH_ELASTIC &&
      mat->shear_modulus > 0.0)
    extra_ghost_predicted_return(p, i, mat);
}

/** With individual time steps (TimeIntegration:global_step: false):
 *  particle i drifts from ti_old to ti_new on a time line of ticks of
 *  time_base; a particle whose step begins at ti_old (its bin's step
 *  divides ti_old) first takes its half kick by half its step, and its
 *  predicted state is that of ti_new, from the middle of its own step
 *  (drift_part_to).  Returns 1 when the particle ends its step at ti_new;
 *  a particle that does not is marked PART_INACTIVE: the FORCE phase
 *  skips it, and its density, pressure and sound speeds are predicted
 *  (drift_predict_hydro).  hp: the SPH settings (SPH:xsph, h_max,
 *  h_evolution), mats: the materials (the host's table on the CPU, the
 *  device's on the GPU). */
BOLIDE_INLINE int drift_part_bins(struct parts *BOLIDE_RESTRICT p, size_t i, double time_base,
                                  integertime_t ti_old, integertime_t ti_new,
                                  const struct hydro_props *hp, const struct material_table *mats) {
  const integertime_t step = timeline_step_of_bin(p->time_bin[i] > 0 ? p->time_bin[i] : 1);
  const integertime_t since = ti_old % step; /* 0: its step begins at ti_old */
  if (since == 0) {
    kick_part(p, i, 0.5 * (double)step * time_base);
    drift_h_root(p, i);
  }
  const integertime_t ti_mid = ti_old - since + step / 2;
  const double dt = (double)(ti_new - ti_old) * time_base;
  const double w = drift_h_exponent(p, i, dt, hp->h_continuity);
  drift_part_to(p, i, dt, (double)(ti_new - ti_mid) * time_base, hp->xsph, hp->h_max,
                hp->h_continuity);
  const int active = ti_new % step == 0;
  if (active) {
    p->flags[i] &= ~PART_INACTIVE;
  } else {
    p->flags[i] |= PART_INACTIVE;
    drift_predict_hydro(p, i, w, hp, mats);
  }
  return active;
}

#endif
