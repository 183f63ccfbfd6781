/* Polytrope: P = K rho^gamma, written P = P0 (rho / rho0)^gamma so that every
 * parameter has a fixed unit (K = P0 / rho0^gamma).  Barotropic: u is
 * ignored; c^2 = dP/drho = gamma P / rho. */
#ifndef BOLIDE_EOS_POLYTROPIC_H
#define BOLIDE_EOS_POLYTROPIC_H

#include "src/materials/eos_common.h"

/* clang-format off */
#define EOS_POLYTROPIC_PARAMS(X)                                                                       \
  X(eos_polytropic, gamma, "gamma", NAN, 0.0, 1, 10.0, MATERIAL_UNIT_NONE, "polytropic exponent")      \
  X(eos_polytropic, rho0, "rho0", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_DENSITY,                        \
    "reference density at which P = P0")                                                               \
  X(eos_polytropic, P0, "P0", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_PRESSURE,                           \
    "pressure at the reference density (K = P0 / rho0^gamma)")
/* clang-format on */

/** Polytropic parameters (members: see EOS_POLYTROPIC_PARAMS). */
struct eos_polytropic {
  EOS_POLYTROPIC_PARAMS(EOS_PARAM_FIELD)
};

/** P = P0 (rho/rho0)^gamma, c^2 = gamma P / rho. */
BOLIDE_INLINE void eos_polytropic_eval(const struct eos_polytropic *p, double rho, double u,
                                       double *P, double *c2) {
  *P = p->P0 * pow(rho / p->rho0, p->gamma);
  *c2 = p->gamma * *P / rho;
}

/** Pressure. */
BOLIDE_INLINE double eos_polytropic_pressure(const struct eos_polytropic *p, double rho, double u) {
  return p->P0 * pow(rho / p->rho0, p->gamma);
}

/** Sound speed sqrt(gamma P / rho). */
BOLIDE_INLINE double eos_polytropic_sound_speed(const struct eos_polytropic *p, double rho,
                                                double u) {
  return sqrt(p->gamma * eos_polytropic_pressure(p, rho, u) / rho);
}

/** No temperature. */
BOLIDE_INLINE int eos_polytropic_has_temperature(const struct eos_polytropic *p) {
  return 0;
}

/** Not defined: 0. */
BOLIDE_INLINE double eos_polytropic_temperature(const struct eos_polytropic *p, double rho,
                                                double u) {
  return 0.0;
}

/** Cross-checks beyond the per-key ranges: none. */
static inline const char *eos_polytropic_check(const struct eos_polytropic *p, const char **key) {
  return NULL;
}

#endif
