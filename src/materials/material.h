/* Materials: the table of materials a run uses, each with its equation of
 * state, its elastic moduli and the parameters of its strength and damage
 * models.
 *
 * Particles carry a material id (MaterialIDs, any int32 >= 0, SWIFT's
 * planetary ids included).  The engine looks a material up once per particle
 * (material_table_find) and calls material_eos(), which switches once on the
 * EOS type and calls one inline function of src/materials/eos_*.h.  All of
 * it compiles as C11 and as CUDA C++; the table has no pointers except the
 * node arrays of tabulated EOS, so it can be copied to a device as is.
 *
 * One list for everything: MATERIAL_EOS_TYPES (name in YAML, enum, struct,
 * functions), each EOS's EOS_*_PARAMS (struct members, YAML keys, ranges,
 * units, documentation), MATERIAL_STRENGTH_TYPES and MATERIAL_PARAMS (the
 * material-level keys). */
#ifndef BOLIDE_MATERIAL_H
#define BOLIDE_MATERIAL_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "src/inline.h"
#include "src/materials/eos_ideal_gas.h"
#include "src/materials/eos_isothermal.h"
#include "src/materials/eos_polytropic.h"
#include "src/materials/eos_liquid.h"
#include "src/materials/eos_murnaghan.h"
#include "src/materials/eos_tillotson.h"
#include "src/materials/eos_mie_gruneisen.h"
#include "src/materials/eos_table.h"
#include "src/materials/porosity.h"

struct params;
struct unit_system;

/** Kinds of unit of a parameter: the SI unit and the dimension M^a L^b T^c
 *  used to convert it to internal units (temperatures stay in K). */
#define MATERIAL_UNITS(X)                    \
  X(NONE, "-", 0, 0, 0)                      \
  X(DENSITY, "kg m^-3", 1, -3, 0)            \
  X(PRESSURE, "Pa", 1, -1, -2)               \
  X(ENERGY, "J kg^-1", 0, 2, -2)             \
  X(SPEED, "m s^-1", 0, 1, -1)               \
  X(HEAT_CAPACITY, "J kg^-1 K^-1", 0, 2, -2) \
  X(PER_VOLUME, "m^-3", 0, -3, 0)            \
  X(RATE, "s^-1", 0, 0, -1)                  \
  X(TEMPERATURE, "K", 0, 0, 0)               \
  X(PER_PRESSURE, "Pa^-1", -1, 1, 2)         \
  X(VISCOSITY, "Pa s", 1, -1, -1)

/** Unit kinds (MATERIAL_UNIT_DENSITY, ...). */
enum material_unit {
#define MATERIAL_UNIT_ENUM(name, si, a, b, c) MATERIAL_UNIT_##name,
  MATERIAL_UNITS(MATERIAL_UNIT_ENUM)
#undef MATERIAL_UNIT_ENUM
};

/** Every EOS: X(name, NAME, "doc").  `name` is the YAML value of `eos:`, the
 *  struct eos_name, the member of union material_eos_params and the prefix
 *  of its functions; EOS_NAME is the enum value. */
#define MATERIAL_EOS_TYPES(X)                                                              \
  X(ideal_gas, IDEAL_GAS, "ideal gas P = (gamma-1) rho u")                                 \
  X(isothermal, ISOTHERMAL, "isothermal gas P = cs^2 rho")                                 \
  X(polytropic, POLYTROPIC, "polytrope P = P0 (rho/rho0)^gamma")                           \
  X(liquid, LIQUID, "weakly compressible liquid P = c0^2 (rho - rho0) (Gray et al. 2001)") \
  X(murnaghan, MURNAGHAN, "Murnaghan 1944 P = K0/n ((rho/rho0)^n - 1)")                    \
  X(tillotson, TILLOTSON, "Tillotson 1962 (Melosh 1989; Benz & Asphaug 1999)")             \
  X(mie_gruneisen, MIE_GRUNEISEN, "Mie-Grueneisen with a shock Hugoniot reference")        \
  X(table, TABLE, "tabulated P, c_s (and T) on a (rho, u) grid")

/** EOS types. */
enum material_eos_type {
#define MATERIAL_EOS_ENUM(name, NAME, doc) EOS_##NAME,
  MATERIAL_EOS_TYPES(MATERIAL_EOS_ENUM)
#undef MATERIAL_EOS_ENUM
      EOS_COUNT
};

