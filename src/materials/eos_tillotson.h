/* Tillotson equation of state (Tillotson 1962, General Atomic report
 * GA-3216; in the form of Melosh 1989, "Impact Cratering", Appendix II, and
 * Benz & Asphaug 1999, Icarus 142, 5, sect. 2.2).
 *
 * With eta = rho/rho0, mu = eta - 1, z = rho0/rho - 1 = 1/eta - 1 and
 * w = u / (E0 eta^2) + 1:
 *
 *  compressed (rho >= rho0) and cold expanded (rho < rho0, u <= Eiv):
 *    P_c = (a + b/w) rho u + A mu + B mu^2                          (T1)
 *  expanded (rho < rho0, u >= Ecv):
 *    P_e = a rho u + [ b rho u / w + A mu exp(-beta z) ] exp(-alpha z^2)
 *                                                                   (T2)
 *  hybrid (rho < rho0, Eiv < u < Ecv), linear in u (Melosh 1989, App. II;
 *  Benz & Asphaug 1999; Schaefer et al. 2016, A&A 590, A19):
 *    P_h = [ (u - Eiv) P_e + (Ecv - u) P_c ] / (Ecv - Eiv)          (T3)
 *
 * In the cold expanded state T1 gives negative pressures (tension), which
 * is what a solid with strength needs (Benz & Asphaug 1999); a fluid
 * without strength does not carry it: the material's P_min floor
 * (material.h; 0 by default without strength, as SWIFT's planetary
 * Tillotson's 0.01 Pa) is applied by material_eos().
 * Optional low-density ramp (SWIFT's planetary Tillotson): P_c is multiplied
 * by (eta - eta_zero)/(eta_min - eta_zero) for eta_zero < eta < eta_min and
 * set to 0 below eta_zero (eta_min = eta_zero = 0: off).
 *
 * Sound speed: the exact isentropic derivative of the pressure actually
 * returned, c^2 = (dP/drho)_u + P/rho^2 (dP/du)_rho (de = -P dV at constant
 * entropy, so du/drho = P/rho^2 along an isentrope).  In the hybrid region
 * this is the derivative of T3 itself, including the term (P_e - P_c)/(Ecv -
 * Eiv) from the u-dependence of the weights; it is NOT the linear
 * interpolation of c_c^2 and c_e^2 used by some codes (SWIFT, miluphcuda),
 * which is not the sound speed of T3.  The derivatives of T1 and T2 are in
 * theory/eos.md (eqs. T4-T7).  c^2 may be <= 0 (tension near the spinodal):
 * the material's cs_min floor is applied by material_eos().
 *
 * Temperature: T = u / cv when cv > 0 (a crude estimate that ignores the
 * cold compression energy). */
#ifndef BOLIDE_EOS_TILLOTSON_H
#define BOLIDE_EOS_TILLOTSON_H

#include "src/materials/eos_common.h"

/* clang-format off */
#define EOS_TILLOTSON_PARAMS(X)                                                                        \
  X(eos_tillotson, rho0, "rho0", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_DENSITY, "reference density rho_0") \
  X(eos_tillotson, A, "A", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_PRESSURE,                              \
    "Tillotson A (linear term; the bulk modulus at rho0, u = 0)")                                      \
  X(eos_tillotson, B, "B", NAN, 0.0, 0, INFINITY, MATERIAL_UNIT_PRESSURE, "Tillotson B (quadratic term)") \
  X(eos_tillotson, E0, "E0", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_ENERGY, "Tillotson E_0 (u_0)")       \
  X(eos_tillotson, Eiv, "Eiv", NAN, 0.0, 0, INFINITY, MATERIAL_UNIT_ENERGY,                            \
    "specific energy of incipient vaporisation")                                                       \
  X(eos_tillotson, Ecv, "Ecv", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_ENERGY,                            \
    "specific energy of complete vaporisation (> Eiv)")                                                \
  X(eos_tillotson, a, "a", NAN, 0.0, 0, 10.0, MATERIAL_UNIT_NONE, "Tillotson a")                       \
  X(eos_tillotson, b, "b", NAN, 0.0, 0, 10.0, MATERIAL_UNIT_NONE, "Tillotson b")                       \
  X(eos_tillotson, alpha, "alpha", NAN, 0.0, 0, 100.0, MATERIAL_UNIT_NONE, "Tillotson alpha")          \
  X(eos_tillotson, beta, "beta", NAN, 0.0, 0, 100.0, MATERIAL_UNIT_NONE, "Tillotson beta")             \
  X(eos_tillotson, eta_min, "eta_min", 0.0, 0.0, 0, 1.0, MATERIAL_UNIT_NONE,                           \
    "upper end of the low-density ramp of P_c (SWIFT; 0: off)")                                        \
  X(eos_tillotson, eta_zero, "eta_zero", 0.0, 0.0, 0, 1.0, MATERIAL_UNIT_NONE,                         \
    "P_c = 0 below rho/rho0 = eta_zero (SWIFT; <= eta_min)")                                           \
  X(eos_tillotson, cv, "cv", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_HEAT_CAPACITY,                       \
    "specific heat capacity for T = u / cv (0: no temperature)")
