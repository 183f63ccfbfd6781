/* "Liquid" (weakly compressible) EOS: P = c0^2 (rho - rho0).
 *
 * Monaghan 1994 (J. Comput. Phys. 110, 399) and Gray, Monaghan & Swift 2001
 * (Comput. Methods Appl. Mech. Engrg. 190, 6641, the colliding rubber rings:
 * "p = c0^2 (rho - rho0)"); Schaefer et al. 2016 (A&A 590, A19) list it as
 * the "liquid" EOS of miluphcuda.  It is the Murnaghan form with n = 1 and
 * K0 = rho0 c0^2.  Below rho / rho0 = eta_limit the material is taken as
 * cavitated (or fragmented) and P = 0 (eta_limit = 0: no cutoff).
 * Barotropic: u is ignored.  c^2 = dP/drho = c0^2 everywhere: in the
 * cavitated branch P is flat, but c0 is kept as the signal speed (the
 * material re-compresses at c0), so the time step does not collapse.
 *
 * The sound speed is given either directly (c0) or through the
 * compressibility (bulk) modulus K0 of the liquid, c0 = sqrt(K0 / rho0):
 * water, rho0 = 1000 kg/m^3 and K0 = 2.2 GPa, has c0 = 1483 m/s (the
 * weakly compressible water of Eghtesad & Knezevic 2018, Comp. Part. Mech.
 * 5, 387; theory/eos.md, "Weakly compressible liquid"). */
#ifndef BOLIDE_EOS_LIQUID_H
#define BOLIDE_EOS_LIQUID_H

#include "src/materials/eos_common.h"

/* clang-format off */
#define EOS_LIQUID_PARAMS(X)                                                                           \
  X(eos_liquid, rho0, "rho0", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_DENSITY, "reference density")       \
  X(eos_liquid, c0, "c0", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_SPEED,                                  \
    "bulk sound speed (give c0 or K0)")                                                                \
  X(eos_liquid, K0, "K0", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_PRESSURE,                               \
    "compressibility (bulk) modulus: c0 = sqrt(K0/rho0) (give c0 or K0)")                             \
  X(eos_liquid, eta_limit, "eta_limit", 0.0, 0.0, 0, 1.0, MATERIAL_UNIT_NONE,                          \
    "P = 0 below rho/rho0 = eta_limit (cavitation; 0: no cutoff)")
/* clang-format on */

/** Liquid parameters (members: see EOS_LIQUID_PARAMS). */
struct eos_liquid {
  EOS_LIQUID_PARAMS(EOS_PARAM_FIELD)
};

/** Squared sound speed: c0^2, or K0 / rho0 when the liquid is given by its
 *  bulk modulus. */
BOLIDE_INLINE double eos_liquid_c2(const struct eos_liquid *p) {
  return p->c0 > 0.0 ? p->c0 * p->c0 : p->K0 / p->rho0;
}

/** P = c0^2 (rho - rho0) (Gray et al. 2001), 0 below the cutoff; c^2 = c0^2. */
BOLIDE_INLINE void eos_liquid_eval(const struct eos_liquid *p, double rho, double u, double *P,
                                   double *c2) {
  *c2 = eos_liquid_c2(p);
  *P = rho < p->eta_limit * p->rho0 ? 0.0 : *c2 * (rho - p->rho0);
}

/** Pressure. */
BOLIDE_INLINE double eos_liquid_pressure(const struct eos_liquid *p, double rho, double u) {
  double P, c2;
  eos_liquid_eval(p, rho, u, &P, &c2);
  return P;
}

/** Sound speed c0. */
BOLIDE_INLINE double eos_liquid_sound_speed(const struct eos_liquid *p, double rho, double u) {
  return sqrt(eos_liquid_c2(p));
}

/** No temperature. */
BOLIDE_INLINE int eos_liquid_has_temperature(const struct eos_liquid *p) {
  return 0;
}

/** Not defined: 0. */
BOLIDE_INLINE double eos_liquid_temperature(const struct eos_liquid *p, double rho, double u) {
  return 0.0;
}

/** Cross-checks beyond the per-key ranges: exactly one of c0 and K0. */
static inline const char *eos_liquid_check(const struct eos_liquid *p, const char **key) {
  *key = "c0";
  if (!(p->c0 > 0.0) && !(p->K0 > 0.0))
    return "is required for EOS liquid (or its bulk modulus K0)";
  if (p->c0 > 0.0 && p->K0 > 0.0) return "and K0 cannot both be given (c0 = sqrt(K0/rho0))";
  return NULL;
}

#endif