/** The parameters of a material's EOS, one member per EOS type. */
union material_eos_params {
#define MATERIAL_EOS_MEMBER(name, NAME, doc) struct eos_##name name;
  MATERIAL_EOS_TYPES(MATERIAL_EOS_MEMBER)
#undef MATERIAL_EOS_MEMBER
};

/** Strength models (yield functions in strength_*.h, dispatch in strength.h):
 *  X(name, NAME, "doc"). */
#define MATERIAL_STRENGTH_TYPES(X)                                                            \
  X(none, NONE, "fluid: no deviatoric stress")                                                \
  X(elastic, ELASTIC, "Hooke's law, no yielding")                                             \
  X(von_mises, VON_MISES, "von Mises yield stress Y0, reduced to 0 at melt (Benz & Asphaug)") \
  X(drucker_prager, DRUCKER_PRAGER, "Drucker-Prager: Y = cohesion + friction P, up to Y_M")   \
  X(mohr_coulomb, MOHR_COULOMB, "Mohr-Coulomb: Y = cohesion + friction P")                    \
  X(collins, COLLINS, "Collins et al. 2004: intact Lundborg + damaged Drucker-Prager")        \
  X(johnson_cook, JOHNSON_COOK, "Johnson & Cook 1983: (A + B eps^n)(1 + C ln eps')(1 - T*^m)")

/** Strength model types. */
enum material_strength_type {
#define MATERIAL_STRENGTH_ENUM(name, NAME, doc) STRENGTH_##NAME,
  MATERIAL_STRENGTH_TYPES(MATERIAL_STRENGTH_ENUM)
#undef MATERIAL_STRENGTH_ENUM
      STRENGTH_COUNT
};

/* Material-level keys (besides name, reference, eos, strength, swift_id and
 * the EOS parameters), in the format of the EOS lists (eos_common.h).
 * A NAN default on P_min, cs_min and bulk_modulus means "derived": see
 * material_finalize(). */