/* clang-format on */

/** Tillotson parameters (members: see EOS_TILLOTSON_PARAMS). */
struct eos_tillotson {
  EOS_TILLOTSON_PARAMS(EOS_PARAM_FIELD)
};

/** Regions of the Tillotson EOS (for tests and diagnostics). */
enum eos_tillotson_region {
  EOS_TILLOTSON_COMPRESSED = 0, /**< rho >= rho0, or rho < rho0 and u <= Eiv: T1 */
  EOS_TILLOTSON_EXPANDED = 1,   /**< rho < rho0 and u >= Ecv: T2 */
  EOS_TILLOTSON_HYBRID = 2,     /**< rho < rho0 and Eiv < u < Ecv: T3 */
};

/** Which formula applies at (rho, u). */
BOLIDE_INLINE enum eos_tillotson_region eos_tillotson_region(const struct eos_tillotson *p,
                                                             double rho, double u) {
  if (rho >= p->rho0 || u <= p->Eiv) return EOS_TILLOTSON_COMPRESSED;
  if (u >= p->Ecv) return EOS_TILLOTSON_EXPANDED;
  return EOS_TILLOTSON_HYBRID;
}

/** Compressed form T1 (with the optional low-density ramp) and its partial
 *  derivatives dP/drho at constant u and dP/du at constant rho. */
BOLIDE_INLINE void eos_tillotson_compressed(const struct eos_tillotson *p, double rho, double u,
                                            double *P, double *dPdrho, double *dPdu) {
  const double eta = rho / p->rho0;
  const double mu = eta - 1.0;
  const double w = 1.0 + u / (p->E0 * eta * eta);
  const double g = p->a + p->b / w;
  /* rho u dg/drho = 2 u b (w-1)/w^2 since dw/drho = -2 (w-1)/rho;
   * rho u dg/du = -rho b (w-1)/w^2 since dw/du = (w-1)/u */
  const double bw2 = p->b * (w - 1.0) / (w * w);
  double Pc = g * rho * u + p->A * mu + p->B * mu * mu;
  double dr = g * u + 2.0 * u * bw2 + (p->A + 2.0 * p->B * mu) / p->rho0;
  double du = rho * (g - bw2);
  if (eta < p->eta_min) {
    if (eta <= p->eta_zero) {
      Pc = dr = du = 0.0;
    } else {
      const double f = (eta - p->eta_zero) / (p->eta_min - p->eta_zero);
      const double dfdrho = 1.0 / (p->rho0 * (p->eta_min - p->eta_zero));
      dr = f * dr + Pc * dfdrho;
      du *= f;
      Pc *= f;
    }
  }
  *P = Pc;
  *dPdrho = dr;
  *dPdu = du;
}

