/* Tests of the unit systems (src/io/units.c): SI <-> cgs factors that must be
 * exact (correctly rounded powers of ten), round trips through custom
 * systems, units read from a parameter file (time = length / velocity),
 * physical constants in SI and in custom units, and the unit strings. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "src/error.h"
#include "src/io/params.h"
#include "src/io/units.h"

static int failures = 0;

/** Record a failed check with its line. */
#define CHECK(cond)                                                      \
  do {                                                                   \
    if (!(cond)) {                                                       \
      fprintf(stderr, "test_units.c:%d: FAILED: %s\n", __LINE__, #cond); \
      failures++;                                                        \
    }                                                                    \
  } while (0)

/** |a - b| <= tol |b| */
static int close_to(double a, double b, double tol) {
  return fabs(a - b) <= tol * fabs(b);
}

/** SI <-> cgs: each factor is a power of ten, so it must be exact. */
static void test_si_cgs(void) {
  struct unit_system si, cgs;
  units_init_si(&si);
  units_init_cgs(&cgs);
  static const struct {
    int a, b, c;      /* dimension M^a L^b T^c */
    double si_to_cgs; /* exact factor */
  } dims[] = {
      {1, 0, 0, 1e3},   /* mass: kg -> g */
      {0, 1, 0, 1e2},   /* length: m -> cm */
      {0, 0, 1, 1.},    /* time */
      {1, -3, 0, 1e-3}, /* density: kg m^-3 -> g cm^-3 */
      {0, 1, -1, 1e2},  /* velocity */
      {0, 2, -2, 1e4},  /* specific energy: J/kg -> erg/g */
      {1, 2, -2, 1e7},  /* energy: J -> erg */
      {1, -1, -2, 1e1}, /* pressure: Pa -> Ba */
      {-1, 3, -2, 1e3}, /* G's dimension */
      {0, 0, 0, 1.},    /* dimensionless */
  };
  for (size_t k = 0; k < sizeof dims / sizeof dims[0]; k++) {
    double f = units_conversion_factor(&si, &cgs, dims[k].a, dims[k].b, dims[k].c);
    double g = units_conversion_factor(&cgs, &si, dims[k].a, dims[k].b, dims[k].c);
    if (f != dims[k].si_to_cgs) fprintf(stderr, "dimension %zu: %.17g\n", k, f);
    CHECK(f == dims[k].si_to_cgs);
    CHECK(g == 1. / dims[k].si_to_cgs);
    CHECK(units_cgs_factor(&si, dims[k].a, dims[k].b, dims[k].c) == f);
  }
  CHECK(units_G(&cgs) == 6.67430e-8);
  CHECK(close_to(units_G(&si), 6.6743e-11, 1e-15));
  CHECK(close_to(units_k_B(&si), 1.380649e-23, 1e-15));
  CHECK(units_k_B(&cgs) == 1.380649e-16);
  CHECK(close_to(units_m_H(&si), 1.6735575e-27, 1e-15));
}

/** Round trips through custom systems, and their consistency. */
static void test_custom(void) {
  struct unit_system si, earth = {5.9722e27, 6.371e8, 6.371e8 / 1e5, 1., 1., 0.};
  struct unit_system odd = {3.7, 0.013, 1234.5, 2., 300., 0.};
  units_init_si(&si);
  for (int a = -3; a <= 3; a++)
    for (int b = -3; b <= 3; b++)
      for (int c = -3; c <= 3; c++) {
        double f = units_conversion_factor(&earth, &odd, a, b, c);
        double g = units_conversion_factor(&odd, &earth, a, b, c);
        CHECK(close_to(f * g, 1., 4e-16 * 12));
        /* through a third system */
        double h = units_conversion_factor(&earth, &si, a, b, c) *
                   units_conversion_factor(&si, &odd, a, b, c);
        CHECK(close_to(h, f, 4e-16 * 24));
        /* from the definition: product of base-unit ratios */
        double direct = pow(earth.mass_cgs / odd.mass_cgs, a) *
                        pow(earth.length_cgs / odd.length_cgs, b) *
                        pow(earth.time_cgs / odd.time_cgs, c);
        CHECK(close_to(f, direct, 1e-14));
      }
  /* G in Earth units: G M_E / R_E^2 = surface gravity 9.8 m/s^2 */
  double g_surface = units_G(&earth) * units_cgs_factor(&earth, 0, 1, -2); /* cm s^-2 */
  CHECK(close_to(g_surface, 6.67430e-8 * 5.9722e27 / (6.371e8 * 6.371e8), 1e-14));
  CHECK(close_to(g_surface, 982., 0.01));
  /* k_B per internal temperature unit of 300 K */
  CHECK(close_to(units_k_B(&odd) * units_cgs_factor(&odd, 1, 2, -2), 1.380649e-16 * 300., 1e-14));
}

/** units_init_from_params: time = length / velocity; SI without the section. */
static void test_from_params(void) {
  char dir[] = "/tmp/test_units_XXXXXX", path[256];
  if (!mkdtemp(dir)) error_exit("cannot make a temporary folder");
  snprintf(path, sizeof path, "%s/u.yml", dir);
  FILE *f = fopen(path, "w");
  fputs("InitialConditions: {file_name: x.hdf5}\nTimeIntegration: {time_end: 1}\n", f);
  fclose(f);
  struct params *p = params_read(path, 0, NULL);
  struct unit_system us, si;
  units_init_from_params(&us, p);
  units_init_si(&si);
  CHECK(memcmp(&us, &si, sizeof us) == 0);
  params_free(p);
  char *over[] = {"InternalUnitSystem:UnitMass_in_cgs:5.9722e27",
                  "InternalUnitSystem:UnitLength_in_cgs:6.371e8",
                  "InternalUnitSystem:UnitVelocity_in_cgs:1e5",
                  "InternalUnitSystem:UnitTemp_in_cgs:1000"};
  p = params_read(path, 4, over);
  units_init_from_params(&us, p);
  CHECK(us.mass_cgs == 5.9722e27 && us.length_cgs == 6.371e8 && us.temperature_cgs == 1000.);
  CHECK(us.time_cgs == 6.371e8 / 1e5);
  params_free(p);
  units_init_from_params(&us, NULL);
  CHECK(memcmp(&us, &si, sizeof us) == 0);
  unlink(path);
  rmdir(dir);
}

/** The cgs unit strings of attributes. */
static void test_strings(void) {
  char buf[64];
  units_cgs_string(1, -3, 0, buf, sizeof buf);
  CHECK(strcmp(buf, "[g cm^-3]") == 0);
  units_cgs_string(0, 1, -1, buf, sizeof buf);
  CHECK(strcmp(buf, "[cm s^-1]") == 0);
  units_cgs_string(0, 0, 0, buf, sizeof buf);
  CHECK(strcmp(buf, "[-]") == 0);
  units_cgs_string(1, 0, 0, buf, sizeof buf);
  CHECK(strcmp(buf, "[g]") == 0);
  units_cgs_string(1, 2, -2, buf, 6); /* truncated, still terminated */
  CHECK(strlen(buf) == 5);
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  test_si_cgs();
  test_custom();
  test_from_params();
  test_strings();
  if (failures) fprintf(stderr, "test_units: %d failures\n", failures);
  return failures ? 1 : 0;
}