/* clang-format off */
#define MATERIAL_PARAMS(X)                                                                             \
  X(material, P_min, "P_min", NAN, -INFINITY, 0, INFINITY, MATERIAL_UNIT_PRESSURE,                     \
    "pressure floor of the EOS (default: 0 for a material without strength, which carries no tension, as SWIFT's planetary fluids; -inf, tension allowed, for a material with strength)") \
  X(material, density_floor, "density_floor", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_DENSITY,            \
    "smallest density used by the EOS (0: none)")                                                      \
  X(material, cs_min, "cs_min", NAN, 0.0, 0, INFINITY, MATERIAL_UNIT_SPEED,                            \
    "sound speed floor (default: 0.1 sqrt(A/rho0) for Tillotson, 0 otherwise)")                        \
  X(material, shear_modulus, "shear_modulus", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_PRESSURE,           \
    "shear modulus mu (0: a fluid)")                                                                   \
  X(material, viscosity, "viscosity", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_VISCOSITY,                  \
    "dynamic viscosity eta of a Newtonian fluid (strength none): deviatoric stress 2 eta e' (0: inviscid; water 1.0e-3)") \
  X(material, bulk_modulus, "bulk_modulus", NAN, 0.0, 0, INFINITY, MATERIAL_UNIT_PRESSURE,             \
    "bulk modulus K (default: rho0 c_s^2 of the EOS at rho0, u = 0)")                                  \
  X(material, yield_stress, "yield_stress", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_PRESSURE,             \
    "von Mises yield stress Y0; cohesion of the intact material for pressure-dependent models")       \
  X(material, yield_stress_max, "yield_stress_max", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_PRESSURE,     \
    "limiting (von Mises) strength Y_M of pressure-dependent models")                                  \
  X(material, cohesion_damaged, "cohesion_damaged", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_PRESSURE,     \
    "cohesion of the fully damaged material")                                                          \
  X(material, friction_intact, "friction_intact", 0.0, 0.0, 0, 100.0, MATERIAL_UNIT_NONE,              \
    "coefficient of internal friction of the intact material")                                         \
  X(material, friction_damaged, "friction_damaged", 0.0, 0.0, 0, 100.0, MATERIAL_UNIT_NONE,            \
    "coefficient of friction of the damaged material")                                                 \
  X(material, melt_energy, "melt_energy", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_ENERGY,                 \
    "specific energy of melting: strength falls to 0 (0: never)")                                      \
  X(material, jc_A, "jc_A", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_PRESSURE, "Johnson-Cook A")           \
  X(material, jc_B, "jc_B", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_PRESSURE, "Johnson-Cook B")           \
  X(material, jc_C, "jc_C", 0.0, 0.0, 0, 10.0, MATERIAL_UNIT_NONE, "Johnson-Cook C")                   \
  X(material, jc_m, "jc_m", 1.0, 0.0, 1, 10.0, MATERIAL_UNIT_NONE, "Johnson-Cook thermal exponent m")  \
  X(material, jc_n, "jc_n", 1.0, 0.0, 1, 10.0, MATERIAL_UNIT_NONE, "Johnson-Cook hardening exponent n") \
  X(material, jc_strain_rate_ref, "jc_strain_rate_ref", 1.0, 0.0, 1, INFINITY, MATERIAL_UNIT_RATE,     \
    "Johnson-Cook reference plastic strain rate")                                                      \
  X(material, T_ref, "T_ref", 293.0, 0.0, 0, INFINITY, MATERIAL_UNIT_TEMPERATURE,                      \
    "reference (room) temperature of Johnson-Cook")                                                    \
  X(material, T_melt, "T_melt", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_TEMPERATURE,                      \
    "melting temperature (0: none)")                                                                   \
  X(material, specific_heat, "specific_heat", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_HEAT_CAPACITY,      \
    "specific heat c_v for T = T_ref + u / c_v (Johnson-Cook; 0: the EOS's temperature)")              \
  X(material, jc_D1, "jc_D1", 0.0, -INFINITY, 0, INFINITY, MATERIAL_UNIT_NONE,                       \
    "Johnson-Cook (1985) fracture D1 (D1 = D2 = 0: no failure)")                                       \
  X(material, jc_D2, "jc_D2", 0.0, -INFINITY, 0, INFINITY, MATERIAL_UNIT_NONE, "Johnson-Cook fracture D2") \
  X(material, jc_D3, "jc_D3", 0.0, -INFINITY, 0, INFINITY, MATERIAL_UNIT_NONE,                       \
    "Johnson-Cook fracture D3 (exponent of the stress triaxiality)")                                   \
  X(material, jc_D4, "jc_D4", 0.0, -INFINITY, 0, INFINITY, MATERIAL_UNIT_NONE,                       \
    "Johnson-Cook fracture D4 (strain rate)")                                                          \
  X(material, jc_D5, "jc_D5", 0.0, -INFINITY, 0, INFINITY, MATERIAL_UNIT_NONE,                       \
    "Johnson-Cook fracture D5 (temperature)")                                                          \
  X(material, spall_pressure, "spall_pressure", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_PRESSURE,       \
    "Johnson-Cook fracture also where the pressure falls below -spall_pressure (0: never)")            \
  X(material, weibull_k, "weibull_k", 0.0, 0.0, 0, INFINITY, MATERIAL_UNIT_PER_VOLUME,                 \
    "Weibull k of the flaw distribution (0: no brittle damage)")                                       \
  X(material, weibull_m, "weibull_m", 0.0, 0.0, 0, 100.0, MATERIAL_UNIT_NONE, "Weibull m")          \
  X(material, shear_failure_strain, "shear_failure_strain", 0.0, 0.0, 0, 10.0, MATERIAL_UNIT_NONE,   \
    "shear damage (Collins et al. 2004): plastic strain at failure at low pressure eps_fb (0: no shear damage)") \
  X(material, shear_failure_slope, "shear_failure_slope", 1e-11, 0.0, 0, INFINITY,                  \
    MATERIAL_UNIT_PER_PRESSURE, "shear damage: growth of the failure strain with pressure B, eps_f = max(eps_fb, B (P - P_c))") \
  X(material, shear_failure_pressure, "shear_failure_pressure", 3e8, -INFINITY, 0, INFINITY,        \
    MATERIAL_UNIT_PRESSURE, "shear damage: pressure P_c above which the failure strain grows")
/* clang-format on */

#define MATERIAL_NAME_LEN 48
#define MATERIAL_REFERENCE_LEN 256
/** Largest number of materials in one run. */
#define MATERIAL_MAX 32
/** Ids below this are found by a direct lookup; larger ids by a search. */
#define MATERIAL_ID_DIRECT 512

