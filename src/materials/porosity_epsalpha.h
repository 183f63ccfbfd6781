/* epsilon-alpha porosity model (Wuennemann, Collins & Melosh 2006, Icarus
 * 180, 514, "WCM06"; Collins, Melosh & Wuennemann 2011, Int. J. Impact Eng.
 * 38, 434, "CMW11").  Equations EA1-EA6 of theory/porosity.md.
 *
 * The distention alpha is a function of the volumetric strain eps_v of the
 * bulk material (negative in compression; deps_v/dt = div v = -drho/dt /
 * rho), with these regimes (CMW11 sect. 2, eqs. 5-9):
 *   eps_v >= 0:            alpha_0
 *   eps_e <= eps_v < 0:    alpha_0 exp(chi kappa eps_v)          (elastic, EA1)
 *   eps_x <= eps_v < eps_e: alpha_e exp(kappa (eps_v - eps_e))   (exponential, EA2)
 *   eps_c <= eps_v < eps_x: 1 + (alpha_x - 1) ((eps_c - eps_v)/(eps_c - eps_x))^2
 *                                                                (power law, EA3)
 *   eps_v < eps_c:         1                                     (compacted)
 * with alpha_e = alpha_0 exp(chi kappa eps_e), alpha_x = alpha_e exp(kappa
 * (eps_x - eps_e)) and eps_c = eps_x + 2 (1 - alpha_x)/(kappa alpha_x), which
 * makes alpha and dalpha/deps continuous at eps_x (EA4).  chi = kappa_e /
 * kappa is CMW11's ratio of the elastic to the plastic compaction rate
 * (chi = 0, the default: WCM06, no elastic compaction, alpha = alpha_0
 * exp(kappa (eps_v - eps_e)) in the exponential regime).
 *
 * Evolution: dalpha/dt = (dalpha/deps_v) deps_v/dt while compacting
 * (deps_v/dt < 0) on the curve (alpha >= alpha(eps_v)), else 0 (EA5):
 * compaction is irreversible, alpha never increases.  Because alpha is an
 * explicit function of eps_v, the caller may instead (or in addition) set
 * alpha = min(alpha, alpha(eps_v)) after each drift (EA6), which is exact. */
#ifndef BOLIDE_POROSITY_EPSALPHA_H
#define BOLIDE_POROSITY_EPSALPHA_H

#include "src/materials/eos_common.h"

/* clang-format off */
#define POROSITY_EPSALPHA_PARAMS(X)                                                                    \
  X(porosity_epsalpha, alpha_0, "alpha_0", NAN, 1.0, 0, 100.0, MATERIAL_UNIT_NONE,                     \
    "initial distention alpha_0 = rho_s/rho")                                                          \
  X(porosity_epsalpha, eps_e, "eps_e", NAN, -1.0, 0, 0.0, MATERIAL_UNIT_NONE,                          \
    "volumetric strain at the elastic limit (<= 0)")                                                   \
  X(porosity_epsalpha, eps_x, "eps_x", NAN, -10.0, 0, 0.0, MATERIAL_UNIT_NONE,                         \
    "volumetric strain of the exponential to power-law transition (<= eps_e)")                        \
  X(porosity_epsalpha, kappa, "kappa", NAN, 0.0, 1, 100.0, MATERIAL_UNIT_NONE,                         \
    "exponential compaction rate kappa")                                                               \
  X(porosity_epsalpha, chi, "chi", 0.0, 0.0, 0, 1.0, MATERIAL_UNIT_NONE,                               \
    "ratio of elastic to plastic compaction rate (0: no elastic compaction)")
/* clang-format on */

/** epsilon-alpha parameters (members: see POROSITY_EPSALPHA_PARAMS) and the
 *  derived members filled by porosity_epsalpha_derive. */
struct porosity_epsalpha {
  POROSITY_EPSALPHA_PARAMS(EOS_PARAM_FIELD)
  double alpha_e; /**< distention at eps_e (derived, EA1) */
  double alpha_x; /**< distention at eps_x (derived, EA2) */
  double eps_c;   /**< strain of full compaction (derived, EA4) */
};

/** Fill alpha_e, alpha_x and eps_c from the parameters (EA1, EA2, EA4). */
BOLIDE_INLINE void porosity_epsalpha_derive(struct porosity_epsalpha *p) {
  p->alpha_e = p->alpha_0 * exp(p->chi * p->kappa * p->eps_e);
  p->alpha_x = p->alpha_e * exp(p->kappa * (p->eps_x - p->eps_e));
  p->eps_c = p->eps_x + 2.0 * (1.0 - p->alpha_x) / (p->kappa * p->alpha_x);
}

/** Distention on the compaction curve at volumetric strain eps (EA1-EA3). */
BOLIDE_INLINE double porosity_epsalpha_alpha(const struct porosity_epsalpha *p, double eps) {
  if (eps >= 0.0) return p->alpha_0;
  if (eps >= p->eps_e) return p->alpha_0 * exp(p->chi * p->kappa * eps);
  if (eps >= p->eps_x) return p->alpha_e * exp(p->kappa * (eps - p->eps_e));
  if (eps > p->eps_c) {
    const double f = (p->eps_c - eps) / (p->eps_c - p->eps_x);
    return 1.0 + (p->alpha_x - 1.0) * f * f;
  }
  return 1.0;
}

/** Slope dalpha/deps of the compaction curve (>= 0; derivative of EA1-EA3). */
BOLIDE_INLINE double porosity_epsalpha_slope(const struct porosity_epsalpha *p, double eps) {
  if (eps >= 0.0) return 0.0;
  if (eps >= p->eps_e) return p->chi * p->kappa * p->alpha_0 * exp(p->chi * p->kappa * eps);
  if (eps >= p->eps_x) return p->kappa * p->alpha_e * exp(p->kappa * (eps - p->eps_e));
  if (eps > p->eps_c) {
    const double d = p->eps_c - p->eps_x;
    return -2.0 * (p->alpha_x - 1.0) * (p->eps_c - eps) / (d * d);
  }
  return 0.0;
}

/** dalpha/dt from the volumetric strain eps and its rate deps_dt = div v
 *  (EA5): the slope of the curve times deps_dt while compacting on the
 *  curve (relative slack 1e-12), else 0.  Never positive. */
BOLIDE_INLINE double porosity_epsalpha_dalpha_dt(const struct porosity_epsalpha *p, double eps,
                                                 double deps_dt, double alpha) {
  if (!(deps_dt < 0.0) || !(alpha > 1.0)) return 0.0;
  if (alpha < porosity_epsalpha_alpha(p, eps) * (1.0 - 1e-12)) return 0.0;
  return porosity_epsalpha_slope(p, eps) * deps_dt;
}

#endif
