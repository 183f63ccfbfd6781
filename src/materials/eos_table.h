/* Tabulated EOS on a grid in (ln rho, ln u).
 *
 * The table holds P, c^2 and (optionally) T at n_rho x n_u nodes.  The
 * nodes are either log-spaced, rho_i = exp(ln_rho_min + i dln_rho) and
 * u_j = exp(ln_u_min + j dln_u) (the cell of a state is then found by one
 * division), or any strictly increasing axes given as the arrays ln_rho and
 * ln_u (miluphcuda's tables, which it searches by bisection; the cell is
 * then found by bisection).  Values between nodes are bilinear in (ln rho,
 * ln u): continuous across cells, exact at the nodes, and monotone wherever
 * the node values are (along each axis the interpolant is a convex
 * combination of neighbouring nodes, so it cannot overshoot).  The error of
 * bilinear interpolation in a cell of widths (h_rho, h_u) in ln rho and ln u
 * is bounded by (h_rho^2/8) max|d2P/dln_rho2| + (h_u^2/8) max|d2P/dln_u2|
 * over the cell (tensor-product linear interpolation).
 *
 * Outside the grid (theory/eos.md, "Tables"): u below the first energy node
 * is clamped to it; u above the last one is clamped too, unless gamma_vapor
 * > 0, where the state is an ideal gas P = (gamma_vapor - 1) rho u, c^2 =
 * gamma_vapor (gamma_vapor - 1) u (miluphcuda's ANEOS vapour fallback,
 * aneos_gamma; T stays clamped); rho outside the density nodes is clamped,
 * or with rho_extrapolate (format miluphcuda) extrapolated linearly in rho
 * from the outermost cell, as miluphcuda does.  c^2 is tabulated, not
 * differentiated from the bilinear interpolant (whose derivatives jump
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
    "reference density (initial conditions, bulk modulus)")                                           \
  X(eos_table, gamma_vapor, "gamma_vapor", 0.0, 0.0, 0, 10.0, MATERIAL_UNIT_NONE,                      \
    "above the table's last energy node an ideal gas of this gamma (miluphcuda's aneos_gamma); "       \
    "0: clamp u to the last node")
/* clang-format on */

/** A tabulated EOS (the list gives rho0; the rest comes from the file). */
struct eos_table {
  EOS_TABLE_PARAMS(EOS_PARAM_FIELD)
  int n_rho;            /**< number of density nodes (>= 2) */
  int n_u;              /**< number of energy nodes (>= 2) */
  double ln_rho_min;    /**< ln of the first density node */
  double dln_rho;       /**< spacing of ln rho */
  double ln_u_min;      /**< ln of the first energy node */
  double dln_u;         /**< spacing of ln u */
  const double *ln_rho; /**< ln of the density nodes when not log-spaced, else NULL */
  const double *ln_u;   /**< ln of the energy nodes when not log-spaced, else NULL */
  const double *P;      /**< pressure at node (i, j): P[i * n_u + j] */
  const double *c2;     /**< squared sound speed at the nodes */
  const double *T;      /**< temperature at the nodes, NULL if not given */
  int rho_extrapolate;  /**< 1: linear in rho outside the density nodes; 0: clamped */
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

/** Cell index and weight along an axis of n increasing nodes xs, by
 *  bisection (as miluphcuda's array_index), clamped to the nodes. */
BOLIDE_INLINE void eos_table_search(double x, const double *xs, int n, int *i, double *t) {
  if (!(x > xs[0])) { /* also NaN from ln(0) */
    *i = 0;
    *t = 0.0;
    return;
  }
  if (x >= xs[n - 1]) {
    *i = n - 2;
    *t = 1.0;
    return;
  }
  int lo = 0, hi = n - 1; /* xs[lo] <= x < xs[hi] */
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (xs[mid] <= x)
      lo = mid;
    else
      hi = mid;
  }
  *i = lo;
  *t = (x - xs[lo]) / (xs[lo + 1] - xs[lo]);
}

/** ln of density node i. */
BOLIDE_INLINE double eos_table_ln_rho_node(const struct eos_table *p, int i) {
  return p->ln_rho ? p->ln_rho[i] : p->ln_rho_min + i * p->dln_rho;
}

/** ln of energy node j. */
BOLIDE_INLINE double eos_table_ln_u_node(const struct eos_table *p, int j) {
  return p->ln_u ? p->ln_u[j] : p->ln_u_min + j * p->dln_u;
}

/** Bilinear interpolation of one node array at (rho, u) (rho extrapolated
 *  linearly in rho outside the nodes where p->rho_extrapolate). */
BOLIDE_INLINE double eos_table_interp(const struct eos_table *p, const double *f, double rho,
                                      double u) {
  int i, j;
  double t, v;
  const double lr = log(rho), lu = u > 0.0 ? log(u) : -INFINITY;
  if (p->ln_rho)
    eos_table_search(lr, p->ln_rho, p->n_rho, &i, &t);
  else
    eos_table_locate(lr, p->ln_rho_min, p->dln_rho, p->n_rho, &i, &t);
  if (p->ln_u)
    eos_table_search(lu, p->ln_u, p->n_u, &j, &v);
  else
    eos_table_locate(lu, p->ln_u_min, p->dln_u, p->n_u, &j, &v);
  if (p->rho_extrapolate && (t == 0.0 || t == 1.0)) {
    /* miluphcuda: the weight of the outermost cell, linear in rho */
    const double r_a = exp(eos_table_ln_rho_node(p, i)), r_b = exp(eos_table_ln_rho_node(p, i + 1));
    if (rho < r_a || rho > r_b) t = (rho - r_a) / (r_b - r_a);
  }
  const double *r0 = f + (size_t)i * (size_t)p->n_u + j;
  const double *r1 = r0 + p->n_u;
  return (1.0 - t) * ((1.0 - v) * r0[0] + v * r0[1]) + t * ((1.0 - v) * r1[0] + v * r1[1]);
}

/** Whether u lies at or above the last energy node with an ideal-gas
 *  fallback there (miluphcuda: e >= e_max). */
BOLIDE_INLINE int eos_table_vapor(const struct eos_table *p, double u) {
  return p->gamma_vapor > 0.0 && log(u) >= eos_table_ln_u_node(p, p->n_u - 1);
}

/** Pressure and tabulated c^2. */
BOLIDE_INLINE void eos_table_eval(const struct eos_table *p, double rho, double u, double *P,
                                  double *c2) {
  if (eos_table_vapor(p, u)) {
    const double g = p->gamma_vapor;
    *P = (g - 1.0) * rho * u;
    *c2 = g * (g - 1.0) * u;
    return;
  }
  *P = eos_table_interp(p, p->P, rho, u);
  *c2 = eos_table_interp(p, p->c2, rho, u);
}

/** Pressure. */
BOLIDE_INLINE double eos_table_pressure(const struct eos_table *p, double rho, double u) {
  if (eos_table_vapor(p, u)) return (p->gamma_vapor - 1.0) * rho * u;
  return eos_table_interp(p, p->P, rho, u);
}

/** Sound speed (0 where the interpolated c^2 <= 0). */
BOLIDE_INLINE double eos_table_sound_speed(const struct eos_table *p, double rho, double u) {
  const double c2 = eos_table_vapor(p, u) ? p->gamma_vapor * (p->gamma_vapor - 1.0) * u
                                          : eos_table_interp(p, p->c2, rho, u);
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
  if (!(p->gamma_vapor == 0.0 || p->gamma_vapor > 1.0)) {
    *key = "gamma_vapor";
    return "must be 0 (u clamped to the last node) or larger than 1";
  }
  return NULL;
}

#endif