/** One material. */
struct material {
  int32_t id;                             /**< material id (MaterialIDs), >= 0 */
  int32_t swift_id;                       /**< SWIFT planetary id it stands for, -1: none */
  char name[MATERIAL_NAME_LEN];           /**< name ("basalt") */
  char reference[MATERIAL_REFERENCE_LEN]; /**< where the parameters come from */
  enum material_eos_type eos_type;        /**< which member of eos is used */
  union material_eos_params eos;          /**< the EOS parameters */
  enum material_strength_type strength;   /**< strength model */
  struct porosity porosity;               /**< porosity model (porosity.h; none by default) */
  double rho0;                            /**< reference density (copied from the EOS) */
  int u_floor;                            /**< 1 when the EOS has no meaning at u < 0 (ideal gas,
                                               tables): the kick keeps u >= 0 (drift.h) */
  MATERIAL_PARAMS(EOS_PARAM_FIELD)        /**< the keys of MATERIAL_PARAMS, see there */
  /** 1: fixed boundary particles (key boundary: true): they take part in their neighbours' sums
   *  as any particle but are never moved or kicked (kick2_rates; theory/boundaries.md) */
  int boundary;
};

/** The materials of a run. */
struct material_table {
  int n;                                   /**< number of materials */
  struct material mats[MATERIAL_MAX];      /**< the materials, in input order */
  int16_t index_of_id[MATERIAL_ID_DIRECT]; /**< index in mats of id < MATERIAL_ID_DIRECT, -1 */
};

/** The material of a given id, NULL if the table has none. */
BOLIDE_INLINE const struct material *material_table_find(const struct material_table *t,
                                                         int32_t id) {
  if (id >= 0 && id < MATERIAL_ID_DIRECT) {
    const int k = t->index_of_id[id];
    return k >= 0 ? &t->mats[k] : NULL;
  }
  for (int k = 0; k < t->n; k++)
    if (t->mats[k].id == id) return &t->mats[k];
  return NULL;
}

/** Pressure P and sound speed cs of material `mat` at density rho and
 *  specific internal energy u: clamps rho to the density floor, switches
 *  once on the EOS type, applies the pressure floor P_min (where it acts the
 *  pressure does not change with rho or u: c^2 = 0) and the cs_min floor.
 *  The floors change only what the force and energy equations are given;
 *  both use the same P, so the pairwise exchange still conserves energy. */
BOLIDE_INLINE void material_eos(const struct material *mat, double rho, double u, double *P,
                                double *cs) {
  double c2 = 0.0, p = 0.0;
  if (rho < mat->density_floor) rho = mat->density_floor;
  if (rho > 0.0) {
    switch (mat->eos_type) {
#define MATERIAL_EOS_CASE(name, NAME, doc)              \
  case EOS_##NAME:                                      \
    eos_##name##_eval(&mat->eos.name, rho, u, &p, &c2); \
    break;
      MATERIAL_EOS_TYPES(MATERIAL_EOS_CASE)
#undef MATERIAL_EOS_CASE
      default:
        break;
    }
  }
  if (p < mat->P_min) {
    p = mat->P_min;
    c2 = 0.0;
  }
  *P = p;
  *cs = sqrt(c2 > mat->cs_min * mat->cs_min ? c2 : mat->cs_min * mat->cs_min);
}

/** Whether particles of material `mat` carry a deviatoric stress: a solid
 *  (a strength model) or a viscous fluid (theory/fluids.md).  Runs with such
 *  a material need the gradient tasks. */
BOLIDE_INLINE int material_has_stress(const struct material *mat) {
  return mat->strength != STRENGTH_NONE || mat->viscosity > 0.0;
}

/** Whether particles of material `mat` take tensile damage: Weibull flaws
 *  (weibull_k > 0) and a shear modulus (tasks/damage). */
BOLIDE_INLINE int material_is_brittle(const struct material *mat) {
  return mat->weibull_k > 0.0 && mat->shear_modulus > 0.0;
}

/** Temperature of material `mat` at (rho, u); 0 where its EOS defines none. */
BOLIDE_INLINE double material_temperature(const struct material *mat, double rho, double u) {
  if (rho < mat->density_floor) rho = mat->density_floor;
  switch (mat->eos_type) {
#define MATERIAL_EOS_CASE(name, NAME, doc) \
  case EOS_##NAME:                         \
    return eos_##name##_temperature(&mat->eos.name, rho, u);
    MATERIAL_EOS_TYPES(MATERIAL_EOS_CASE)
#undef MATERIAL_EOS_CASE
    default:
      return 0.0;
  }
}

/* ---- host functions (material.c, material_params.c) ---- */

/** Whether the material's EOS defines a temperature. */
int material_has_temperature(const struct material *mat);

