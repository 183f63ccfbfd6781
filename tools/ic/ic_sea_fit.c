/* The SPH density of a particle set as Bolide computes it at start-up, and
 * the two corrections of SEA planets that use it (theory/planets.md,
 * "SEA planet: the 1 % bar"):
 *
 * - ic_sph_density: h_i solves sum_j W(r_ij, h_i) = (eta / h_i)^3 (the
 *   number-density form of SWIFT and Bolide, self included), then
 *   rho_i = sum_j m_j W(r_ij, h_i), with the compiled-in kernel of
 *   tasks/hydro/kernel.h;
 * - ic_sea_relax: moves particles along their shells (never radially) down
 *   the gradient of rho_SPH / rho_profile, so that the density scatter of
 *   the SEA collars evens out.
 *
 * Neighbours come from a uniform grid of cubic cells.  The loops over
 * particles run on all online cores (BOLIDE_IC_THREADS sets the number);
 * every particle's result depends on the inputs only, so the output does
 * not depend on the thread count. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "src/error.h"
#include "tools/ic/ic_planet.h"
#include "tasks/hydro/kernel.h"

/** Points sorted into cubic cells of side `cell`. */
struct sea_grid {
  double lo[3], cell;
  long n[3];
  size_t *start; /**< first entry of each cell in idx (n cells + 1) */
  size_t *idx;   /**< point indices, cell by cell */
};

static long sea_grid_coord(const struct sea_grid *g, int d, double v) {
  long c = (long)floor((v - g->lo[d]) / g->cell);
  return c < 0 ? 0 : c >= g->n[d] ? g->n[d] - 1 : c;
}

static void sea_grid_build(struct sea_grid *g, size_t n, const double *x, const double *y,
                           const double *z, double cell) {
  const double *c[3] = {x, y, z};
  double hi[3];
  for (int d = 0; d < 3; d++) {
    g->lo[d] = INFINITY, hi[d] = -INFINITY;
    for (size_t i = 0; i < n; i++) g->lo[d] = fmin(g->lo[d], c[d][i]), hi[d] = fmax(hi[d], c[d][i]);
  }
  /* at most ~2 million cells */
  double ext = fmax(hi[0] - g->lo[0], fmax(hi[1] - g->lo[1], hi[2] - g->lo[2]));
  if (ext / cell > 128) cell = ext / 128;
  g->cell = cell;
  size_t nc = 1;
  for (int d = 0; d < 3; d++) g->n[d] = (long)floor((hi[d] - g->lo[d]) / cell) + 1, nc *= g->n[d];
  g->start = error_malloc((nc + 1) * sizeof(size_t), "SPH density grid");
  g->idx = error_malloc((n ? n : 1) * sizeof(size_t), "SPH density grid");
  size_t *cid = error_malloc((n ? n : 1) * sizeof(size_t), "SPH density grid");
  memset(g->start, 0, (nc + 1) * sizeof(size_t));
  for (size_t i = 0; i < n; i++) {
    cid[i] =
        (size_t)((sea_grid_coord(g, 0, x[i]) * g->n[1] + sea_grid_coord(g, 1, y[i])) * g->n[2] +
                 sea_grid_coord(g, 2, z[i]));
    g->start[cid[i] + 1]++;
  }
  for (size_t k = 0; k < nc; k++) g->start[k + 1] += g->start[k];
  size_t *fill = error_malloc((nc + 1) * sizeof(size_t), "SPH density grid");
  memcpy(fill, g->start, (nc + 1) * sizeof(size_t));
  for (size_t i = 0; i < n; i++) g->idx[fill[cid[i]]++] = i;
  free(fill), free(cid);
}

static void sea_grid_free(struct sea_grid *g) {
  free(g->start), free(g->idx);
}

/** Neighbour buffer: indices and distances of the points within `rad` of i. */
struct sea_ngb {
  size_t n, cap, *j;
  double *r;
};

/** Threads of the particle loops: BOLIDE_IC_THREADS, else the online cores. */
static int sea_threads(void) {
  const char *env = getenv("BOLIDE_IC_THREADS");
  long t = env ? strtol(env, NULL, 10) : sysconf(_SC_NPROCESSORS_ONLN);
  if (env && t < 1)
    error_exit("bolide-ic: BOLIDE_IC_THREADS must be a positive integer, not '%s'", env);
  return t < 1 ? 1 : t > 256 ? 256 : (int)t;
}

/** One slice [lo, hi) of a particle loop, with its own neighbour buffer. */
struct sea_slice {
  size_t lo, hi;
  void (*body)(void *ctx, size_t i, struct sea_ngb *b);
  void *ctx;
};

static void *sea_slice_run(void *arg) {
  struct sea_slice *s = arg;
  struct sea_ngb b = {0};
  for (size_t i = s->lo; i < s->hi; i++) s->body(s->ctx, i, &b);
  free(b.j), free(b.r);
  return NULL;
}

