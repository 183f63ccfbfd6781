/* Unit systems.
 *
 * Bolide computes in an internal unit system (InternalUnitSystem section,
 * SI by default).  Files declare their units in /Units with SWIFT's
 * attribute names ("Unit mass in cgs (U_M)", "Unit length in cgs (U_L)",
 * "Unit time in cgs (U_t)", "Unit current in cgs (U_I)", "Unit temperature
 * in cgs (U_T)"); a quantity of dimension M^a L^b T^c converts between two
 * systems by the product of the base-unit ratios. */
#ifndef BOLIDE_UNITS_H
#define BOLIDE_UNITS_H

struct params;

struct unit_system {
  double mass_cgs;        /**< one internal mass unit in g */
  double length_cgs;      /**< one internal length unit in cm */
  double time_cgs;        /**< one internal time unit in s */
  double current_cgs;     /**< one internal current unit in A */
  double temperature_cgs; /**< one internal temperature unit in K */
  double G;               /**< Newton's constant in these units when set by the parameter
                               file (PhysicalConstants:G, SWIFT's key); 0: the CODATA value */
};

/** SI: kg, m, s, A, K. */
void units_init_si(struct unit_system *us);
/** cgs: g, cm, s, A, K. */
void units_init_cgs(struct unit_system *us);
/** From the InternalUnitSystem section (UnitMass_in_cgs, UnitLength_in_cgs,
 *  UnitVelocity_in_cgs, UnitCurrent_in_cgs, UnitTemp_in_cgs); SI when the
 *  section is absent. */
void units_init_from_params(struct unit_system *us, const struct params *p);

/** Factor converting a quantity of dimension M^a L^b T^c from system `from`
 *  to system `to`: value_to = value_from * factor. */
double units_conversion_factor(const struct unit_system *from, const struct unit_system *to, int a,
                               int b, int c);
/** Factor from internal units to cgs for dimension M^a L^b T^c. */
double units_cgs_factor(const struct unit_system *us, int a, int b, int c);

/** Physical constants in internal units. */
double units_G(const struct unit_system *us);   /**< gravitational constant (us->G when set) */
double units_k_B(const struct unit_system *us); /**< Boltzmann constant */
double units_m_H(const struct unit_system *us); /**< hydrogen mass */

/** A string such as "[cm s^-1]" for the dimension, in cgs (for XDMF and
 *  dataset attributes). */
void units_cgs_string(int a, int b, int c, char *buf, int len);

#endif