/** Name of an EOS type ("tillotson"), and the type of a name (-1 if none). */
const char *material_eos_name(enum material_eos_type type);
int material_eos_from_name(const char *name);
/** Name of a strength model, and the model of a name (-1 if none). */
const char *material_strength_name(enum material_strength_type type);
int material_strength_from_name(const char *name);

/** Start a material: id, name, EOS type, every key at its default (NAN where
 *  the key is required). */
void material_init(struct material *mat, int32_t id, const char *name, enum material_eos_type type);

/** Set a key ("A", "shear_modulus") of the material or of its EOS.  Returns 0,
 *  or -1 with a message "material 'NAME': key 'K' ..." in msg when the key
 *  is unknown or the value out of range. */
int material_set(struct material *mat, const char *key, double value, char *msg, size_t len);

/** Fill the derived members (rho0 from the EOS; cs_min and bulk_modulus
 *  where not given) and check the material: every required key given, every
 *  value in range, the EOS's cross-checks.  Returns 0, or -1 with a one-line
 *  message "material 'NAME': key 'K' must be positive" in msg. */
int material_finalize(struct material *mat, char *msg, size_t len);

/** Check a material without changing it (the checks of material_finalize). */
int material_check(const struct material *mat, char *msg, size_t len);

/** Empty table. */
void material_table_init(struct material_table *t);
/** Add a finalized material; stops with an error on a duplicate id or a
 *  full table.  Returns the stored copy. */
struct material *material_table_add(struct material_table *t, const struct material *mat);
/** Free the node arrays of tabulated EOS. */
void material_table_free(struct material_table *t);

/** Convert every dimensional parameter from SI to the internal unit system
 *  (call once, after material_table_from_params, when it is not SI). */
void material_table_convert_units(struct material_table *t, const struct unit_system *us);

/** Load a tabulated EOS from a text file (format 0: columns rho u P [cs];
 *  format 1: rho T u P [cs], converted to a (rho, u) grid; format 2: SWIFT's
 *  planetary tables, material_eos_table_load_swift; format 3: miluphcuda's
 *  ANEOS tables, material_eos_table_load_miluphcuda).  Errors stop with
 *  "FILE:LINE: ..." naming the table file. */
void material_eos_table_load(struct eos_table *tab, const char *filename, int format);

/** Load a table in the format of SWIFT's planetary EOS (SESAME-like, as woma
 *  writes them for material ids 300-307, 400-402 and 900-909): 12 header
 *  lines, the version date, N_RHO N_T, the densities, the temperatures, then
 *  "u P c s" for every (rho, T) with rho varying fastest, in SI.  Converted to
 *  a (rho, u) grid as format 1 is. */
void material_eos_table_load_swift(struct eos_table *tab, const char *filename);

/** Load a table in the format of miluphcuda's ANEOS lookup tables (its
 *  eos.type = 7, eos.table_path): 3 header lines, then one row per (rho, e)
 *  node, "rho e P T cs [s phase_flag ...]", e varying fastest, in SI.  The
 *  axes may have any strictly increasing, positive nodes (log-spaced ones
 *  take the fast path of eos_table.h); outside the densities the table is
 *  extrapolated linearly in rho, as miluphcuda does.  n_rho and n_e
 *  (miluphcuda's keys) are checked against the file when > 0, else taken
 *  from it. */
void material_eos_table_load_miluphcuda(struct eos_table *tab, const char *filename, int n_rho,
                                        int n_e);

/** Fill the table from the parameter file's Materials section (values in SI;
 *  see examples/parameters.yml and examples/materials.yml).  Without a
 *  Materials section: one ideal gas, id 0, with gamma = SPH:gamma.  Every
 *  error stops with "FILE:LINE: material 'NAME': key 'K' ...". */
void material_table_from_params(struct material_table *t, const struct params *p);

/** Read one named material of a library file (examples/materials.yml) into
 *  mat, with the given id (bolide-eos, tests). */
void material_from_library(struct material *mat, const char *library, const char *name, int32_t id);

/** The default library: $BOLIDE_MATERIALS if set, else the installed
 *  materials.yml, else the source tree's examples/materials.yml. */
const char *material_default_library(void);

/** Write the documentation of every EOS and material key as YAML comments
 *  (bolide-eos --keys, the reference parameter file). */
void material_write_keys(FILE *f);

/** Print one line per material (id, name, EOS, rho0, reference) to the log. */
void material_table_log(const struct material_table *t);

#endif
