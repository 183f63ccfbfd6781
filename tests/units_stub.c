/* TEST-ONLY STUB of src/io/units.c, for the io branch before the real unit
 * module is merged.  DELETE at merge time (and empty IO_UNITS_STUB in
 * src/io/hdf5.am): the real units.c provides these functions. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "units.h"

void units_init_si(struct unit_system *us) {
  us->mass_cgs = 1e3;
  us->length_cgs = 1e2;
  us->time_cgs = 1;
  us->current_cgs = 1;
  us->temperature_cgs = 1;
}

void units_init_cgs(struct unit_system *us) {
  us->mass_cgs = 1;
  us->length_cgs = 1;
  us->time_cgs = 1;
  us->current_cgs = 1;
  us->temperature_cgs = 1;
}

double units_cgs_factor(const struct unit_system *us, int a, int b, int c) {
  return pow(us->mass_cgs, a) * pow(us->length_cgs, b) * pow(us->time_cgs, c);
}

double units_conversion_factor(const struct unit_system *from, const struct unit_system *to, int a,
                               int b, int c) {
  return units_cgs_factor(from, a, b, c) / units_cgs_factor(to, a, b, c);
}

void units_cgs_string(int a, int b, int c, char *buf, int len) {
  char tmp[128] = "";
  const char *names[3] = {"g", "cm", "s"};
  const int e[3] = {a, b, c};
  for (int i = 0; i < 3; i++) {
    if (e[i] == 0) continue;
    char part[32];
    if (e[i] == 1)
      snprintf(part, sizeof part, "%s%s", tmp[0] ? " " : "", names[i]);
    else
      snprintf(part, sizeof part, "%s%s^%d", tmp[0] ? " " : "", names[i], e[i]);
    strncat(tmp, part, sizeof tmp - strlen(tmp) - 1);
  }
  snprintf(buf, (size_t)len, "[%s]", tmp);
}
