/* Tabulated EOS for the tests: a (rho, u) table filled from an analytic EOS
 * (no tables can be downloaded; the analytic EOS is the reference the
 * interpolation is compared with).  Used by test_eos.c and test_gpu.c. */
#ifndef BOLIDE_TEST_EOS_TABLES_H
#define BOLIDE_TEST_EOS_TABLES_H

#include <math.h>
#include <stdlib.h>

#include "src/materials/material.h"

/** Fill t from Tillotson p on [r0, r1] x [u0, u1], nr x nu log-spaced nodes
 *  (P and c^2 malloc'ed: material_table_free releases them). */
static void table_from_tillotson(struct eos_table *t, const struct eos_tillotson *p, int nr, int nu,
                                 double r0, double r1, double u0, double u1) {
  double *P = malloc(sizeof(double) * nr * nu), *c2 = malloc(sizeof(double) * nr * nu);
  t->rho0 = p->rho0;
  t->n_rho = nr;
  t->n_u = nu;
  t->ln_rho_min = log(r0);
  t->dln_rho = (log(r1) - log(r0)) / (nr - 1);
  t->ln_u_min = log(u0);
  t->dln_u = (log(u1) - log(u0)) / (nu - 1);
  for (int i = 0; i < nr; i++)
    for (int j = 0; j < nu; j++)
      eos_tillotson_eval(p, exp(t->ln_rho_min + i * t->dln_rho), exp(t->ln_u_min + j * t->dln_u),
                         &P[i * nu + j], &c2[i * nu + j]);
  t->P = P;
  t->c2 = c2;
  t->T = NULL;
  t->ln_rho = t->ln_u = NULL;
  t->gamma_vapor = 0.0;
  t->rho_extrapolate = 0;
}

#endif
