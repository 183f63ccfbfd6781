/* Stretched equal-area (SEA) particle placement (Kegerreis et al. 2019,
 * MNRAS 487, 5029, Sect. 2), built on the recursive zonal equal-area
 * partition of the sphere (Leopardi 2006, ETNA 25, 309).
 *
 * A shell of N particles: two polar caps of area 4 pi / N, collars of
 * near-equal latitude width between them with the number of regions per
 * collar rounded with the remainder carried; a particle at the centre of
 * each region, each collar rotated to be as far as possible in longitude
 * from the collar before it, the colatitudes stretched away from the poles,
 * then the whole shell rotated at random.  An isolated shell (ic_sea_shell)
 * of up to 20000 points takes the stretching and collar count that make its
 * SPH density most uniform (the paper fits a for N < 80 by hand); shells of
 * a planet (ic_sea_shell_a) keep the given a, b = 10 a.
 *
 * A planet: a tetrahedron of four particles at the centre, then nested
 * shells whose thickness follows the density, dr ∝ rho^(-1/3), with every
 * layer boundary on a shell boundary.  Shell masses come from the profile;
 * the particle count of each shell is its mass over the mean particle mass,
 * rounded with the remainder carried, so particle masses are equal within
 * that rounding and the total mass is exact (the outermost shell takes what
 * is left).  Then (ic_sea_planet's options) the shells' placement density is
 * iterated against their SPH density and the particles are relaxed along
 * their shells (ic_sea_fit.c).  See theory/planets.md, "SEA planet: the 1 %
 * bar". */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "tools/ic/ic_planet.h"
#include "tasks/hydro/kernel.h"

/* Isolated shells (ic_sea_shell): the resolution_eta of the SPH density
 * whose spread the choice of stretching and collar count minimises (Bolide's
 * default for the compiled-in kernel: 1.7 with Wendland C2, 1.2348 with the
 * cubic spline), the largest N searched (~7 s at 20000 on one core with the
 * cubic spline, ~3 times that with Wendland C2 at 1.7: ~80 points in the
 * support against ~28), and the grid of a searched, a = 0.10, 0.11, ...,
 * 0.32. */
#define SEA_ETA KERNEL_ETA_DEFAULT
#define SEA_FIT_NMAX 20000
#define SEA_FIT_A0 0.10
#define SEA_FIT_DA 0.01
#define SEA_FIT_NA 22

/** Colatitude of the cap of area `area` on the unit sphere. */
static double sea_cap_angle(double area) {
  double s = sqrt(area / (4 * M_PI));
  return 2 * asin(s < 1 ? s : 1);
}

/** Apply a uniformly random rotation (random unit quaternion, Shoemake
 *  1992, Graphics Gems III) to n points. */
static void sea_rotate(int n, double *x, double *y, double *z, uint64_t *rng) {
  const double u1 = ic_rng_uniform(rng), u2 = 2 * M_PI * ic_rng_uniform(rng),
               u3 = 2 * M_PI * ic_rng_uniform(rng);
  const double a = sqrt(1 - u1) * sin(u2), b = sqrt(1 - u1) * cos(u2), c = sqrt(u1) * sin(u3),
               w = sqrt(u1) * cos(u3);
  const double R[3][3] = {{1 - 2 * (b * b + c * c), 2 * (a * b - c * w), 2 * (a * c + b * w)},
                          {2 * (a * b + c * w), 1 - 2 * (a * a + c * c), 2 * (b * c - a * w)},
                          {2 * (a * c - b * w), 2 * (b * c + a * w), 1 - 2 * (a * a + b * b)}};
  for (int i = 0; i < n; i++) {
    const double p[3] = {x[i], y[i], z[i]};
    x[i] = R[0][0] * p[0] + R[0][1] * p[1] + R[0][2] * p[2];
    y[i] = R[1][0] * p[0] + R[1][1] * p[1] + R[1][2] * p[2];
    z[i] = R[2][0] * p[0] + R[2][1] * p[1] + R[2][2] * p[2];
  }
}

/** Latitude stretching of Kegerreis et al. (2019, eq. 3) of colatitude th
 *  for N particles (a = 0.2, b = 2 in the paper): pushes collars near the
 *  poles towards the equator, where the equal-area regions are too tall. */
static double sea_stretch(double th, int N, double a, double b) {
  const double s = 1.0 / sqrt((double)N);
  return th + (M_PI / 2 - th) * a * s * exp(-(M_PI / 2 - fabs(M_PI / 2 - th)) / (M_PI * b * s));
}