/** Expanded form T2 and its partial derivatives (rho < rho0 only). */
BOLIDE_INLINE void eos_tillotson_expanded(const struct eos_tillotson *p, double rho, double u,
                                          double *P, double *dPdrho, double *dPdu) {
  const double eta = rho / p->rho0;
  const double mu = eta - 1.0;
  const double z = p->rho0 / rho - 1.0;
  const double w = 1.0 + u / (p->E0 * eta * eta);
  const double bw2 = p->b * (w - 1.0) / (w * w);
  const double eb = exp(-p->beta * z);
  const double ea = exp(-p->alpha * z * z);
  /* F = b rho u / w, G = A mu exp(-beta z), P_e = a rho u + (F + G) exp(-alpha z^2) */
  const double F = p->b * rho * u / w;
  const double G = p->A * mu * eb;
  double dr = p->a * u;
  double du = p->a * rho;
  if (ea > 0.0) {
    const double dF = p->b * u / w + 2.0 * u * bw2;
    const double dG = p->A * eb * (1.0 / p->rho0 + p->beta * mu * p->rho0 / (rho * rho));
    /* d exp(-alpha z^2)/drho = exp(-alpha z^2) 2 alpha z rho0 / rho^2 */
    dr += (dF + dG + (F + G) * 2.0 * p->alpha * z * p->rho0 / (rho * rho)) * ea;
    du += rho * (p->b / w - bw2) * ea;
  }
  *P = p->a * rho * u + (F + G) * ea;
  *dPdrho = dr;
  *dPdu = du;
}

/** Pressure and c^2 = (dP/drho)_u + P/rho^2 (dP/du)_rho of the Tillotson EOS
 *  (T1-T3).  u < 0 is treated as u = 0. */
BOLIDE_INLINE void eos_tillotson_eval(const struct eos_tillotson *p, double rho, double u,
                                      double *P, double *c2) {
  double Pt, dr, du;
  if (u < 0.0) u = 0.0;
  const enum eos_tillotson_region region = eos_tillotson_region(p, rho, u);
  if (region == EOS_TILLOTSON_COMPRESSED) {
    eos_tillotson_compressed(p, rho, u, &Pt, &dr, &du);
  } else if (region == EOS_TILLOTSON_EXPANDED) {
    eos_tillotson_expanded(p, rho, u, &Pt, &dr, &du);
  } else {
    double Pc, drc, duc, Pe, dre, due;
    eos_tillotson_compressed(p, rho, u, &Pc, &drc, &duc);
    eos_tillotson_expanded(p, rho, u, &Pe, &dre, &due);
    const double inv = 1.0 / (p->Ecv - p->Eiv);
    const double we = (u - p->Eiv) * inv, wc = (p->Ecv - u) * inv;
    Pt = we * Pe + wc * Pc;                     /* T3 */
    dr = we * dre + wc * drc;                   /* d(T3)/drho at constant u */
    du = we * due + wc * duc + (Pe - Pc) * inv; /* d(T3)/du at constant rho */
  }
  *P = Pt;
  *c2 = dr + Pt / (rho * rho) * du;
}

/** Pressure. */
BOLIDE_INLINE double eos_tillotson_pressure(const struct eos_tillotson *p, double rho, double u) {
  double P, c2;
  eos_tillotson_eval(p, rho, u, &P, &c2);
  return P;
}

/** Sound speed (0 where c^2 <= 0; no cs_min floor here). */
BOLIDE_INLINE double eos_tillotson_sound_speed(const struct eos_tillotson *p, double rho,
                                               double u) {
  double P, c2;
  eos_tillotson_eval(p, rho, u, &P, &c2);
  return c2 > 0.0 ? sqrt(c2) : 0.0;
}

/** Whether the temperature is defined (cv given). */
BOLIDE_INLINE int eos_tillotson_has_temperature(const struct eos_tillotson *p) {
  return p->cv > 0.0;
}

/** Temperature u / cv (0 without cv). */
BOLIDE_INLINE double eos_tillotson_temperature(const struct eos_tillotson *p, double rho,
                                               double u) {
  return p->cv > 0.0 ? u / p->cv : 0.0;
}

/** Cross-checks: Eiv < Ecv, eta_zero <= eta_min. */
static inline const char *eos_tillotson_check(const struct eos_tillotson *p, const char **key) {
  if (!(p->Ecv > p->Eiv)) {
    *key = "Ecv";
    return "must be larger than Eiv";
  }
  if (p->eta_zero > p->eta_min) {
    *key = "eta_zero";
    return "must not exceed eta_min";
  }
  if (p->eta_min > 0.0 && p->eta_zero == p->eta_min) {
    *key = "eta_zero";
    return "must be smaller than eta_min when eta_min > 0";
  }
  return NULL;
}

#endif
