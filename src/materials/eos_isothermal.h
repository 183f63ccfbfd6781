/* Isothermal gas: P = c_s^2 rho with a constant sound speed c_s (the
 * Boss & Bodenheimer 1979 collapse test).  Barotropic: u is ignored. */
#ifndef BOLIDE_EOS_ISOTHERMAL_H
#define BOLIDE_EOS_ISOTHERMAL_H

#include "src/materials/eos_common.h"

/* clang-format off */
#define EOS_ISOTHERMAL_PARAMS(X)                                                                       \
  X(eos_isothermal, cs, "cs", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_SPEED, "isothermal sound speed")    \
  X(eos_isothermal, rho0, "rho0", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_DENSITY,                        \
    "reference density (initial conditions and density floor only; 0: none)")
/* clang-format on */

/** Isothermal parameters (members: see EOS_ISOTHERMAL_PARAMS). */
struct eos_isothermal {
  EOS_ISOTHERMAL_PARAMS(EOS_PARAM_FIELD)
};

/** P = cs^2 rho; c^2 = dP/drho = cs^2 (no dependence on u). */
BOLIDE_INLINE void eos_isothermal_eval(const struct eos_isothermal *p, double rho, double u,
                                       double *P, double *c2) {
  *c2 = p->cs * p->cs;
  *P = *c2 * rho;
}

/** Pressure cs^2 rho. */
BOLIDE_INLINE double eos_isothermal_pressure(const struct eos_isothermal *p, double rho, double u) {
  return p->cs * p->cs * rho;
}

/** Sound speed cs. */
BOLIDE_INLINE double eos_isothermal_sound_speed(const struct eos_isothermal *p, double rho,
                                                double u) {
  return p->cs;
}

/** No temperature (it would need a molecular weight; not used). */
BOLIDE_INLINE int eos_isothermal_has_temperature(const struct eos_isothermal *p) {
  return 0;
}

/** Not defined: 0. */
BOLIDE_INLINE double eos_isothermal_temperature(const struct eos_isothermal *p, double rho,
                                                double u) {
  return 0.0;
}

/** Cross-checks beyond the per-key ranges: none. */
static inline const char *eos_isothermal_check(const struct eos_isothermal *p, const char **key) {
  return NULL;
}

#endif
