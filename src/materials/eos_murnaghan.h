/* Murnaghan EOS (Murnaghan 1944, Proc. Natl. Acad. Sci. 30, 244): the
 * bulk modulus grows linearly with pressure, K = K0 + n P, which integrates
 * to
 *   P = (K0 / n) [ (rho / rho0)^n - 1 ],
 *   c^2 = dP/drho = (K0 / rho0) (rho / rho0)^(n - 1).
 * Barotropic (u ignored).  Below rho / rho0 = eta_limit, P = 0 (tensile
 * cutoff as in the miluphcuda implementation, Schaefer et al. 2016); c^2
 * keeps the formula there so that the signal speed stays finite. */
#ifndef BOLIDE_EOS_MURNAGHAN_H
#define BOLIDE_EOS_MURNAGHAN_H

#include "src/materials/eos_common.h"

/* clang-format off */
#define EOS_MURNAGHAN_PARAMS(X)                                                                        \
  X(eos_murnaghan, rho0, "rho0", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_DENSITY, "reference density")    \
  X(eos_murnaghan, K0, "K0", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_PRESSURE,                            \
    "bulk modulus at zero pressure")                                                                   \
  X(eos_murnaghan, n, "n", NAN, 0.0, 1, 100.0, MATERIAL_UNIT_NONE, "pressure derivative dK/dP")        \
  X(eos_murnaghan, eta_limit, "eta_limit", 0.0, 0.0, 0, 1.0, MATERIAL_UNIT_NONE,                       \
    "P = 0 below rho/rho0 = eta_limit (0: no cutoff)")
/* clang-format on */

/** Murnaghan parameters (members: see EOS_MURNAGHAN_PARAMS). */
struct eos_murnaghan {
  EOS_MURNAGHAN_PARAMS(EOS_PARAM_FIELD)
};

/** Pressure and c^2 of the Murnaghan EOS. */
BOLIDE_INLINE void eos_murnaghan_eval(const struct eos_murnaghan *p, double rho, double u,
                                      double *P, double *c2) {
  const double eta = rho / p->rho0;
  const double etan1 = pow(eta, p->n - 1.0);
  *c2 = p->K0 / p->rho0 * etan1;
  *P = eta < p->eta_limit ? 0.0 : p->K0 / p->n * (etan1 * eta - 1.0);
}

/** Pressure. */
BOLIDE_INLINE double eos_murnaghan_pressure(const struct eos_murnaghan *p, double rho, double u) {
  double P, c2;
  eos_murnaghan_eval(p, rho, u, &P, &c2);
  return P;
}

/** Sound speed. */
BOLIDE_INLINE double eos_murnaghan_sound_speed(const struct eos_murnaghan *p, double rho,
                                               double u) {
  double P, c2;
  eos_murnaghan_eval(p, rho, u, &P, &c2);
  return sqrt(c2);
}

/** No temperature. */
BOLIDE_INLINE int eos_murnaghan_has_temperature(const struct eos_murnaghan *p) {
  return 0;
}

/** Not defined: 0. */
BOLIDE_INLINE double eos_murnaghan_temperature(const struct eos_murnaghan *p, double rho,
                                               double u) {
  return 0.0;
}

/** Cross-checks beyond the per-key ranges: none. */
static inline const char *eos_murnaghan_check(const struct eos_murnaghan *p, const char **key) {
  return NULL;
}

#endif