/** Longitude distance from phi to the nearest of m points at off + 2 pi k / m. */
static double sea_lon_gap(double phi, double off, int m) {
  const double d = 2 * M_PI / m;
  double t = fmod(phi - off, d);
  if (t < 0) t += d;
  return fmin(t, d - t);
}

/** The regular configurations for N <= 4: point, segment, triangle,
 *  tetrahedron (unrotated). */
static void sea_shell_small(int N, double *x, double *y, double *z) {
  static const double pts[4][4][3] = {
      {{0, 0, 1}},
      {{0, 0, 1}, {0, 0, -1}},
      {{1, 0, 0}, {-0.5, 0.8660254037844386, 0}, {-0.5, -0.8660254037844386, 0}},
      {{0.5773502691896258, 0.5773502691896258, 0.5773502691896258},
       {0.5773502691896258, -0.5773502691896258, -0.5773502691896258},
       {-0.5773502691896258, 0.5773502691896258, -0.5773502691896258},
       {-0.5773502691896258, -0.5773502691896258, 0.5773502691896258}}};
  for (int i = 0; i < N; i++)
    x[i] = pts[N - 1][i][0], y[i] = pts[N - 1][i][1], z[i] = pts[N - 1][i][2];
}

/** One unrotated SEA shell of N > 4 points with stretching parameters a,
 *  b and dcol collars more than the rounded ideal number.
 *  Returns 0 (nothing usable written) where that collar count leaves the
 *  last collar fewer than zero regions, 1 otherwise. */
static int sea_shell_place(int N, double a, double b, int dcol, double *x, double *y, double *z) {
  const double area = 4 * M_PI / N;
  const double th_c = sea_cap_angle(area);
  /* Leopardi 2006, Sect. 3: ideal collar width sqrt(area), number of collars */
  int n_col = (int)lround((M_PI - 2 * th_c) / sqrt(area)) + dcol;
  if (n_col < 1) {
    if (dcol != 0) return 0;
    n_col = 1;
  }
  const double d_f = (M_PI - 2 * th_c) / n_col;
  int i = 0;
  x[i] = 0, y[i] = 0, z[i] = 1, i++;
  double carry = 0, th_lo = th_c, prev_off = 0;
  int prev_m = 0, cum = 1;
  for (int j = 1; j <= n_col; j++) {
    /* ideal regions of collar j, rounded with the remainder carried */
    const double t0 = th_c + (j - 1) * d_f, t1 = th_c + j * d_f;
    const double y_j = 2 * M_PI * (cos(t0) - cos(t1)) / area;
    int m = (int)lround(y_j + carry);
    if (j == n_col) m = N - 1 - cum; /* the last collar takes what is left for the south cap */
    carry += y_j - m;
    if (m < 0) return 0;
    /* colatitude of the collar's lower edge so that it holds exactly m regions */
    cum += m;
    const double th_hi = j == n_col ? M_PI - th_c : sea_cap_angle(cum * area);
    if (m == 0) { /* an empty collar (never seen for dcol = 0; kept as before) */
      th_lo = th_hi;
      continue;
    }
    const double th = sea_stretch(0.5 * (th_lo + th_hi), N, a, b);
    /* rotate the collar to maximise the smallest longitude gap to the
     * previous collar: try 32 offsets over one region width */
    double off = 0, best = -1;
    for (int c = 0; c < 32 && prev_m > 0; c++) {
      const double o = (c + 0.5) / 32 * 2 * M_PI / m;
      double g = INFINITY;
      for (int q = 0; q < m && g > best; q++)
        g = fmin(g, sea_lon_gap(o + 2 * M_PI * q / m, prev_off, prev_m));
      if (g > best) best = g, off = o;
    }
    for (int q = 0; q < m; q++, i++) {
      const double phi = off + 2 * M_PI * q / m;
      x[i] = sin(th) * cos(phi), y[i] = sin(th) * sin(phi), z[i] = cos(th);
    }
    prev_off = off, prev_m = m;
    th_lo = th_hi;
  }
  x[i] = 0, y[i] = 0, z[i] = -1, i++;
  if (i != N) error_bug("SEA shell of %d points placed %d", N, i);
  return 1;
}

void ic_sea_shell_a(int N, double a, double *x, double *y, double *z, uint64_t *rng) {
  if (N <= 0) return;
  if (N <= 4)
    sea_shell_small(N, x, y, z);
  else if (!sea_shell_place(N, a, 10 * a, 0, x, y, z))
    error_bug("SEA shell of %d points: no room for the last collar", N);
  sea_rotate(N, x, y, z, rng);
}

