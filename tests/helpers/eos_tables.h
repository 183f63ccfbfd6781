/* Tabulated EOS for the tests: a (rho, u) table filled from an analytic EOS
 * (no tables can be downloaded; the analytic EOS is the reference the
 * interpolation is compared with).  Used by test_eos.c and test_gpu.c. */
#ifndef BOLIDE_TEST_EOS_TABLES_H
#define BOLIDE_TEST_EOS_TABLES_H

#include <math.h>
#include <stdlib.h>

#include "src/materials/material.h"

/** Fill t from Tillotson p on the given density and energy nodes (any
 *  increasing positive values: ln_rho and ln_u node arrays, the bisection
 *  path of eos_table.h), with rho extrapolated linearly outside the nodes
 *  and an ideal gas of gamma_vapor above the last energy (format
 *  miluphcuda's behaviour); all arrays malloc'ed. */
static void table_from_tillotson_nodes(struct eos_table *t, const struct eos_tillotson *p,
                                       const double *rho, int nr, const double *u, int nu,
                                       double gamma_vapor) {
  double *P = malloc(sizeof(double) * nr * nu), *c2 = malloc(sizeof(double) * nr * nu);
  double *lr = malloc(sizeof(double) * nr), *lu = malloc(sizeof(double) * nu);
  for (int i = 0; i < nr; i++) lr[i] = log(rho[i]);
  for (int j = 0; j < nu; j++) lu[j] = log(u[j]);
  t->rho0 = p->rho0;
  t->n_rho = nr;
  t->n_u = nu;
  t->ln_rho_min = lr[0];
  t->dln_rho = (lr[nr - 1] - lr[0]) / (nr - 1);
  t->ln_u_min = lu[0];
  t->dln_u = (lu[nu - 1] - lu[0]) / (nu - 1);
  for (int i = 0; i < nr; i++)
    for (int j = 0; j < nu; j++)
      eos_tillotson_eval(p, rho[i], u[j], &P[i * nu + j], &c2[i * nu + j]);
  t->P = P;
  t->c2 = c2;
  t->T = NULL;
  t->ln_rho = lr;
  t->ln_u = lu;
  t->gamma_vapor = gamma_vapor;
  t->rho_extrapolate = 1;
}

/** Fill t from Tillotson p on [r0, r1] x [u0, u1], nr x nu log-spaced nodes
 *  (the division path of eos_table.h: no node arrays; clamped outside; P
 *  and c^2 malloc'ed: material_table_free releases them). */
static void table_from_tillotson(struct eos_table *t, const struct eos_tillotson *p, int nr, int nu,
                                 double r0, double r1, double u0, double u1) {
  const double lr0 = log(r0), dlr = (log(r1) - lr0) / (nr - 1);
  const double lu0 = log(u0), dlu = (log(u1) - lu0) / (nu - 1);
  double *rho = malloc(sizeof(double) * nr), *u = malloc(sizeof(double) * nu);
  for (int i = 0; i < nr; i++) rho[i] = exp(lr0 + i * dlr);
  for (int j = 0; j < nu; j++) u[j] = exp(lu0 + j * dlu);
  table_from_tillotson_nodes(t, p, rho, nr, u, nu, 0.0);
  free(rho);
  free(u);
  free((void *)t->ln_rho);
  free((void *)t->ln_u);
  t->ln_rho = t->ln_u = NULL;
  t->rho_extrapolate = 0;
  t->ln_rho_min = lr0;
  t->dln_rho = dlr;
  t->ln_u_min = lu0;
  t->dln_u = dlu;
}

#endif
