/* Uniform boxes, the Sod shock tube and the Sedov blast: lattices of equal
 * mass particles.  See ic_tools.h. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "src/error.h"
#include "tools/ic/ic_tools.h"

/** Lattice cells along each axis and the cell side lengths of a region. */
struct icgen_grid {
  enum icgen_lattice lattice; /**< arrangement */
  int n[3];                   /**< cells (cubic, fcc) or points (hcp) along each axis */
  double lo[3];               /**< lower corner of the region */
  double len[3];              /**< side lengths of the region */
};

/** Particles per lattice cell. */
static int icgen_per_cell(enum icgen_lattice l) {
  return l == ICGEN_FCC ? 4 : 1;
}

static size_t icgen_grid_count(const struct icgen_grid *g) {
  return (size_t)g->n[0] * (size_t)g->n[1] * (size_t)g->n[2] * (size_t)icgen_per_cell(g->lattice);
}

/** Choose the cells along y and z so that the lattice is as close to
 *  isotropic as the region allows, given nx along x.  hcp: the rows of a
 *  triangular layer are a*sqrt(3)/2 apart and the layers a*sqrt(2/3) apart;
 *  both counts are kept even so that the ABAB stacking is periodic. */
static void icgen_grid_from_n(struct icgen_grid *g, int nx) {
  const double a = g->len[0] / nx;
  g->n[0] = nx;
  if (g->lattice == ICGEN_HCP) {
    const double dy = a * sqrt(3.0) / 2, dz = a * sqrt(2.0 / 3.0);
    g->n[1] = 2 * (int)fmax(1, lround(g->len[1] / dy / 2));
    g->n[2] = 2 * (int)fmax(1, lround(g->len[2] / dz / 2));
  } else {
    g->n[1] = (int)fmax(1, lround(g->len[1] / a));
    g->n[2] = (int)fmax(1, lround(g->len[2] / a));
  }
}

/** Positions of the lattice points, written from index `first`. */
static void icgen_grid_fill(const struct icgen_grid *g, struct parts *p, size_t first) {
  const double d[3] = {g->len[0] / g->n[0], g->len[1] / g->n[1], g->len[2] / g->n[2]};
  /* fcc: the four sites of a cubic cell, in units of the cell side */
  static const double fcc[4][3] = {
      {0.25, 0.25, 0.25}, {0.75, 0.75, 0.25}, {0.75, 0.25, 0.75}, {0.25, 0.75, 0.75}};
  size_t i = first;
  for (int kx = 0; kx < g->n[0]; kx++)
    for (int ky = 0; ky < g->n[1]; ky++)
      for (int kz = 0; kz < g->n[2]; kz++) {
        if (g->lattice == ICGEN_CUBIC) {
          p->x[i] = g->lo[0] + (kx + 0.5) * d[0];
          p->y[i] = g->lo[1] + (ky + 0.5) * d[1];
          p->z[i] = g->lo[2] + (kz + 0.5) * d[2];
          i++;
        } else if (g->lattice == ICGEN_FCC) {
          for (int s = 0; s < 4; s++, i++) {
            p->x[i] = g->lo[0] + (kx + fcc[s][0]) * d[0];
            p->y[i] = g->lo[1] + (ky + fcc[s][1]) * d[1];
            p->z[i] = g->lo[2] + (kz + fcc[s][2]) * d[2];
          }
        } else {
          /* hcp: odd rows shifted by half a spacing in x; B layers shifted
           * to the centroid of an A triangle, (a/2, row/3) */
          double fx = kx + 0.25 + 0.5 * (ky % 2) + 0.5 * (kz % 2);
          if (fx >= g->n[0]) fx -= g->n[0];
          p->x[i] = g->lo[0] + fx * d[0];
          p->y[i] = g->lo[1] + (ky + 1.0 / 6.0 + (kz % 2) / 3.0) * d[1];
          p->z[i] = g->lo[2] + (kz + 0.5) * d[2];
          i++;
        }
      }
}

/** The grid of the whole box from --n or --nx. */
static struct icgen_grid icgen_box_grid(const struct icgen_opts *o) {
  struct icgen_grid g = {.lattice = o->lattice};
  memcpy(g.len, o->size, sizeof g.len);
  if (o->nx[0] > 0) {
    memcpy(g.n, o->nx, sizeof g.n);
    if (g.lattice == ICGEN_HCP && o->periodic && (g.n[1] % 2 || g.n[2] % 2))
      error_exit("--nx: a periodic hcp lattice needs even NY and NZ (got %d,%d)", g.n[1], g.n[2]);
  } else {
    icgen_grid_from_n(&g, o->n);
  }
  return g;
}