static int sea_cmp_double(const void *p, const void *q) {
  const double a = *(const double *)p, b = *(const double *)q;
  return (a > b) - (a < b);
}

/** Largest |rho_SPH / median - 1| of N points of unit mass (Bolide's SPH
 *  density, ic_sph_density, resolution_eta SEA_ETA); work: 3 N doubles. */
static double sea_shell_spread(int N, const double *x, const double *y, const double *z,
                               double *work) {
  double *m = work, *h = work + N, *rho = work + 2 * N;
  for (int i = 0; i < N; i++) m[i] = 1, h[i] = SEA_ETA * sqrt(4 * M_PI / N);
  ic_sph_density((size_t)N, x, y, z, m, SEA_ETA, h, rho);
  memcpy(h, rho, N * sizeof(double));
  qsort(h, N, sizeof(double), sea_cmp_double);
  const double med = N % 2 ? h[N / 2] : 0.5 * (h[N / 2 - 1] + h[N / 2]);
  double d = 0;
  for (int i = 0; i < N; i++) d = fmax(d, fabs(rho[i] / med - 1));
  return d;
}

void ic_sea_shell(int N, double *x, double *y, double *z, uint64_t *rng) {
  if (N <= 4 || N > SEA_FIT_NMAX) {
    ic_sea_shell_a(N, 0.2, x, y, z, rng);
    return;
  }
  /* the stretching a, b and the collar count (the rounded ideal one, or
   * one fewer or more) that give the smallest spread of the SPH density
   * (the shell's random rotation does not change it); theory/planets.md,
   * "One shell of N points" */
  double *work = error_malloc(3 * (size_t)N * sizeof(double), "SEA shell");
  double best = INFINITY, best_a = 0.2, best_b = 2;
  int best_dcol = 0;
  /* first b = 10 a (Kegerreis et al.) and the three collar counts, then,
   * with the best collar count, b = 7 a and b = 14 a */
  for (int pass = 0; pass < 5; pass++) {
    const int dc = pass < 3 ? (pass == 2 ? -1 : pass) : best_dcol;
    const double bf = pass < 3 ? 10 : pass == 3 ? 7 : 14;
    for (int k = 0; k <= SEA_FIT_NA; k++) {
      const double a = SEA_FIT_A0 + k * SEA_FIT_DA, b = bf * a;
      if (!sea_shell_place(N, a, b, dc, x, y, z)) break;
      const double d = sea_shell_spread(N, x, y, z, work);
      if (d < best) best = d, best_a = a, best_b = b, best_dcol = dc;
    }
  }
  free(work);
  if (!sea_shell_place(N, best_a, best_b, best_dcol, x, y, z))
    error_bug("SEA shell of %d points", N);
  sea_rotate(N, x, y, z, rng);
}

/** Index j of the profile segment [r_j, r_j+1] holding r. */
static size_t sea_seg(const struct ic_planet_profile *p, double r) {
  size_t lo = 0, hi = p->n - 1;
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    if (p->r[mid] <= r)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

/** Value of array v at radius r inside layer k (never across a jump). */
static double sea_at(const struct ic_planet_profile *p, const double *v, double r, int k) {
  const size_t j = sea_seg(p, r);
  if (p->layer[j] != k) return v[j + 1];
  if (p->layer[j + 1] != k) return v[j];
  const double t = (r - p->r[j]) / (p->r[j + 1] - p->r[j]);
  return v[j] + t * (v[j + 1] - v[j]);
}

/** Cumulative integrals over the profile, centre outward: enclosed mass
 *  (recomputed from rho so that it is consistent with the density used),
 *  mass-weighted radius moment int r dm, and s = int rho^(1/3) dr. */
struct sea_cum {
  double *m, *rm, *s;
};

static double sea_interp(const struct ic_planet_profile *p, const double *v, double r) {
  const size_t j = sea_seg(p, r);
  const double t = (r - p->r[j]) / (p->r[j + 1] - p->r[j]);
  return v[j] + t * (v[j + 1] - v[j]);
}

/** Radius where the cumulative s reaches target. */
static double sea_invert(const struct ic_planet_profile *p, const double *s, double target) {
  size_t lo = 0, hi = p->n - 1;
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    if (s[mid] <= target)
      lo = mid;
    else
      hi = mid;
  }
  const double t = s[hi] > s[lo] ? (target - s[lo]) / (s[hi] - s[lo]) : 0;
  return p->r[lo] + t * (p->r[hi] - p->r[lo]);
}

