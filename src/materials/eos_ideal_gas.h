/* Ideal gas: P = (gamma - 1) rho u, c^2 = gamma (gamma - 1) u.
 * (e.g. Landau & Lifshitz, Fluid Mechanics, sect. 80; SWIFT's default
 * planetary material 0.)  Temperature T = u / cv when cv > 0. */
#ifndef BOLIDE_EOS_IDEAL_GAS_H
#define BOLIDE_EOS_IDEAL_GAS_H

#include "src/materials/eos_common.h"

/* clang-format off */
#define EOS_IDEAL_GAS_PARAMS(X)                                                                        \
  X(eos_ideal_gas, gamma, "gamma", NAN, 1.0, 1, 10.0, MATERIAL_UNIT_NONE, "adiabatic index (> 1)")     \
  X(eos_ideal_gas, rho0, "rho0", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_DENSITY,                         \
    "reference density (initial conditions and density floor only; 0: none)")                          \
  X(eos_ideal_gas, cv, "cv", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_HEAT_CAPACITY,                       \
    "specific heat at constant volume for T = u / cv (0: no temperature)")
/* clang-format on */

/** Ideal-gas parameters (members: see EOS_IDEAL_GAS_PARAMS). */
struct eos_ideal_gas {
  EOS_IDEAL_GAS_PARAMS(EOS_PARAM_FIELD)
};

/** Pressure and squared sound speed of an ideal gas. */
BOLIDE_INLINE void eos_ideal_gas_eval(const struct eos_ideal_gas *p, double rho, double u,
                                      double *P, double *c2) {
  *P = (p->gamma - 1.0) * rho * u;
  /* (dP/drho)_u = (gamma-1) u, (dP/du)_rho = (gamma-1) rho */
  *c2 = (p->gamma - 1.0) * u + *P / (rho * rho) * (p->gamma - 1.0) * rho;
}

/** Pressure of an ideal gas. */
BOLIDE_INLINE double eos_ideal_gas_pressure(const struct eos_ideal_gas *p, double rho, double u) {
  return (p->gamma - 1.0) * rho * u;
}

/** Sound speed of an ideal gas (0 for u <= 0). */
BOLIDE_INLINE double eos_ideal_gas_sound_speed(const struct eos_ideal_gas *p, double rho,
                                               double u) {
  double P, c2;
  eos_ideal_gas_eval(p, rho, u, &P, &c2);
  return c2 > 0.0 ? sqrt(c2) : 0.0;
}

/** Whether the temperature is defined (cv given). */
BOLIDE_INLINE int eos_ideal_gas_has_temperature(const struct eos_ideal_gas *p) {
  return p->cv > 0.0;
}

/** Temperature u / cv (0 without cv). */
BOLIDE_INLINE double eos_ideal_gas_temperature(const struct eos_ideal_gas *p, double rho,
                                               double u) {
  return p->cv > 0.0 ? u / p->cv : 0.0;
}

/** Cross-checks beyond the per-key ranges: none. */
static inline const char *eos_ideal_gas_check(const struct eos_ideal_gas *p, const char **key) {
  return NULL;
}

#endif