/** body(ctx, i, buffer) for every i < n, in parallel slices. */
static void sea_for(size_t n, void (*body)(void *, size_t, struct sea_ngb *), void *ctx) {
  int t = sea_threads();
  if ((size_t)t > n / 256 + 1) t = (int)(n / 256 + 1);
  struct sea_slice sl[256];
  pthread_t th[256];
  for (int k = 0; k < t; k++)
    sl[k] =
        (struct sea_slice){n * (size_t)k / (size_t)t, n * (size_t)(k + 1) / (size_t)t, body, ctx};
  int started = 1;
  for (int k = 1; k < t; k++, started++)
    if (pthread_create(&th[k], NULL, sea_slice_run, &sl[k])) break;
  sea_slice_run(&sl[0]);
  for (int k = started; k < t; k++) sea_slice_run(&sl[k]); /* threads that could not start */
  for (int k = 1; k < started; k++) pthread_join(th[k], NULL);
}

static void sea_gather(const struct sea_grid *g, const double *x, const double *y, const double *z,
                       size_t i, double rad, struct sea_ngb *b) {
  long lo[3], hi[3];
  const double p[3] = {x[i], y[i], z[i]};
  for (int d = 0; d < 3; d++)
    lo[d] = sea_grid_coord(g, d, p[d] - rad), hi[d] = sea_grid_coord(g, d, p[d] + rad);
  b->n = 0;
  const double r2max = rad * rad;
  for (long a = lo[0]; a <= hi[0]; a++)
    for (long c = lo[1]; c <= hi[1]; c++)
      for (long e = lo[2]; e <= hi[2]; e++) {
        const size_t k = (size_t)((a * g->n[1] + c) * g->n[2] + e);
        for (size_t s = g->start[k]; s < g->start[k + 1]; s++) {
          const size_t j = g->idx[s];
          const double dx = x[j] - p[0], dy = y[j] - p[1], dz = z[j] - p[2];
          const double r2 = dx * dx + dy * dy + dz * dz;
          if (r2 >= r2max) continue;
          if (b->n == b->cap) {
            b->cap = b->cap ? 2 * b->cap : 256;
            b->j = realloc(b->j, b->cap * sizeof(size_t));
            b->r = realloc(b->r, b->cap * sizeof(double));
            if (!b->j || !b->r) error_exit("SPH density: out of memory");
          }
          b->j[b->n] = j, b->r[b->n] = sqrt(r2), b->n++;
        }
      }
}

/** h^3 sum_j W(r_j, h) - eta^3 and its derivative in h (increasing in h). */
static double sea_hfun(const struct sea_ngb *b, double h, double eta, double *df) {
  const double H_inv = 1.0 / (kernel_gamma * h);
  double s = 0, ds = 0;
  for (size_t k = 0; k < b->n; k++) {
    const double q = b->r[k] * H_inv;
    if (q >= 1) continue;
    double w, dw;
    kernel_eval(q, &w, &dw);
    s += w, ds -= dw * q / h;
  }
  const double g3 = kernel_pow3(1.0 / kernel_gamma);
  *df = ds * g3;
  return s * g3 - kernel_pow3(eta);
}

/** Solve h of point i (h: the guess in, the solution out) and return its
 *  SPH density; leaves the neighbours within the support in b. */
static double sea_density_one(const struct sea_grid *g, const double *x, const double *y,
                              const double *z, const double *m, size_t i, double eta, double *h,
                              struct sea_ngb *b) {
  double rad = 1.3 * kernel_gamma * *h;
  for (int tries = 0;; tries++) {
    sea_gather(g, x, y, z, i, rad, b);
    const double h_hi = rad / kernel_gamma;
    double df;
    if (sea_hfun(b, h_hi, eta, &df) < 0) { /* the support needs to be larger */
      if (tries > 60) error_exit("SPH density: no smoothing length found for point %zu", i);
      rad *= 1.5;
      continue;
    }
    /* safeguarded Newton on [lo, hi] */
    double lo = 0, hi = h_hi, hh = fmin(*h, h_hi);
    for (int it = 0; it < 100; it++) {
      const double f = sea_hfun(b, hh, eta, &df);
      if (f < 0)
        lo = hh;
      else
        hi = hh;
      double nx = df > 0 ? hh - f / df : -1;
      if (!(nx > lo && nx < hi)) nx = 0.5 * (lo + hi);
      if (fabs(nx - hh) < 1e-12 * hh || hi - lo < 1e-12 * hh) {
        hh = nx;
        break;
      }
      hh = nx;
    }
    *h = hh;
    double rho = 0;
    for (size_t k = 0; k < b->n; k++) rho += m[b->j[k]] * kernel_W(b->r[k], hh);
    return rho;
  }
}

/** What the parallel loops of this file read and write. */
struct sea_ctx {
  const struct sea_grid *g;
  const double *x, *y, *z, *m, *rho_t;
  double eta, *h, *rho, *e, *dx;
};

static void sea_density_body(void *arg, size_t i, struct sea_ngb *b) {
  struct sea_ctx *c = arg;
  c->rho[i] = sea_density_one(c->g, c->x, c->y, c->z, c->m, i, c->eta, &c->h[i], b);
  if (c->e) c->e[i] = c->rho[i] / c->rho_t[i];
}