/** Correction g(r) of the placement density (theory/planets.md, "SEA
 *  planet: the 1 % bar"): piecewise linear through (gr[k], gv[k]), constant
 *  beyond the ends; 1 where ng == 0. */
static double sea_g(const double *gr, const double *gv, int ng, double r) {
  if (ng <= 0) return 1;
  if (r <= gr[0]) return gv[0];
  if (r >= gr[ng - 1]) return gv[ng - 1];
  int lo = 0, hi = ng - 1;
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    if (gr[mid] <= r)
      lo = mid;
    else
      hi = mid;
  }
  const double t = (r - gr[lo]) / (gr[hi] - gr[lo]);
  return gv[lo] + t * (gv[hi] - gv[lo]);
}

/** One SEA placement of the profile, the shells' particle counts and radii
 *  following the density rho(r) g(r) (g == 1: the profile itself).  The
 *  outermost shell takes the mass that is left, so the total is exactly the
 *  profile's.  Writes the shell index of each particle to *shell_of (grown
 *  as needed), the radius and first particle of each shell to *sh_r,
 *  *sh_first (n_shells + 1 entries), and returns the number of shells. */
static int sea_place(const struct ic_planet_profile *prof, const int32_t *mat_id, size_t N,
                     double eta, uint64_t seed, int64_t first_id, struct parts *p, double dr_fac,
                     double a, const double *gr, const double *gv, int ng, double **sh_r,
                     size_t **sh_first, int **sh_layer, int verbose) {
  const size_t n = prof->n;
  struct sea_cum c = {error_malloc(n * sizeof(double), "planet profile"),
                      error_malloc(n * sizeof(double), "planet profile"),
                      error_malloc(n * sizeof(double), "planet profile")};
  c.m[0] = c.rm[0] = c.s[0] = 0;
  double m_plain = 0;
  for (size_t j = 1; j < n; j++) {
    /* trapezoids over each segment, each end with the density of the
     * segment's own layer side */
    const double r0 = prof->r[j - 1], r1 = prof->r[j], dr = r1 - r0;
    const int k = prof->layer[j];
    const double rho0p = prof->layer[j - 1] == k ? prof->rho[j - 1] : prof->rho[j];
    const double rho1p = prof->rho[j];
    m_plain += 2 * M_PI * dr * (r0 * r0 * rho0p + r1 * r1 * rho1p);
    const double rho0 = rho0p * sea_g(gr, gv, ng, r0), rho1 = rho1p * sea_g(gr, gv, ng, r1);
    c.m[j] = c.m[j - 1] + 2 * M_PI * dr * (r0 * r0 * rho0 + r1 * r1 * rho1);
    c.rm[j] = c.rm[j - 1] + 2 * M_PI * dr * (r0 * r0 * r0 * rho0 + r1 * r1 * r1 * rho1);
    c.s[j] = c.s[j - 1] + 0.5 * dr * (cbrt(rho0) + cbrt(rho1));
  }
  /* the trapezoids differ from the profile's own (explicit) integration by
   * O(dr): scale so that the particles carry exactly the profile's mass */
  const double scale = prof->M / m_plain;
  for (size_t j = 0; j < n; j++) c.m[j] *= scale, c.rm[j] *= scale;
  const double M = prof->M;
  const double mp = M / (double)N;
  uint64_t rng = seed * 0x2545f4914f6cdd1dULL + 12345;
  parts_alloc(p, 0);
  parts_reserve(p, N + N / 10 + 64);
  double carry = 0;
  double *sx = error_malloc((N + 64) * sizeof(double), "planet profile"),
         *sy = error_malloc((N + 64) * sizeof(double), "planet profile"),
         *sz = error_malloc((N + 64) * sizeof(double), "planet profile");
  /* central tetrahedron: the sphere holding 4 mean particle masses */
  double r_in = 0;
  {
    double lo = 0, hi = prof->r_layer[0];
    if (sea_interp(prof, c.m, hi) < 4 * mp)
      error_exit("planet: the innermost layer holds fewer than 4 particles; use more particles");
    for (int it = 0; it < 100; it++) {
      const double mid = 0.5 * (lo + hi);
      if (sea_interp(prof, c.m, mid) < 4 * mp)
        lo = mid;
      else
        hi = mid;
    }
    r_in = hi;
  }
  int n_shells = 0, cap_shells = 64;
  *sh_r = error_malloc(cap_shells * sizeof(double), "planet shells");
  *sh_first = error_malloc((cap_shells + 1) * sizeof(size_t), "planet shells");
  *sh_layer = error_malloc(cap_shells * sizeof(int), "planet shells");
  size_t count = 0;
  for (int k = 0; k < prof->n_layers; k++) {
    const double r_out = prof->r_layer[k];
    const double r_lo = k == 0 ? 0 : prof->r_layer[k - 1];
    const double s_lo = sea_interp(prof, c.s, k == 0 ? r_in : r_lo);
    const double s_hi = sea_interp(prof, c.s, r_out);
    /* shells of thickness dr_fac (mp / rho)^(1/3): their number is
     * mp^(-1/3) int rho^(1/3) dr / dr_fac */
    int ns = (int)lround((s_hi - s_lo) / (dr_fac * cbrt(mp)));
    if (ns < 1) ns = 1;
    int layer_count = 0;
    for (int i = (k == 0 ? -1 : 0); i < ns; i++) {
      double ra, rb;
      int Ni;
      const int last = k == prof->n_layers - 1 && i == ns - 1;
      if (i < 0) {
        ra = 0, rb = r_in, Ni = 4;
      } else {
        ra = i == 0 ? (k == 0 ? r_in : r_lo) : sea_invert(prof, c.s, s_lo + (s_hi - s_lo) * i / ns);
        rb = i == ns - 1 ? r_out : sea_invert(prof, c.s, s_lo + (s_hi - s_lo) * (i + 1) / ns);
        double want = (sea_interp(prof, c.m, rb) - sea_interp(prof, c.m, ra)) / mp;
        if (last) { /* the outermost shell: what is left of the profile's mass */
          double done = 0;
          for (size_t q = 0; q < count; q++) done += p->m[q];
          want = (M - done) / mp - carry;
        }
        Ni = (int)lround(want + carry);
        if (Ni < 1) Ni = 1;
        carry += want - Ni;
      }
      double Mi = sea_interp(prof, c.m, rb) - sea_interp(prof, c.m, ra);
      /* shell radius: mean of the half-way and the mass-weighted radii */
      const double r_mw = (sea_interp(prof, c.rm, rb) - sea_interp(prof, c.rm, ra)) / Mi;
      const double rs = 0.5 * (0.5 * (ra + rb) + r_mw);
      if (last) {
        double done = 0;
        for (size_t q = 0; q < count; q++) done += p->m[q];
        Mi = M - done;
        if (!(Mi > 0)) error_bug("SEA planet: no mass left for the outermost shell");
      }
      const double rho = sea_at(prof, prof->rho, rs, k), u = sea_at(prof, prof->u, rs, k);
      const double m = Mi / Ni;
      if ((size_t)Ni > N + 64) error_bug("SEA shell of %d particles", Ni);
      ic_sea_shell_a(Ni, a, sx, sy, sz, &rng);
      if (count + (size_t)Ni > p->capacity) parts_reserve(p, 2 * (count + (size_t)Ni));
      if (n_shells + 1 >= cap_shells) {
        cap_shells *= 2;
        *sh_r = realloc(*sh_r, cap_shells * sizeof(double));
        *sh_first = realloc(*sh_first, (cap_shells + 1) * sizeof(size_t));
        *sh_layer = realloc(*sh_layer, cap_shells * sizeof(int));
        if (!*sh_r || !*sh_first || !*sh_layer) error_exit("planet shells: out of memory");
      }
      (*sh_r)[n_shells] = rs, (*sh_first)[n_shells] = count, (*sh_layer)[n_shells] = k;
      for (int q = 0; q < Ni; q++, count++) {
        p->x[count] = rs * sx[q], p->y[count] = rs * sy[q], p->z[count] = rs * sz[q];
        p->vx[count] = p->vy[count] = p->vz[count] = 0;
        p->m[count] = m;
        p->rho[count] = rho;
        p->u[count] = u;
        p->h[count] = eta * cbrt(m / rho);
        p->mat[count] = mat_id[k];
        p->id[count] = first_id + (int64_t)count;
      }
      p->count = count;
      layer_count += Ni;
      n_shells++;
    }
    if (verbose)
      printf("  layer %d: %d shells, %d particles, r %.6g .. %.6g m\n", k, ns + (k == 0),
             layer_count, r_lo, r_out);
  }
  (*sh_first)[n_shells] = count;
  p->count = count;
  free(sx), free(sy), free(sz);
  free(c.m), free(c.rm), free(c.s);
  return n_shells;
}

