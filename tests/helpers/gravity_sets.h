/* Particle sets of the gravity tests (test_gravity, test_gravity_reuse,
 * test_gravity_hsoft): random points drawn with drand48 in a fixed order, so
 * that a seed gives the same set in every test. */
#ifndef BOLIDE_TESTS_GRAVITY_SETS_H
#define BOLIDE_TESTS_GRAVITY_SETS_H

#include <math.h>
#include <stddef.h>
#include <stdlib.h>

#include "src/part.h"

/** A random direction times r, added to c (draws z, then the azimuth). */
static inline void gset_place(double r, const double c[3], double out[3]) {
  const double z = 2.0 * drand48() - 1.0, ph = 2.0 * M_PI * drand48(), s = sqrt(1.0 - z * z);
  out[0] = c[0] + r * s * cos(ph);
  out[1] = c[1] + r * s * sin(ph);
  out[2] = c[2] + r * z;
}

/** Radius drawn from a Plummer sphere of scale a, truncated at rmax
 *  (Aarseth, Henon & Wielen 1974: M(<r)/M = r^3 / (r^2 + a^2)^(3/2)). */
static inline double gset_plummer_radius(double a, double rmax) {
  for (;;) {
    const double X = drand48();
    if (X <= 0.0) continue;
    const double r = a / sqrt(pow(X, -2.0 / 3.0) - 1.0);
    if (r < rmax) return r;
  }
}

/** Point i of n of two clustered bodies centred near c: a Plummer sphere of
 *  2/3 of the particles (scale 0.15) and one of 1/3 (scale 0.08) 1.2 apart. */
static inline void gset_two_bodies(size_t i, size_t n, const double c[3], double out[3]) {
  const int big = i < 2 * n / 3;
  const double cc[3] = {c[0] + (big ? -0.4 : 0.8), c[1] + (big ? 0.0 : 0.3), c[2]};
  gset_place(gset_plummer_radius(big ? 0.15 : 0.08, 0.9), cc, out);
}

/** Fill p (allocated, count n) for the walks' tests (test_gravity_walk,
 *  test_gravity_remote): two bodies (gset_two_bodies) or a uniform sphere
 *  of radius 1 about c; mass 1/n, h uniform in [0.01, 0.02), ids 0 .. n-1.
 *  The caller seeds drand48. */
static inline void gset_fill_walk(struct parts *p, size_t n, const double c[3], int two_bodies) {
  for (size_t i = 0; i < n; i++) {
    double x[3];
    if (two_bodies)
      gset_two_bodies(i, n, c, x);
    else
      gset_place(cbrt(drand48()), c, x);
    p->x[i] = x[0], p->y[i] = x[1], p->z[i] = x[2];
    p->m[i] = 1.0 / n;
    p->h[i] = 0.01 * (1.0 + drand48());
    p->id[i] = (int64_t)i;
  }
}

/** qsort comparison of doubles. */
static inline int gset_cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

#endif
