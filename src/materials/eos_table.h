/* Tabulated EOS on a regular grid in (ln rho, ln u).
 *
 * The table holds P, c^2 and (optionally) T at n_rho x n_u nodes, with
 * rho_i = exp(ln_rho_min + i dln_rho) and u_j = exp(ln_u_min + j dln_u).
 * Values between nodes are bilinear in (ln rho, ln u): continuous across
 * cells, exact at the nodes, and monotone wherever the node values are
 * (along each axis the interpolant is a convex combination of neighbouring
 * nodes, so it cannot overshoot).  The error of bilinear interpolation is
 * bounded by (dln_rho^2/8) max|d2P/dln_rho2| + (dln_u^2/8) max|d2P/dln_u2|
 * (tensor-product linear interpolation).  Outside the grid the state is
 * clamped to the nearest edge (constant extrapolation).  c^2 is tabulated,
 * not differentiated from the bilinear interpolant (whose derivatives jump
 * between cells); when a table file has no sound speed, material.c computes
 * c^2 at the nodes by centred differences of P at load.
 *
 * Tables are loaded by material_eos_table_load() (material.c) from text
 * files in (rho, u) or in (rho, T) (converted to (rho, u) at load); the
 * arrays are host memory owned by the material table (a GPU copy has to
 * replace the pointers by device pointers). */
#ifndef BOLIDE_EOS_TABLE_H
#define BOLIDE_EOS_TABLE_H

#include "src/materials/eos_common.h"

/* clang-format off */
#define EOS_TABLE_PARAMS(X)                                                                            \
  X(eos_table, rho0, "rho0", NAN, 0.0, 1, INFINITY, MATERIAL_UNIT_DENSITY,                             \
    "reference density (initial conditions, bulk modulus)")
/* clang-format on */

/** A tabulated EOS (the list gives rho0; the rest comes from the file). */
struct eos_table {
  EOS_TABLE_PARAMS(EOS_PARAM_FIELD)
  int n_rho;         /**< number of density nodes (>= 2) */
  int n_u;           /**< number of energy nodes (>= 2) */
  double ln_rho_min; /**< ln of the first density node */
  double dln_rho;    /**< spacing of ln rho */
  double ln_u_min;   /**< ln of the first energy node */
  double dln_u;      /**< spacing of ln u */
  const double *P;   /**< pressure at node (i, j): P[i * n_u + j] */
  const double *c2;  /**< squared sound speed at the nodes */
  const double *T;   /**< temperature at the nodes, NULL if not given */
};

/** Cell index and weight along one axis, clamped to the grid. */
BOLIDE_INLINE void eos_table_locate(double x, double x0, double dx, int n, int *i, double *t) {
  double s = (x - x0) / dx;
  if (!(s > 0.0)) s = 0.0; /* also catches NaN from ln(0) */
  if (s > (double)(n - 1)) s = (double)(n - 1);
  int k = (int)s;
  if (k > n - 2) k = n - 2;
  *i = k;
  *t = s - (double)k;
}

/** Bilinear interpolation of one node array at (rho, u). */
BOLIDE_INLINE double eos_table_interp(const struct eos_table *p, const double *f, double rho,
                                      double u) {
  int i, j;
  double t, v;
  eos_table_locate(log(rho), p->ln_rho_min, p->dln_rho, p->n_rho, &i, &t);
  eos_table_locate(u > 0.0 ? log(u) : -INFINITY, p->ln_u_min, p->dln_u, p->n_u, &j, &v);
  const double *r0 = f + (size_t)i * (size_t)p->n_u + j;
  const double *r1 = r0 + p->n_u;
  return (1.0 - t) * ((1.0 - v) * r0[0] + v * r0[1]) + t * ((1.0 - v) * r1[0] + v * r1[1]);
}

/** Pressure and tabulated c^2. */
BOLIDE_INLINE void eos_table_eval(const struct eos_table *p, double rho, double u, double *P,
                                  double *c2) {
  *P = eos_table_interp(p, p->P, rho, u);
  *c2 = eos_table_interp(p, p->c2, rho, u);
}

/** Pressure. */
BOLIDE_INLINE double eos_table_pressure(const struct eos_table *p, double rho, double u) {
  return eos_table_interp(p, p->P, rho, u);
}

/** Sound speed (0 where the interpolated c^2 <= 0). */
BOLIDE_INLINE double eos_table_sound_speed(const struct eos_table *p, double rho, double u) {
  const double c2 = eos_table_interp(p, p->c2, rho, u);
  return c2 > 0.0 ? sqrt(c2) : 0.0;
}

/** Whether the table has temperatures. */
BOLIDE_INLINE int eos_table_has_temperature(const struct eos_table *p) {
  return p->T != NULL;
}

/** Interpolated temperature (0 without one). */
BOLIDE_INLINE double eos_table_temperature(const struct eos_table *p, double rho, double u) {
  return p->T ? eos_table_interp(p, p->T, rho, u) : 0.0;
}

/** Cross-checks: a loaded grid of at least 2 x 2 nodes. */
static inline const char *eos_table_check(const struct eos_table *p, const char **key) {
  if (!p->P || !p->c2 || p->n_rho < 2 || p->n_u < 2) {
    *key = "file";
    return "must name a table of at least 2 x 2 nodes";
  }
  return NULL;
}

#endif