void ic_sph_density(size_t n, const double *x, const double *y, const double *z, const double *m,
                    double eta, double *h, double *rho) {
  double hmax = 0;
  for (size_t i = 0; i < n; i++) hmax = fmax(hmax, h[i]);
  struct sea_grid g;
  sea_grid_build(&g, n, x, y, z, kernel_gamma * hmax);
  struct sea_ctx c = {.g = &g, .x = x, .y = y, .z = z, .m = m, .eta = eta, .h = h, .rho = rho};
  sea_for(n, sea_density_body, &c);
  sea_grid_free(&g);
}

/** displacement -beta h^2 sum_j V_j (e_j - e_i) grad_i W_ij (the SPH
 *  pressure force with P proportional to rho_SPH / rho_profile), along the
 *  shell only, at most a tenth of the particle spacing */
static void sea_relax_body(void *arg, size_t i, struct sea_ngb *b) {
  struct sea_ctx *c = arg;
  const double *x = c->x, *y = c->y, *z = c->z, *m = c->m, *rho = c->rho, *e = c->e;
  const double beta = 0.3, hs = c->h[i];
  sea_gather(c->g, x, y, z, i, kernel_gamma * hs, b);
  double f[3] = {0, 0, 0};
  for (size_t k = 0; k < b->n; k++) {
    const size_t j = b->j[k];
    if (j == i || b->r[k] <= 0) continue;
    const double w = m[j] / rho[j] * (e[j] - e[i]) * kernel_dW_dr(b->r[k], hs) / b->r[k];
    f[0] += w * (x[i] - x[j]), f[1] += w * (y[i] - y[j]), f[2] += w * (z[i] - z[j]);
  }
  const double r = sqrt(x[i] * x[i] + y[i] * y[i] + z[i] * z[i]);
  double d[3] = {-beta * hs * hs * f[0], -beta * hs * hs * f[1], -beta * hs * hs * f[2]};
  if (r > 0) {
    const double u[3] = {x[i] / r, y[i] / r, z[i] / r};
    const double dr = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    for (int k = 0; k < 3; k++) d[k] -= dr * u[k];
  }
  const double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), cap = 0.1 * hs / c->eta;
  const double f_cap = len > cap ? cap / len : 1;
  for (int k = 0; k < 3; k++) c->dx[3 * i + k] = d[k] * f_cap;
}

void ic_sea_relax(size_t n, double *x, double *y, double *z, const double *m, const double *rho_t,
                  double eta, double *h, double *rho, int steps) {
  double *dx = error_malloc(3 * (n ? n : 1) * sizeof(double), "SEA relaxation");
  double *e = error_malloc((n ? n : 1) * sizeof(double), "SEA relaxation");
  for (int s = 0; s <= steps; s++) {
    double hmax = 0;
    for (size_t i = 0; i < n; i++) hmax = fmax(hmax, h[i]);
    struct sea_grid g;
    sea_grid_build(&g, n, x, y, z, kernel_gamma * hmax);
    struct sea_ctx c = {.g = &g,
                        .x = x,
                        .y = y,
                        .z = z,
                        .m = m,
                        .rho_t = rho_t,
                        .eta = eta,
                        .h = h,
                        .rho = rho,
                        .e = e,
                        .dx = dx};
    sea_for(n, sea_density_body, &c);
    if (s == steps) { /* the last pass only measures */
      sea_grid_free(&g);
      break;
    }
    sea_for(n, sea_relax_body, &c);
    sea_grid_free(&g);
    for (size_t i = 0; i < n; i++) {
      const double r = sqrt(x[i] * x[i] + y[i] * y[i] + z[i] * z[i]);
      double p[3] = {x[i] + dx[3 * i], y[i] + dx[3 * i + 1], z[i] + dx[3 * i + 2]};
      const double r1 = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      if (r > 0 && r1 > 0) x[i] = p[0] * r / r1, y[i] = p[1] * r / r1, z[i] = p[2] * r / r1;
    }
  }
  /* the moves along the shells shift the centre of mass: take it back to
   * the origin, again along the shells (each pass removes 2/3 of it) */
  for (int pass = 0; pass < 60; pass++) {
    double c[4] = {0, 0, 0, 0}, r2 = 0;
    for (size_t i = 0; i < n; i++) {
      c[0] += m[i] * x[i], c[1] += m[i] * y[i], c[2] += m[i] * z[i], c[3] += m[i];
      r2 = fmax(r2, x[i] * x[i] + y[i] * y[i] + z[i] * z[i]);
    }
    for (int k = 0; k < 3; k++) c[k] /= c[3];
    if (sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) < 1e-13 * sqrt(r2)) break;
    for (size_t i = 0; i < n; i++) {
      const double r = sqrt(x[i] * x[i] + y[i] * y[i] + z[i] * z[i]);
      const double p[3] = {x[i] - c[0], y[i] - c[1], z[i] - c[2]};
      const double r1 = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      if (r > 0 && r1 > 0) x[i] = p[0] * r / r1, y[i] = p[1] * r / r1, z[i] = p[2] * r / r1;
    }
  }
  free(dx), free(e);
}
