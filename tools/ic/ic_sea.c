/* Stretched equal-area (SEA) particle placement (Kegerreis et al. 2019,
 * MNRAS 487, 5029, Sect. 2), built on the recursive zonal equal-area
 * partition of the sphere (Leopardi 2006, ETNA 25, 309).
 *
 * A shell of N particles: two polar caps of area 4 pi / N, collars of
 * near-equal latitude width between them with the number of regions per
 * collar rounded with the remainder carried; a particle at the centre of
 * each region, each collar rotated to be as far as possible in longitude
 * from the collar before it, the colatitudes stretched away from the poles,
 * then the whole shell rotated at random.
 *
 * A planet: a tetrahedron of four particles at the centre, then nested
 * shells whose thickness follows the density, dr ∝ rho^(-1/3), with every
 * layer boundary on a shell boundary.  Shell masses come from the profile;
 * the particle count of each shell is its mass over the mean particle mass,
 * rounded with the remainder carried, so particle masses are equal within
 * that rounding and the total mass is exact.  See theory/planets.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "ic_planet.h"

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
 *  for N particles, a = 0.2, b = 2: pushes collars near the poles towards
 *  the equator, where the equal-area regions are too tall. */
static double sea_stretch(double th, int N) {
  const double a = 0.2, b = 2.0, s = 1.0 / sqrt((double)N);
  return th + (M_PI / 2 - th) * a * s * exp(-(M_PI / 2 - fabs(M_PI / 2 - th)) / (M_PI * b * s));
}

/** Longitude distance from phi to the nearest of m points at off + 2 pi k / m. */
static double sea_lon_gap(double phi, double off, int m) {
  const double d = 2 * M_PI / m;
  double t = fmod(phi - off, d);
  if (t < 0) t += d;
  return fmin(t, d - t);
}

void ic_sea_shell(int N, double *x, double *y, double *z, uint64_t *rng) {
  if (N <= 0) return;
  if (N <= 4) {
    /* the regular configurations: point, segment, triangle, tetrahedron */
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
    sea_rotate(N, x, y, z, rng);
    return;
  }
  const double area = 4 * M_PI / N;
  const double th_c = sea_cap_angle(area);
  /* Leopardi 2006, Sect. 3: ideal collar width sqrt(area), number of collars */
  int n_col = (int)lround((M_PI - 2 * th_c) / sqrt(area));
  if (n_col < 1) n_col = 1;
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
    if (m < 0) m = 0;
    /* colatitude of the collar's lower edge so that it holds exactly m regions */
    cum += m;
    const double th_hi = j == n_col ? M_PI - th_c : sea_cap_angle(cum * area);
    if (m > 0) {
      const double th = sea_stretch(0.5 * (th_lo + th_hi), N);
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
    }
    th_lo = th_hi;
  }
  x[i] = 0, y[i] = 0, z[i] = -1, i++;
  if (i != N) error_bug("SEA shell of %d points placed %d", N, i);
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

void ic_sea_planet(const struct ic_planet_profile *prof, const int32_t *mat_id, size_t N,
                   double eta, uint64_t seed, int64_t first_id, struct parts *p, int verbose) {
  const size_t n = prof->n;
  struct sea_cum c = {error_malloc(n * sizeof(double), "planet profile"),
                      error_malloc(n * sizeof(double), "planet profile"),
                      error_malloc(n * sizeof(double), "planet profile")};
  c.m[0] = c.rm[0] = c.s[0] = 0;
  for (size_t j = 1; j < n; j++) {
    /* trapezoids over each segment, each end with the density of the
     * segment's own layer side */
    const double r0 = prof->r[j - 1], r1 = prof->r[j], dr = r1 - r0;
    const int k = prof->layer[j];
    const double rho0 = prof->layer[j - 1] == k ? prof->rho[j - 1] : prof->rho[j];
    const double rho1 = prof->rho[j];
    c.m[j] = c.m[j - 1] + 2 * M_PI * dr * (r0 * r0 * rho0 + r1 * r1 * rho1);
    c.rm[j] = c.rm[j - 1] + 2 * M_PI * dr * (r0 * r0 * r0 * rho0 + r1 * r1 * r1 * rho1);
    c.s[j] = c.s[j - 1] + 0.5 * dr * (cbrt(rho0) + cbrt(rho1));
  }
  /* the trapezoids differ from the profile's own (explicit) integration by
   * O(dr): scale so that the particles carry exactly the profile's mass */
  const double scale = prof->M / c.m[n - 1];
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
  double r_in = sea_interp(prof, c.s, 0); /* 0 */
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
  struct shell_out {
    double r, mass;
    int N, k;
  };
  int n_shells = 0;
  size_t count = 0;
  for (int k = 0; k < prof->n_layers; k++) {
    const double r_out = prof->r_layer[k];
    const double r_lo = k == 0 ? 0 : prof->r_layer[k - 1];
    const double s_lo = sea_interp(prof, c.s, k == 0 ? r_in : r_lo);
    const double s_hi = sea_interp(prof, c.s, r_out);
    /* shells of thickness (mp / rho)^(1/3): their number is mp^(-1/3) int rho^(1/3) dr */
    int ns = (int)lround((s_hi - s_lo) / cbrt(mp));
    if (ns < 1) ns = 1;
    int layer_count = 0;
    for (int i = (k == 0 ? -1 : 0); i < ns; i++) {
      double ra, rb;
      int Ni;
      if (i < 0) {
        ra = 0, rb = r_in, Ni = 4;
      } else {
        ra = i == 0 ? (k == 0 ? r_in : r_lo) : sea_invert(prof, c.s, s_lo + (s_hi - s_lo) * i / ns);
        rb = i == ns - 1 ? r_out : sea_invert(prof, c.s, s_lo + (s_hi - s_lo) * (i + 1) / ns);
        const double want = (sea_interp(prof, c.m, rb) - sea_interp(prof, c.m, ra)) / mp;
        Ni = (int)lround(want + carry);
        if (Ni < 1) Ni = 1;
        carry += want - Ni;
      }
      const double Mi = sea_interp(prof, c.m, rb) - sea_interp(prof, c.m, ra);
      /* shell radius: mean of the half-way and the mass-weighted radii */
      const double r_mw = (sea_interp(prof, c.rm, rb) - sea_interp(prof, c.rm, ra)) / Mi;
      const double rs = 0.5 * (0.5 * (ra + rb) + r_mw);
      const double rho = sea_at(prof, prof->rho, rs, k), u = sea_at(prof, prof->u, rs, k);
      const double m = Mi / Ni;
      if ((size_t)Ni > N + 64) error_bug("SEA shell of %d particles", Ni);
      ic_sea_shell(Ni, sx, sy, sz, &rng);
      if (count + (size_t)Ni > p->capacity) parts_reserve(p, 2 * (count + (size_t)Ni));
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
  p->count = count;
  free(sx), free(sy), free(sz);
  free(c.m), free(c.rm), free(c.s);
}
