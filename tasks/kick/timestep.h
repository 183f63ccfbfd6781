/* The time step of one particle (theory/sph.md, "Time steps"): every
 * criterion once, used by the CPU kick (kick_cpu.c), the CUDA kick
 * (kick_gpu.cu) and the diagnostic of a step below dt_min
 * (kick_dt_culprit) through timestep_part_criteria. */
#ifndef BOLIDE_TIMESTEP_H
#define BOLIDE_TIMESTEP_H

#include <math.h>

#include "tasks/damage/damage_part.h"
#include "tasks/gravity/gravity_iact.h"
#include "tasks/hydro/hydro_props.h"
#include "src/inline.h"
#include "tasks/hydro/kernel.h"
#include "src/materials/material.h"
#include "src/part.h"
#include "src/materials/viscosity.h"
#include "src/sym3.h"
#include "tasks/gradient/gradient_finish.h"

/** Norm sqrt(T:T) of a symmetric tensor (xx xy xz yy yz zz). */
BOLIDE_INLINE double timestep_sym_norm(const double T[6]) {
  return sqrt(T[0] * T[0] + T[3] * T[3] + T[5] * T[5] +
              2.0 * (T[1] * T[1] + T[2] * T[2] + T[4] * T[4]));
}

/** Limits on the relative change of density, energy and deviatoric stress in
 *  one step, dt = f (|q| + q_min) / |dq/dt| with f = SPH:max_relative_change
 *  (Schaefer et al. 2016, Sec. 3.5 and miluphcuda's scheme): q_min = 0 for
 *  rho, 1e-2 c_s^2 for u, 1e-3 rho c_s^2 (a thousandth of the bulk modulus)
 *  for |S|, so that quantities starting at zero do not stall the run. */
BOLIDE_INLINE double timestep_relative_change(const struct hydro_props *hp, double rho,
                                              double drho_dt, double u, double du_dt, double cs,
                                              const double S[6], const double dS[6]) {
  const double f = hp->max_rel_change;
  double dt = 1e300;
  if (drho_dt != 0.0 && rho > 0.0) dt = f * rho / fabs(drho_dt);
  if (du_dt != 0.0) {
    const double d = f * (fabs(u) + 1e-2 * cs * cs) / fabs(du_dt);
    if (d < dt) dt = d;
  }
  const double nds = timestep_sym_norm(dS);
  if (nds > 0.0) {
    const double d = f * (timestep_sym_norm(S) + 1e-3 * rho * cs * cs) / nds;
    if (d < dt) dt = d;
  }
  return dt;
}

/** With SPH:continuity_correction (CSPM continuity, theory/solids.md E14):
 *  the factor sqrt(lambda_min) on the Courant step of particle i, lambda_min
 *  the smallest eigenvalue of its correction-tensor sum M (gradient_iact.h;
 *  the identity for a full kernel), where it is below 1: a truncated
 *  kernel (a free surface, an edge, a corner) whose M^-1 multiplies the
 *  density rate's response to a compression by up to 1/lambda_min, a
 *  stiffer oscillator whose stable step is shorter by sqrt(lambda_min)
 *  (theory/fluids.md, "CSPM density at free corners").  1 where M is not
 *  inverted (gradient_invert_sym: the uncorrected divergence is used). */
BOLIDE_INLINE double timestep_cspm_factor(const struct parts *BOLIDE_RESTRICT p, size_t i) {
  const double M[6] = {p->gmxx[i], p->gmxy[i], p->gmxz[i], p->gmyy[i], p->gmyz[i], p->gmzz[i]};
  double Minv[9], lam[3];
  if (gradient_invert_sym(M, Minv) != 0) return 1.0;
  sym3_eigen(M, lam, NULL);
  return lam[2] > 0.0 && lam[2] < 1.0 ? sqrt(lam[2]) : 1.0;
}

/** The criteria of timestep_part_criteria, in the order of its array. */
enum timestep_criterion {
  TIMESTEP_COURANT = 0, /**< 2 C H / v_sig */
  TIMESTEP_ACCEL,       /**< sqrt(2 C H / |a|) */
  TIMESTEP_VOLUME,      /**< ln(max volume change) / |div v| */
  TIMESTEP_VISCOUS,     /**< viscous diffusion of a Newtonian fluid (viscosity.h) */
  TIMESTEP_RELATIVE,    /**< relative change of rho, u or S (SPH:max_relative_change) */
  TIMESTEP_DAMAGE,      /**< damage growth (Damage:max_change) */
  TIMESTEP_GRAVITY,     /**< sqrt(2 eta eps_i / |a_grav|) */
  TIMESTEP_CSPM,        /**< the Courant step times sqrt(lambda_min(M)) (CSPM continuity) */
  TIMESTEP_NR
};

/** What, besides hydro_props, decides the kick and the time step of a
 *  particle (filled by kick_timestep_props on the host, by the kick
 *  kernel from its arguments on the GPU). */
struct timestep_props {
  int hydro;                /**< hydrodynamics on: the hydrodynamic criteria */
  int porous;               /**< P-alpha / epsilon-alpha rates and return around the kick */
  double damage_max_change; /**< Damage:max_change; 0: no damage criterion */
  int gravity;              /**< self-gravity: ga joins a, and the gravitational criterion */
  double grav_eps;          /**< Gravity:softening (Plummer equivalent) */
  double grav_h_factor;     /**< Gravity:softening_h_factor (eps_i = h_factor h_i when > 0) */
  double grav_eta;          /**< Gravity:eta */
};

