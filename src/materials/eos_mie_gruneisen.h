/* Mie-Grueneisen EOS with a shock-Hugoniot reference curve.
 *
 * The Hugoniot of a material with a linear shock-particle velocity relation
 * U_s = c0 + s u_p is, with mu = rho/rho0 - 1 (Meyers 1994, "Dynamic
 * Behavior of Materials", ch. 4-5),
 *   P_H = rho0 c0^2 mu (1 + mu) / [1 - (s - 1) mu]^2,
 * and its cubic expansion in mu, used by the SPH impact codes of Libersky &
 * Petschek 1991 and Libersky et al. 1993 (J. Comput. Phys. 109, 67), is
 *   P_H = a0 mu + b0 mu^2 + c0' mu^3,   mu > 0 (compression)
 *   P_H = a0 mu,                        mu <= 0 (tension)
 *   a0 = rho0 c0^2, b0 = a0 (2 s - 1), c0' = a0 (s - 1)(3 s - 1).   (MG1)
 * Off the Hugoniot, P = P_H + Gamma rho (u - e_H), with the Rankine-Hugoniot
 * energy e_H = P_H (1/rho0 - 1/rho) / 2 = P_H mu / (2 rho0 (1 + mu)) and
 * Gamma rho = Gamma0 rho0 (Meyers 1994):
 *   P = [1 - Gamma0 mu / (2 (1 + mu))] P_H + Gamma0 rho0 u,   mu > 0,  (MG2)
 *   P = a0 mu + Gamma0 rho0 u,                                mu <= 0. (MG3)
 * In expansion there is no shock Hugoniot to refer to (a rarefaction is
 * not a shock): MG3 is the linear cold curve plus the thermal pressure, the
 * expanded branch of the Grueneisen EOS of hydrocodes (e.g. LS-DYNA's
 * *EOS_GRUNEISEN).  MG2 continued to mu < 0 has the factor
 * 1 + Gamma0 |mu| / (2 (1 + mu)) > 1, which grows without bound as the
 * material expands (tension of -9.4 a0 at rho = rho0 / 10, against -0.9 a0
 * from MG3): expanded debris and spall would be held together by a tension
 * that the cold curve does not have.  MG2 and MG3 meet at mu = 0 with the
 * same P and dP/drho.
 * (Libersky et al. write the factor as 1 - Gamma0 mu / 2, its first-order
 * expansion; that form gives c^2 < 0 above mu ~ 0.7 for aluminium, so the
 * exact factor is used.)  Sound speed c^2 = (dP/drho)_u + P/rho^2
 * (dP/du)_rho with, for f = 1 - Gamma0 mu / (2 (1 + mu)),
 *   (dP/drho)_u = [ f P_H'(mu) - Gamma0 P_H / (2 (1 + mu)^2) ] / rho0,
 *   (dP/du)_rho = Gamma0 rho0
 * in compression, and (dP/drho)_u = a0 / rho0 in expansion.
 * Temperature T = u / cv when cv > 0. */
#ifndef BOLIDE_EOS_MIE_GRUNEISEN_H
#define BOLIDE_EOS_MIE_GRUNEISEN_H

#include "src/materials/eos_common.h"

/* clang-format off */
#define EOS_MIE_GRUNEISEN_PARAMS(X)                                                                    \
  X(eos_mie_gruneisen, rho0, "rho0", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_DENSITY, "reference density") \
  X(eos_mie_gruneisen, c0, "c0", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_SPEED,                           \
    "bulk sound speed: intercept of U_s = c0 + s u_p")                                                 \
  X(eos_mie_gruneisen, s, "s", NAN, 0.0, 0, 10.0, MATERIAL_UNIT_NONE, "slope s of U_s = c0 + s u_p")   \
  X(eos_mie_gruneisen, Gamma0, "Gamma0", NAN, 0.0, 0, 10.0, MATERIAL_UNIT_NONE,                        \
    "Grueneisen parameter at rho0 (Gamma rho = Gamma0 rho0)")                                          \
  X(eos_mie_gruneisen, cv, "cv", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_HEAT_CAPACITY,                   \
    "specific heat capacity for T = u / cv (0: no temperature)")
/* clang-format on */

/** Mie-Grueneisen parameters (members: see EOS_MIE_GRUNEISEN_PARAMS). */
struct eos_mie_gruneisen {
  EOS_MIE_GRUNEISEN_PARAMS(EOS_PARAM_FIELD)
};

/** Pressure (MG1-MG2) and c^2. */
BOLIDE_INLINE void eos_mie_gruneisen_eval(const struct eos_mie_gruneisen *p, double rho, double u,
                                          double *P, double *c2) {
  const double mu = rho / p->rho0 - 1.0;
  const double a0 = p->rho0 * p->c0 * p->c0;
  double PH, dPH;
  if (mu > 0.0) {
    const double b0 = a0 * (2.0 * p->s - 1.0);
    const double cc = a0 * (p->s - 1.0) * (3.0 * p->s - 1.0);
    PH = mu * (a0 + mu * (b0 + mu * cc));
    dPH = a0 + mu * (2.0 * b0 + 3.0 * mu * cc);
  } else {
    PH = a0 * mu;
    dPH = a0;
  }
  /* the Hugoniot-energy correction of MG2 in compression only; in
   * expansion P = a0 mu + Gamma0 rho0 u (MG3) */
  const double eta = rho / p->rho0; /* 1 + mu */
  const double f = mu > 0.0 ? 1.0 - 0.5 * p->Gamma0 * mu / eta : 1.0;
  const double df = mu > 0.0 ? 0.5 * p->Gamma0 * PH / (eta * eta) : 0.0;
  *P = f * PH + p->Gamma0 * p->rho0 * u;
  const double dPdrho = (f * dPH - df) / p->rho0;
  *c2 = dPdrho + *P / (rho * rho) * p->Gamma0 * p->rho0;
}

/** Pressure. */
BOLIDE_INLINE double eos_mie_gruneisen_pressure(const struct eos_mie_gruneisen *p, double rho,
                                                double u) {
  double P, c2;
  eos_mie_gruneisen_eval(p, rho, u, &P, &c2);
  return P;
}

/** Sound speed (0 where c^2 <= 0). */
BOLIDE_INLINE double eos_mie_gruneisen_sound_speed(const struct eos_mie_gruneisen *p, double rho,
                                                   double u) {
  double P, c2;
  eos_mie_gruneisen_eval(p, rho, u, &P, &c2);
  return c2 > 0.0 ? sqrt(c2) : 0.0;
}

/** Whether the temperature is defined (cv given). */
BOLIDE_INLINE int eos_mie_gruneisen_has_temperature(const struct eos_mie_gruneisen *p) {
  return p->cv > 0.0;
}

/** Temperature u / cv (0 without cv). */
BOLIDE_INLINE double eos_mie_gruneisen_temperature(const struct eos_mie_gruneisen *p, double rho,
                                                   double u) {
  return p->cv > 0.0 ? u / p->cv : 0.0;
}

/** Cross-checks beyond the per-key ranges: none. */
static inline const char *eos_mie_gruneisen_check(const struct eos_mie_gruneisen *p,
                                                  const char **key) {
  return NULL;
}

#endif
