/* Helper of tests/tools/test_materials_yaml.sh: read a run's parameter file, build
 * its material table and print one line per material:
 *   ID NAME EOS RHO0 PARAM
 * where PARAM is a characteristic EOS parameter (A for Tillotson, gamma for
 * an ideal gas, c0 otherwise: for a liquid its sound speed, from c0 or K0), so
 * that the script can check library lookups, overrides, inline definitions
 * and SWIFT ids. */
#include <stdio.h>

#include "src/error.h"
#include "src/materials/material.h"
#include "src/io/params.h"

int main(int argc, char **argv) {
  error_init(argv[0]);
  if (argc != 2) error_exit("usage: test_material_params PARAMS.yml");
  struct params *p = params_read(argv[1], 0, NULL);
  struct material_table t;
  material_table_from_params(&t, p);
  for (int k = 0; k < t.n; k++) {
    const struct material *m = &t.mats[k];
    double x = 0.0;
    if (m->eos_type == EOS_TILLOTSON) x = m->eos.tillotson.A;
    if (m->eos_type == EOS_IDEAL_GAS) x = m->eos.ideal_gas.gamma;
    if (m->eos_type == EOS_LIQUID) x = eos_liquid_sound_speed(&m->eos.liquid, m->rho0, 0.0);
    if (m->eos_type == EOS_MIE_GRUNEISEN) x = m->eos.mie_gruneisen.c0;
    printf("%d %s %s %.10g %.10g %.10g\n", (int)m->id, m->name, material_eos_name(m->eos_type),
           m->rho0, x, m->weibull_m);
  }
  material_table_free(&t);
  params_free(p);
  return 0;
}
