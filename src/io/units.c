/* Unit systems: see units.h.
 *
 * A unit system is five base units expressed in cgs.  Conversion factors
 * are formed as one quotient of two products of integer powers of the base
 * units, so that conversions between systems whose units are powers of ten
 * (SI <-> cgs) are correctly rounded: kg m^-3 -> g cm^-3 is exactly 1e-3. */
#include "src/io/units.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "src/io/params.h"

/** Gravitational constant in cm^3 g^-1 s^-2 (CODATA 2018). */
#define UNITS_G_CGS 6.67430e-8
/** Boltzmann constant in erg K^-1 (exact since the 2019 SI). */
#define UNITS_K_B_CGS 1.380649e-16
/** Mass of a hydrogen atom in g. */
#define UNITS_M_H_CGS 1.6735575e-24

void units_init_si(struct unit_system *us) {
  us->mass_cgs = 1000.;
  us->length_cgs = 100.;
  us->time_cgs = 1.;
  us->current_cgs = 1.;
  us->temperature_cgs = 1.;
  us->G = 0.;
}

void units_init_cgs(struct unit_system *us) {
  us->mass_cgs = 1.;
  us->length_cgs = 1.;
  us->time_cgs = 1.;
  us->current_cgs = 1.;
  us->temperature_cgs = 1.;
  us->G = 0.;
}

void units_init_from_params(struct unit_system *us, const struct params *p) {
  units_init_si(us);
  if (!p) return;
  us->mass_cgs = params_get_real(p, "InternalUnitSystem:UnitMass_in_cgs");
  us->length_cgs = params_get_real(p, "InternalUnitSystem:UnitLength_in_cgs");
  us->time_cgs = us->length_cgs / params_get_real(p, "InternalUnitSystem:UnitVelocity_in_cgs");
  us->current_cgs = params_get_real(p, "InternalUnitSystem:UnitCurrent_in_cgs");
  us->temperature_cgs = params_get_real(p, "InternalUnitSystem:UnitTemp_in_cgs");
  us->G = params_get_real(p, "PhysicalConstants:G");
}

/** Multiply *num or *den by the ratio (from/to)^e of one base unit, keeping
 *  every power positive so that each factor is exact when it can be. */
static void units_ratio_power(double from, double to, int e, double *num, double *den) {
  if (e > 0) {
    *num *= pow(from, e);
    *den *= pow(to, e);
  } else if (e < 0) {
    *num *= pow(to, -e);
    *den *= pow(from, -e);
  }
}

double units_conversion_factor(const struct unit_system *from, const struct unit_system *to, int a,
                               int b, int c) {
  double num = 1., den = 1.;
  units_ratio_power(from->mass_cgs, to->mass_cgs, a, &num, &den);
  units_ratio_power(from->length_cgs, to->length_cgs, b, &num, &den);
  units_ratio_power(from->time_cgs, to->time_cgs, c, &num, &den);
  return num / den;
}

double units_cgs_factor(const struct unit_system *us, int a, int b, int c) {
  struct unit_system cgs;
  units_init_cgs(&cgs);
  return units_conversion_factor(us, &cgs, a, b, c);
}

double units_G(const struct unit_system *us) {
  if (us->G > 0.) return us->G;
  struct unit_system cgs;
  units_init_cgs(&cgs);
  return UNITS_G_CGS * units_conversion_factor(&cgs, us, -1, 3, -2);
}

double units_k_B(const struct unit_system *us) {
  /* energy per temperature: erg -> internal energy, per K -> per internal
   * temperature unit (one internal unit is temperature_cgs K) */
  struct unit_system cgs;
  units_init_cgs(&cgs);
  return UNITS_K_B_CGS * units_conversion_factor(&cgs, us, 1, 2, -2) * us->temperature_cgs;
}

double units_m_H(const struct unit_system *us) {
  struct unit_system cgs;
  units_init_cgs(&cgs);
  return UNITS_M_H_CGS * units_conversion_factor(&cgs, us, 1, 0, 0);
}

/** Append " SYMBOL" or " SYMBOL^E" for a base unit with exponent e != 0. */
static void units_append(char *buf, int len, const char *symbol, int e) {
  size_t n = strlen(buf);
  if (e == 0 || (int)n >= len) return;
  if (e == 1)
    snprintf(buf + n, (size_t)len - n, "%s%s", n > 1 ? " " : "", symbol);
  else
    snprintf(buf + n, (size_t)len - n, "%s%s^%d", n > 1 ? " " : "", symbol, e);
}

void units_cgs_string(int a, int b, int c, char *buf, int len) {
  if (len < 1) return;
  snprintf(buf, (size_t)len, "[");
  units_append(buf, len, "g", a);
  units_append(buf, len, "cm", b);
  units_append(buf, len, "s", c);
  size_t n = strlen(buf);
  snprintf(buf + n, (size_t)len - n, "%s]", n == 1 ? "-" : "");
}