/** splitmix64 (Steele, Lea & Flood 2014): reproducible displacements. */
static uint64_t icgen_rng(uint64_t *s) {
  uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/** Uniform random number in [-1, 1). */
static double icgen_uniform(uint64_t *s) {
  return 2.0 * (double)(icgen_rng(s) >> 11) / 9007199254740992.0 - 1.0;
}

/** Displace every particle by up to frac x spacing per axis, keeping it in
 *  the box (periodic wrap). */
static void icgen_perturb(struct parts *p, const double box[3], double spacing, double frac,
                          uint64_t seed) {
  if (frac <= 0) return;
  uint64_t s = seed;
  double *xyz[3] = {p->x, p->y, p->z};
  for (size_t i = 0; i < p->count; i++)
    for (int d = 0; d < 3; d++) {
      double v = xyz[d][i] + frac * spacing * icgen_uniform(&s);
      v = fmod(v, box[d]);
      if (v < 0) v += box[d];
      if (v >= box[d]) v = 0; /* -tiny + box rounds to box */
      xyz[d][i] = v;
    }
}

/** Fill the fields common to every uniform region [first, first+n). */
static void icgen_set_state(struct parts *p, size_t first, size_t n, double m, double h, double rho,
                            double u, int32_t mat) {
  for (size_t i = first; i < first + n; i++) {
    p->m[i] = m;
    p->h[i] = h;
    p->rho[i] = rho;
    p->u[i] = u;
    p->mat[i] = mat;
    p->id[i] = (int64_t)i + 1;
  }
}

void icgen_box(const struct icgen_opts *o, struct parts *p) {
  const struct icgen_grid g = icgen_box_grid(o);
  const size_t n = icgen_grid_count(&g);
  const double vol = o->size[0] * o->size[1] * o->size[2];
  const double spacing = cbrt(vol / (double)n);
  parts_alloc(p, n);
  icgen_grid_fill(&g, p, 0);
  icgen_set_state(p, 0, n, o->rho * vol / (double)n, o->eta * spacing, o->rho, o->u, o->mat);
  icgen_perturb(p, o->size, spacing, o->perturb, o->seed);
}

void icgen_sod(const struct icgen_opts *o, struct parts *p) {
  /* Sod (1978) states: rho 1 / 0.125, P 1 / 0.1, left at x < Lx/2. */
  const double rho_l = 1.0, rho_r = 0.125, p_l = 1.0, p_r = 0.1;
  if (o->lattice == ICGEN_HCP) error_exit("sod: use --lattice cubic or fcc");
  const int nxl = o->nx[0] > 0 ? o->nx[0] : o->n;
  if (nxl < 2 || nxl % 2) error_exit("sod: --nx must be an even number >= 2 (got %d)", nxl);
  /* left cells: Lx/2 / nxl; right cells twice as large (8 x the volume) */
  const double a = 0.5 * o->size[0] / nxl;
  int ny = (int)lround(o->size[1] / a), nz = (int)lround(o->size[2] / a);
  if (ny < 2 || nz < 2 || ny % 2 || nz % 2 || fabs(ny * a - o->size[1]) > 1e-9 * o->size[1] ||
      fabs(nz * a - o->size[2]) > 1e-9 * o->size[2])
    error_exit("sod: Ly and Lz (%g, %g) must be even multiples of the left spacing %g", o->size[1],
               o->size[2], a);
  struct icgen_grid left = {.lattice = o->lattice,
                            .n = {nxl, ny, nz},
                            .lo = {0, 0, 0},
                            .len = {0.5 * o->size[0], o->size[1], o->size[2]}};
  struct icgen_grid right = left;
  right.n[0] = nxl / 2;
  right.n[1] = ny / 2;
  right.n[2] = nz / 2;
  right.lo[0] = 0.5 * o->size[0];
  const size_t nl = icgen_grid_count(&left), nr = icgen_grid_count(&right);
  const double vl = left.len[0] * left.len[1] * left.len[2];
  const double m = rho_l * vl / (double)nl; /* = rho_r * vr / nr: nl = 8 nr */
  parts_alloc(p, nl + nr);
  icgen_grid_fill(&left, p, 0);
  icgen_grid_fill(&right, p, nl);
  const double gm1 = o->gamma - 1;
  icgen_set_state(p, 0, nl, m, o->eta * cbrt(vl / (double)nl), rho_l, p_l / (gm1 * rho_l), o->mat);
  icgen_set_state(p, nl, nr, m, o->eta * cbrt(vl / (double)nr), rho_r, p_r / (gm1 * rho_r), o->mat);
}

/** Shape of the cubic spline M4 kernel (Monaghan & Lattanzio 1985, eq. 21)
 *  with support radius 1, unnormalised: only ratios are used. */
static double icgen_m4(double r) {
  const double q = 2 * r;
  if (q < 1) return 1 - 1.5 * q * q + 0.75 * q * q * q;
  if (q < 2) return 0.25 * (2 - q) * (2 - q) * (2 - q);
  return 0;
}

void icgen_sedov(const struct icgen_opts *o, struct parts *p) {
  icgen_box(o, p);
  const size_t n = p->count;
  const double radius = o->radius > 0 ? o->radius : 2 * p->h[0];
  const double c[3] = {0.5 * o->size[0], 0.5 * o->size[1], 0.5 * o->size[2]};
  /* weights w_i; particle i receives E w_i / sum_j m_j w_j, so that the
   * energy added, sum_i m_i du_i, is E exactly */
  double msum = 0;
  size_t inside = 0;
  for (int pass = 0; pass < 2; pass++)
    for (size_t i = 0; i < n; i++) {
      const double dx = p->x[i] - c[0], dy = p->y[i] - c[1], dz = p->z[i] - c[2];
      const double r = sqrt(dx * dx + dy * dy + dz * dz);
      if (r >= radius) continue;
      const double w = o->kernel_weighting ? icgen_m4(r / radius) : 1.0;
      if (pass == 0) {
        msum += p->m[i] * w;
        inside++;
      } else {
        p->u[i] += o->energy * w / msum;
      }
    }
  if (inside == 0 || !(msum > 0))
    error_exit("sedov: no particle within --radius %g of the centre", radius);
}
