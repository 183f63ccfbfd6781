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

#endif