/** Name of criterion k for messages. */
BOLIDE_INLINE const char *timestep_criterion_name(int k) {
  switch (k) {
    case TIMESTEP_COURANT:
      return "Courant condition (h, v_sig)";
    case TIMESTEP_ACCEL:
      return "acceleration criterion (h, |a|)";
    case TIMESTEP_VOLUME:
      return "volume change (div v)";
    case TIMESTEP_VISCOUS:
      return "viscous diffusion (h, rho, viscosity)";
    case TIMESTEP_RELATIVE:
      return "relative change of rho, u or S";
    case TIMESTEP_DAMAGE:
      return "damage growth";
    case TIMESTEP_GRAVITY:
      return "gravitational criterion (eps_i, |a_grav|)";
    case TIMESTEP_CSPM:
      return "Courant condition of a truncated kernel with CSPM continuity (h, v_sig, M)";
    default:
      return "none";
  }
}

/** Every time-step limit of particle i into d[TIMESTEP_NR] (1e300 or
 *  INFINITY where a criterion does not apply) from its current state
 *  (after the kick: the acceleration a includes ga); returns the smallest.
 *  The hydrodynamic criteria apply with tp->hydro, the viscous one to a
 *  viscous material of a solids run, the relative-change ones with
 *  SPH:max_relative_change, the damage one with tp->damage_max_change > 0,
 *  the gravitational one with self-gravity and a softening eps_i (the
 *  absolute Gravity:softening or softening_h_factor * h_i). */
BOLIDE_INLINE double timestep_part_criteria(const struct parts *BOLIDE_RESTRICT p, size_t i,
                                            const struct hydro_props *hp,
                                            const struct material_table *mats,
                                            const struct timestep_props *tp,
                                            double d[TIMESTEP_NR]) {
  for (int k = 0; k < TIMESTEP_NR; k++) d[k] = 1e300;
  if (tp->hydro) {
    const double H = kernel_gamma * p->h[i];
    const double a = sqrt(p->ax[i] * p->ax[i] + p->ay[i] * p->ay[i] + p->az[i] * p->az[i]);
    if (p->v_sig[i] > 0.0) d[TIMESTEP_COURANT] = 2.0 * hp->cfl * H / p->v_sig[i];
    if (hp->continuity_cspm && d[TIMESTEP_COURANT] < 1e300)
      d[TIMESTEP_CSPM] = d[TIMESTEP_COURANT] * timestep_cspm_factor(p, i);
    if (a > 0.0) d[TIMESTEP_ACCEL] = sqrt(2.0 * hp->cfl * H / a);
    if (p->div_v[i] != 0.0) d[TIMESTEP_VOLUME] = hp->log_max_volume_change / fabs(p->div_v[i]);
    if (hp->solids) {
      const struct material *mat = material_table_find(mats, p->mat[i]);
      if (mat && mat->viscosity > 0.0)
        d[TIMESTEP_VISCOUS] = viscosity_timestep(H, p->rho[i], mat->viscosity);
    }
    if (hp->max_rel_change > 0.0) {
      /* (no stress arrays: a GPU run without stress, gpu_set_absent) */
      double S[6] = {0, 0, 0, 0, 0, 0}, dS[6] = {0, 0, 0, 0, 0, 0};
      if (p->Sxx) {
        S[0] = p->Sxx[i], S[1] = p->Sxy[i], S[2] = p->Sxz[i];
        S[3] = p->Syy[i], S[4] = p->Syz[i], S[5] = p->Szz[i];
        dS[0] = p->dSxx[i], dS[1] = p->dSxy[i], dS[2] = p->dSxz[i];
        dS[3] = p->dSyy[i], dS[4] = p->dSyz[i], dS[5] = p->dSzz[i];
      }
      d[TIMESTEP_RELATIVE] = timestep_relative_change(hp, p->rho[i], p->drho_dt[i], p->u[i],
                                                      p->du_dt[i], p->cs[i], S, dS);
    }
  }
  if (tp->damage_max_change > 0.0)
    d[TIMESTEP_DAMAGE] = damage_part_timestep(p, i, tp->damage_max_change);
  if (tp->gravity && (tp->grav_eps > 0.0 || tp->grav_h_factor > 0.0)) {
    const double ga[3] = {p->gax[i], p->gay[i], p->gaz[i]};
    const double epsi = gravity_pair_softening(tp->grav_eps, tp->grav_h_factor, p->h[i], 0.0);
    d[TIMESTEP_GRAVITY] = gravity_timestep(ga, epsi, tp->grav_eta);
  }
  double dt = 1e300;
  for (int k = 0; k < TIMESTEP_NR; k++)
    if (d[k] < dt) dt = d[k];
  return dt;
}

/** The time step of particle i: the smallest of timestep_part_criteria. */
BOLIDE_INLINE double timestep_part(const struct parts *BOLIDE_RESTRICT p, size_t i,
                                   const struct hydro_props *hp, const struct material_table *mats,
                                   const struct timestep_props *tp) {
  double d[TIMESTEP_NR];
  return timestep_part_criteria(p, i, hp, mats, tp, d);
}

#endif
