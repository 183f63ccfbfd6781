/* The time step of one particle (theory/sph.md, "Time steps"). */
#ifndef BOLIDE_TIMESTEP_H
#define BOLIDE_TIMESTEP_H

#include <math.h>

#include "hydro_props.h"
#include "inline.h"
#include "kernel.h"

/** Smallest of the Courant condition dt = 2 C H / v_sig (SWIFT's form,
 *  Monaghan 1997), the acceleration criterion dt = sqrt(2 C H / |a|) and the
 *  kernel-volume limit dt = ln(max volume change) / |div v|, for support
 *  radius H = kernel_gamma h. */
BOLIDE_INLINE double timestep_hydro(const struct hydro_props *hp, double h, double v_sig,
                                    double a_norm, double div_v) {
  const double H = kernel_gamma * h;
  double dt = 1e300;
  if (v_sig > 0.0) dt = 2.0 * hp->cfl * H / v_sig;
  if (a_norm > 0.0) {
    const double dta = sqrt(2.0 * hp->cfl * H / a_norm);
    if (dta < dt) dt = dta;
  }
  if (div_v != 0.0) {
    const double dtv = hp->log_max_volume_change / fabs(div_v);
    if (dtv < dt) dt = dtv;
  }
  return dt;
}

/** Norm sqrt(T:T) of a symmetric tensor (xx xy xz yy yz zz). */
BOLIDE_INLINE double timestep_sym_norm(const double T[6]) {
  return sqrt(T[0] * T[0] + T[3] * T[3] + T[5] * T[5] + 2.0 * (T[1] * T[1] + T[2] * T[2] + T[4] * T[4]));
}

/** Limits on the relative change of density, energy and deviatoric stress in
 *  one step, dt = f (|q| + q_min) / |dq/dt| with f = SPH:max_relative_change
 *  (Schaefer et al. 2016, Sec. 3.5 and miluphcuda's scheme): q_min = 0 for
 *  rho, 1e-2 c_s^2 for u, 1e-3 rho c_s^2 (a thousandth of the bulk modulus)
 *  for |S|, so that quantities starting at zero do not stall the run. */
BOLIDE_INLINE double timestep_relative_change(const struct hydro_props *hp, double rho, double drho_dt,
                                              double u, double du_dt, double cs, const double S[6],
                                              const double dS[6]) {
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

#endif