/** Per shell: mean, min and max of rho_SPH / rho_profile - 1. */
static void sea_shell_stats(const size_t *first, int ns, const double *rho, const double *rho_t,
                            double *mean, double *lo, double *hi) {
  for (int k = 0; k < ns; k++) {
    double s = 0, a = INFINITY, b = -INFINITY;
    for (size_t i = first[k]; i < first[k + 1]; i++) {
      const double d = rho[i] / rho_t[i] - 1;
      s += d, a = fmin(a, d), b = fmax(b, d);
    }
    mean[k] = s / (double)(first[k + 1] - first[k]), lo[k] = a, hi[k] = b;
  }
}

void ic_sea_planet(const struct ic_planet_profile *prof, const int32_t *mat_id, size_t N,
                   double eta, uint64_t seed, int64_t first_id, struct parts *p,
                   const struct ic_sea_options *opt, int verbose) {
  double *gr = NULL, *gv = NULL, *sh_r = NULL;
  size_t *sh_first = NULL;
  int *sh_layer = NULL;
  int ng = 0;
  const struct ic_sea_options def = IC_SEA_OPTIONS_DEFAULT;
  if (!opt) opt = &def;
  for (int it = 0;; it++) {
    free(sh_r), free(sh_first), free(sh_layer);
    if (it > 0) parts_free(p); /* sea_place allocates p afresh (LeakSanitizer) */
    const int ns =
        sea_place(prof, mat_id, N, eta, seed, first_id, p, opt->shell_thickness, opt->stretch_a, gr,
                  gv, ng, &sh_r, &sh_first, &sh_layer, verbose && it == 0);
    if (opt->density_iter == 0 && opt->relax == 0) break;
    const size_t n = p->count;
    double *rho = error_malloc(n * sizeof(double), "SEA planet");
    double *h = error_malloc(n * sizeof(double), "SEA planet");
    memcpy(h, p->h, n * sizeof(double));
    const int final = it == opt->density_iter;
    if (final && opt->relax > 0)
      ic_sea_relax(n, p->x, p->y, p->z, p->m, p->rho, eta, h, rho, opt->relax);
    else
      ic_sph_density(n, p->x, p->y, p->z, p->m, eta, h, rho);
    double *mean = error_malloc(3 * (size_t)ns * sizeof(double), "SEA planet");
    double *lo = mean + ns, *hi = mean + 2 * ns;
    sea_shell_stats(sh_first, ns, rho, p->rho, mean, lo, hi);
    double worst = 0, wmean = 0;
    int kw = 0, kmw = 0;
    for (int k = 0; k < ns - 1; k++) {
      if (fmax(-lo[k], hi[k]) > worst) worst = fmax(-lo[k], hi[k]), kw = k;
      if (fabs(mean[k]) > wmean) wmean = fabs(mean[k]), kmw = k;
    }
    if (verbose)
      printf(
          "  SPH density, %s %d: largest |rho_SPH / rho - 1| %.4f (shell %d of %d), of a shell "
          "mean %.4f (shell %d), outermost shell mean %+.4f\n",
          final ? "relaxation steps" : "iteration", final ? opt->relax : it, worst, kw, ns, wmean,
          kmw, mean[ns - 1]);
    if (final) {
      free(rho), free(h), free(mean);
      break;
    }
    /* the placement density of every shell but the outermost (which takes
     * what mass is left) and those within 3 shells of an inner layer
     * boundary, divided by its mean rho_SPH / rho */
    double *ngr = error_malloc((size_t)ns * sizeof(double), "SEA planet");
    double *ngv = error_malloc((size_t)ns * sizeof(double), "SEA planet");
    int nn = 0;
    for (int k = 0; k < ns - 1; k++) {
      int near = 0;
      for (int q = k - 3; q <= k + 3; q++)
        if (q >= 0 && q < ns && sh_layer[q] != sh_layer[k]) near = 1;
      if (near) continue;
      ngr[nn] = sh_r[k];
      ngv[nn] = sea_g(gr, gv, ng, sh_r[k]) / (1 + mean[k]);
      nn++;
    }
    free(gr), free(gv);
    gr = ngr, gv = ngv, ng = nn;
    free(rho), free(h), free(mean);
  }
  free(gr), free(gv), free(sh_r), free(sh_first), free(sh_layer);
}
