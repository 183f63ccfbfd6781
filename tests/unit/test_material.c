/* The material table without YAML: parameter validation (one line naming
 * material and key), defaults and derived members, lookup by id (small,
 * SWIFT planetary and large ids), and conversion to internal units. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "src/materials/material.h"
#include "src/io/units.h"

#include "tests/helpers/check.h"

/** Basalt of Benz & Asphaug 1999 through material_set (as the parser does). */
static void basalt(struct material *m, int id) {
  char msg[256];
  material_init(m, id, "basalt", EOS_TILLOTSON);
  const char *keys[] = {"rho0", "A", "B",     "E0",   "Eiv",           "Ecv",
                        "a",    "b", "alpha", "beta", "shear_modulus", "yield_stress"};
  const double vals[] = {2700, 2.67e10, 2.67e10, 4.87e8, 4.72e6,  1.82e7,
                         0.5,  1.5,     5,       5,      2.27e10, 3.5e9};
  for (int k = 0; k < 12; k++)
    CHECK(material_set(m, keys[k], vals[k], msg, sizeof msg) == 0, "set %s: %s", keys[k], msg);
  m->strength = STRENGTH_VON_MISES;
}

/** The message must be exactly one line and contain `want`. */
static void expect(const char *msg, const char *want) {
  CHECK(strstr(msg, want) != NULL && strchr(msg, '\n') == NULL, "message '%s' should contain '%s'",
        msg, want);
}

int main(void) {
  char msg[256];
  struct material m;

  /* a complete material passes */
  basalt(&m, 103);
  CHECK(material_finalize(&m, msg, sizeof msg) == 0, "basalt finalizes: %s", msg);

  /* range errors at set time name material and key */
  basalt(&m, 1);
  CHECK(material_set(&m, "A", -1e9, msg, sizeof msg) == -1, "negative A rejected");
  expect(msg, "material 'basalt': key 'A' must be positive");
  CHECK(material_set(&m, "shear_modulus", -3.0, msg, sizeof msg) == -1, "negative mu rejected");
  expect(msg, "material 'basalt': key 'shear_modulus' must not be negative");
  CHECK(material_set(&m, "a", NAN, msg, sizeof msg) == -1, "NaN rejected");
  expect(msg, "key 'a' must be a number");
  CHECK(material_set(&m, "gamma", 1.4, msg, sizeof msg) == -1, "key of another EOS rejected");
  expect(msg, "material 'basalt': unknown key 'gamma' for EOS tillotson");

  /* missing required key */
  material_init(&m, 2, "rock", EOS_TILLOTSON);
  material_set(&m, "rho0", 2700, msg, sizeof msg);
  CHECK(material_finalize(&m, msg, sizeof msg) == -1, "incomplete Tillotson rejected");
  expect(msg, "material 'rock': key 'A' is required for EOS tillotson");

  /* cross-checks */
  basalt(&m, 3);
  material_set(&m, "Ecv", 1e6, msg, sizeof msg);
  CHECK(material_finalize(&m, msg, sizeof msg) == -1, "Ecv < Eiv rejected");
  expect(msg, "material 'basalt': key 'Ecv' must be larger than Eiv");
  basalt(&m, 4);
  material_set(&m, "yield_stress", 0.0, msg, sizeof msg);
  CHECK(material_finalize(&m, msg, sizeof msg) == -1, "von Mises without Y0 rejected");
  expect(msg, "material 'basalt': key 'yield_stress' must be positive");
  basalt(&m, 5);
  material_set(&m, "weibull_k", 5e34, msg, sizeof msg);
  CHECK(material_finalize(&m, msg, sizeof msg) == -1, "Weibull k without m rejected");
  expect(msg, "key 'weibull_m' must be given together");

  /* ideal gas: gamma must exceed 1 */
  material_init(&m, 0, "gas", EOS_IDEAL_GAS);
  CHECK(material_set(&m, "gamma", 1.0, msg, sizeof msg) == -1, "gamma = 1 rejected");
  expect(msg, "material 'gas': key 'gamma' must be larger than 1");

  /* the table: direct ids, SWIFT ids, large ids, duplicates are errors */
  struct material_table t;
  material_table_init(&t);
  const int ids[] = {0, 101, 103, 400, 70000, 2147483647};
  for (int k = 0; k < 6; k++) {
    basalt(&m, ids[k]);
    CHECK(material_finalize(&m, msg, sizeof msg) == 0, "finalize: %s", msg);
    material_table_add(&t, &m);
  }
  for (int k = 0; k < 6; k++) {
    const struct material *f = material_table_find(&t, ids[k]);
    CHECK(f && f->id == ids[k], "find id %d", ids[k]);
  }
  CHECK(material_table_find(&t, 102) == NULL && material_table_find(&t, 70001) == NULL &&
            material_table_find(&t, -1) == NULL,
        "absent ids not found");

  /* unit conversion to cgs: densities x 1e-3, pressures x 10, energies x 1e4 */
  struct unit_system cgs = {1.0, 1.0, 1.0, 1.0, 1.0, 0.0};
  const double A = t.mats[0].eos.tillotson.A, rho0 = t.mats[0].rho0;
  const double E0 = t.mats[0].eos.tillotson.E0, mu = t.mats[0].shear_modulus;
  double P_si, cs_si, P_cgs, cs_cgs;
  material_eos(&t.mats[0], 3000.0, 1e6, &P_si, &cs_si);
  material_table_convert_units(&t, &cgs);
  CHECK(fabs(t.mats[0].eos.tillotson.A - 10 * A) < 1e-6 * A &&
            fabs(t.mats[0].eos.tillotson.rho0 - 1e-3 * rho0) < 1e-12 &&
            fabs(t.mats[0].rho0 - 1e-3 * rho0) < 1e-12 &&
            fabs(t.mats[0].eos.tillotson.E0 - 1e4 * E0) < 1e-6 * E0 &&
            fabs(t.mats[0].shear_modulus - 10 * mu) < 1e-6 * mu,
        "cgs conversion of A, rho0, E0, mu");
  material_eos(&t.mats[0], 3.0, 1e10, &P_cgs, &cs_cgs);
  CHECK(fabs(P_cgs - 10 * P_si) < 1e-12 * fabs(10 * P_si) &&
            fabs(cs_cgs - 100 * cs_si) < 1e-12 * 100 * cs_si,
        "EOS in cgs: P %g (SI %g), cs %g (SI %g)", P_cgs, P_si, cs_cgs, cs_si);

  printf("test_material: %d checks, %d failed\n", checks, failures);
  return failures ? 1 : 0;
}
