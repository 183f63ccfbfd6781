/* The time-step limiter's wake decided in the density phase
 * (TimeIntegration:limiter_wake: density; theory/sph.md section 8).  In a
 * density pair of an active particle a and a sleeping neighbour s within
 * a's support, s is asked to wake when its bin is longer than
 *   - a's bin + TimeIntegration:max_bin_ratio (the limiter's rule), or
 *   - its own Courant bin of this pair: 2 C H_s / v_sig,as (S19 with the
 *     pair's signal velocity, the force loop's v_sig_dt: the sound speeds
 *     of the solids' longitudinal waves, c_a + c_s - beta mu_as, mu_as the
 *     approach speed), so that a shock wakes it before it arrives.
 * The request, the shortest bin asked, goes into s's wake field; s's ghost
 * then makes it active for the rest of the step (ghost_cpu.c) and the kick
 * closes its truncated step (kick2_part_bins).  Pure per-pair function for
 * the CPU's density loops (density_cpu.c). */
#ifndef BOLIDE_DENSITY_WAKE_H
#define BOLIDE_DENSITY_WAKE_H

#include <math.h>

#include "src/inline.h"
#include "src/part.h"
#include "src/timeline.h"
#include "tasks/hydro/kernel.h"

/** What the density loops need to decide a wake. */
struct density_wake {
  int limit;          /**< TimeIntegration:max_bin_ratio */
  int solids;         /**< the signal velocity of the longitudinal sound speeds */
  double cfl, beta;   /**< SPH:CFL_condition, the viscosity's beta */
  struct timeline tl; /**< the run's time line (the bins of a time step) */
};

/** Active particle a and sleeping particle s at squared distance r2 < H_a^2,
 *  dx = x_a - x_s, dv = v_a - v_s (predicted velocities): s's wake request
 *  (TIMELINE_NR_BINS + 1 - the bin asked, the larger the shorter) raised
 *  where one of the two rules asks for a bin shorter than its own. */
BOLIDE_INLINE void density_wake_pair(struct parts *BOLIDE_RESTRICT p, size_t a, size_t s, double r2,
                                     const double dx[3], const double dv[3],
                                     const struct density_wake *w) {
  int want = p->time_bin[a] + w->limit;
  const double dvdx = dv[0] * dx[0] + dv[1] * dx[1] + dv[2] * dx[2];
  const double mu = (dvdx < 0.0 && r2 > 0.0) ? dvdx / sqrt(r2) : 0.0;
  const double *c = w->solids ? p->cl : p->cs;
  const double v_sig = c[a] + c[s] - w->beta * mu;
  if (v_sig > 0.0) {
    int b = timeline_bin(&w->tl, 2.0 * w->cfl * kernel_gamma * p->h[s] / v_sig);
    if (b < 1) b = 1;
    if (b < want) want = b;
  }
  if (p->time_bin[s] > want) {
    const int32_t req = TIMELINE_NR_BINS + 1 - want;
    if (req > p->wake[s]) p->wake[s] = req;
  }
}

#endif
