/* Ghost: finishing the density sums of one particle and one step of the
 * smoothing-length iteration.  Written once for CPU and GPU.
 *
 * The smoothing length solves n(h) h^3 = eta^3 (theory/sph.md, eq. 2), where
 * n(h) = sum_j W(r_ij, h) is the number density: h = eta n^(-1/3), i.e.
 * 4 pi/3 (kernel_gamma eta)^3 neighbours inside the support.  Newton-Raphson
 * on f(h) = n h^3 - eta^3, safeguarded by a bracket [h_lo, h_hi] and
 * bisection (as in Price 2012, section 3.3). */
#ifndef BOLIDE_GHOST_IACT_H
#define BOLIDE_GHOST_IACT_H

#include <math.h>

#include "src/inline.h"

/** Outcome of one iteration step. */
enum ghost_h_result {
  GHOST_H_CONVERGED = 0, /**< h is the solution within the tolerance */
  GHOST_H_AGAIN = 1,     /**< h was updated: redo the density sums */
  GHOST_H_TAYLOR = 2,    /**< h was updated by a Newton step small enough that the sums at the
                              new h are those at the old one plus the step times their
                              h-derivatives: correct them, do not redo them */
};

/** One step of the h iteration for a particle with smoothing length *h,
 *  number density n and dn/dh.  Updates *h, *h_lo, *h_hi; h_max caps h.
 *  Returns GHOST_H_CONVERGED, GHOST_H_AGAIN, or GHOST_H_TAYLOR when the
 *  Newton step is at most taylor relative (0: never): the neighbours' part
 *  of n hardly depends on h, and a single kernel term, as h^-3, has the
 *  second derivative 12 n / h^2, so the first-order sums at the new h are
 *  off by at most about 6 (step / h)^2 n, below tol for taylor =
 *  sqrt(tol / 6) (theory/sph.md section 2).  On GHOST_H_AGAIN *h is the
 *  h to redo the sums with; on GHOST_H_CONVERGED the sums at the h passed
 *  in are accepted, and *h is the best estimate of the root that they
 *  give (one more Newton step, within the tolerance of the h passed in):
 *  the caller keeps its h for this step's sums and may start the next
 *  step's iteration from the estimate (ghost_part_step). */
BOLIDE_INLINE int ghost_h_iterate(double *h, double *h_lo, double *h_hi, double n, double dn_dh,
                                  double eta, double tol, double taylor, double h_max) {
  const double h0 = *h;
  /* a first guess above the cap (an h of the initial conditions, a cap
   * lowered by the cells) is never accepted, even where its sums happen to
   * fit: in a homologous expansion they do.  Redo the sums at the cap. */
  if (h0 > h_max) {
    *h = h_max;
    return GHOST_H_AGAIN;
  }
  const double eta3 = eta * eta * eta;
  const double h03 = h0 * h0 * h0;
  const double f = n * h03 - eta3;
  const double df = dn_dh * h03 + 3.0 * n * h0 * h0;
  /* |f| / (3 eta^3) is the relative error of h to first order */
  if (fabs(f) <= 3.0 * eta3 * tol) {
    const double hn = (df > 0.0) ? h0 - f / df : h0;
    *h = (hn > 0.5 * h0 && hn < 2.0 * h0) ? (hn < h_max ? hn : h_max) : h0;
    return GHOST_H_CONVERGED;
  }
  if (f < 0.0) {
    if (h0 >= h_max) { /* too few neighbours but capped: accept */
      *h = h_max;
      return GHOST_H_CONVERGED;
    }
    if (h0 > *h_lo) *h_lo = h0;
  } else {
    if (h0 < *h_hi) *h_hi = h0;
  }
  double h1 = (df > 0.0) ? h0 - f / df : -1.0;
  if (h1 > 0.0 && fabs(h1 - h0) <= taylor * h0 && h1 <= h_max) {
    *h = h1;
    return GHOST_H_TAYLOR;
  }
  /* keep the step within a factor 2 and inside the bracket; else bisect */
  if (!(h1 > 0.5 * h0 && h1 < 2.0 * h0 && h1 > *h_lo && h1 < *h_hi)) {
    if (*h_hi < 1e300 && *h_lo > 0.0)
      h1 = sqrt(*h_lo * *h_hi);
    else
      h1 = (f < 0.0) ? 1.26 * h0 : 0.79 * h0; /* volume x2 or /2 */
  }
  if (h1 > h_max) h1 = h_max;
  *h = h1;
  /* a bracket narrower than the tolerance: done */
  if (*h_hi - *h_lo < tol * h1) return GHOST_H_CONVERGED;
  return GHOST_H_AGAIN;
}

/** The Balsara (1995) switch |div v| / (|div v| + |curl v| + 1e-4 c/h). */
BOLIDE_INLINE double ghost_balsara(double div_v, double curl_v_norm, double cs, double h) {
  const double a = fabs(div_v);
  const double d = a + curl_v_norm + 1e-4 * cs / h;
  return d > 0.0 ? a / d : 1.0;
}

#endif
