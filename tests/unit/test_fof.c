/* Friends-of-friends (tools/fof/fof.h):
 *  - synthetic clumps (random points inside well-separated balls, densely
 *    enough to percolate) come out as exactly the clumps, whatever the
 *    particle order, plus isolated single particles as groups of one;
 *  - against the O(N^2) brute force on random points at linking lengths
 *    around the percolation threshold, with and without a keep mask, and on
 *    a box spread over more than 2^21 cells per axis (cell keys wrap):
 *    identical partitions;
 *  - the per-particle linking lengths of bolide-fof's default (friends when
 *    closer than the larger of the two lengths) against their brute force,
 *    on points whose density and lengths vary by 8x across the box, and on
 *    a uniform length equal to fof_groups with that length.
 * Exit 0 pass, 1 fail. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "tasks/damage/flaws.h"
#include "src/error.h"
#include "tools/fof/fof.h"

static int failures = 0;

/** Report one check: count of violations. */
static void check(const char *what, double err, double tol) {
  const int ok = err <= tol && err == err;
  printf("%-64s %10.3e  (tol %.0e)  %s\n", what, err, tol, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

/** Uniform random number in [0, 1). */
static double uniform(struct flaws_rng *r) {
  return (double)(flaws_rng_next(r) >> 11) * 0x1.0p-53;
}

/** Number of particles whose partitions a and b disagree on: the same
 *  partition up to renaming iff a[i] -> b[i] is a bijection. */
static long partition_diff(size_t n, const int64_t *a, const int64_t *b, int64_t na, int64_t nb) {
  if (na != nb) return labs((long)(na - nb)) + 1;
  int64_t *map = malloc((size_t)(na + 1) * sizeof *map),
          *inv = malloc((size_t)(na + 1) * sizeof *inv);
  for (int64_t g = 0; g <= na; g++) map[g] = inv[g] = -2;
  long bad = 0;
  for (size_t i = 0; i < n; i++) {
    if (a[i] < 0 || b[i] < 0) {
      bad += a[i] != b[i];
      continue;
    }
    if (map[a[i]] == -2 && inv[b[i]] == -2) map[a[i]] = b[i], inv[b[i]] = a[i];
    bad += map[a[i]] != b[i] || inv[b[i]] != a[i];
  }
  free(map);
  free(inv);
  return bad;
}

/** Clumps recovered exactly. */
static void test_clumps(void) {
  struct flaws_rng r;
  flaws_rng_seed(&r, 11);
  enum { NC = 12, PER = 400, NS = 30, N = NC * PER + NS };
  static double x[N], y[N], z[N];
  static int64_t truth[N], group[N];
  /* clump c: ball of radius 1 at (10 c, 3 c^2 mod 17, -5 c): separations > 5 */
  size_t n = 0;
  for (int c = 0; c < NC; c++)
    for (int k = 0; k < PER; k++) {
      double u, v, w;
      do {
        u = 2 * uniform(&r) - 1, v = 2 * uniform(&r) - 1, w = 2 * uniform(&r) - 1;
      } while (u * u + v * v + w * w > 1);
      x[n] = 10.0 * c + u, y[n] = (3 * c * c) % 17 + v, z[n] = -5.0 * c + w;
      truth[n++] = c;
    }
  /* isolated particles, far from everything and from each other */
  for (int s = 0; s < NS; s++) {
    x[n] = -100.0 - 7 * s, y[n] = 50.0, z[n] = 3.0 * s;
    truth[n++] = NC + s;
  }
  /* shuffle the order */
  for (size_t i = n - 1; i > 0; i--) {
    const size_t j = flaws_rng_below(&r, i + 1);
    double t = x[i];
    x[i] = x[j], x[j] = t;
    t = y[i], y[i] = y[j], y[j] = t;
    t = z[i], z[i] = z[j], z[j] = t;
    const int64_t g = truth[i];
    truth[i] = truth[j], truth[j] = g;
  }
  /* 400 points in a unit ball: mean spacing ~0.22; L = 0.5 percolates */
  const int64_t ng = fof_groups(n, x, y, z, NULL, 0.5, group);
  printf("clumps: %lld groups (expected %d)\n", (long long)ng, NC + NS);
  check("clumps recovered exactly (particles misassigned)",
        partition_diff(n, truth, group, NC + NS, ng), 0);
}

/** Against brute force. */
static void test_brute(void) {
  struct flaws_rng r;
  flaws_rng_seed(&r, 5);
  enum { N = 3000 };
  static double x[N], y[N], z[N];
  static int64_t a[N], b[N];
  static unsigned char keep[N];
  for (int i = 0; i < N; i++) {
    x[i] = uniform(&r), y[i] = uniform(&r), z[i] = uniform(&r);
    keep[i] = uniform(&r) < 0.7;
  }
  /* mean spacing N^(-1/3) ~ 0.069; percolation near 0.87 spacing */
  const double Ls[] = {0.02, 0.045, 0.06, 0.07, 0.1, 2.0};
  for (size_t k = 0; k < sizeof Ls / sizeof Ls[0]; k++)
    for (int masked = 0; masked < 2; masked++) {
      const unsigned char *kp = masked ? keep : NULL;
      const int64_t na = fof_groups(N, x, y, z, kp, Ls[k], a);
      const int64_t nb = fof_groups_brute(N, x, y, z, kp, Ls[k], b);
      char what[128];
      snprintf(what, sizeof what, "grid = brute force, L = %.3f%s (%lld groups)", Ls[k],
               masked ? ", 70% kept" : "", (long long)nb);
      check(what, partition_diff(N, a, b, na, nb), 0);
    }
  /* a spread over 1e7 linking lengths: keys wrap modulo 2^21 cells */
  for (int i = 0; i < N; i++) {
    const double s = (i % 3 == 0) ? 1e7 : 1.0;
    x[i] = s * uniform(&r), y[i] = uniform(&r), z[i] = s * uniform(&r);
  }
  const int64_t na = fof_groups(N, x, y, z, NULL, 0.09, a);
  const int64_t nb = fof_groups_brute(N, x, y, z, NULL, 0.09, b);
  check("grid = brute force, spread over 1e7 L (wrapped keys)", partition_diff(N, a, b, na, nb), 0);
}

/** Per-particle linking lengths against brute force. */
static void test_local(void) {
  struct flaws_rng r;
  flaws_rng_seed(&r, 9);
  enum { N = 3000 };
  static double x[N], y[N], z[N], ell[N];
  static int64_t a[N], b[N];
  static unsigned char keep[N];
  for (int i = 0; i < N; i++) {
    /* denser towards x = 0: spacing and length grow with x (as the outer
     * shells of a planet are sparser) */
    const double u = uniform(&r);
    x[i] = u * u * u, y[i] = uniform(&r), z[i] = uniform(&r);
    keep[i] = uniform(&r) < 0.8;
  }
  const double F[] = {0.5, 0.8, 1.0, 1.3};
  for (size_t k = 0; k < sizeof F / sizeof F[0]; k++)
    for (int masked = 0; masked < 2; masked++) {
      for (int i = 0; i < N; i++) ell[i] = F[k] * 0.05 * (0.25 + 1.75 * cbrt(x[i]));
      const unsigned char *kp = masked ? keep : NULL;
      const int64_t na = fof_groups_local(N, x, y, z, kp, ell, a);
      const int64_t nb = fof_groups_local_brute(N, x, y, z, kp, ell, b);
      char what[128];
      snprintf(what, sizeof what, "local lengths = brute force, F = %.1f%s (%lld groups)", F[k],
               masked ? ", 80% kept" : "", (long long)nb);
      check(what, partition_diff(N, a, b, na, nb), 0);
    }
  for (int i = 0; i < N; i++) ell[i] = 0.03;
  const int64_t na = fof_groups_local(N, x, y, z, NULL, ell, a);
  const int64_t nb = fof_groups(N, x, y, z, NULL, 0.03, b);
  check("local lengths all equal = one linking length", partition_diff(N, a, b, na, nb), 0);
}

int main(int argc, char **argv) {
  (void)argc;
  error_init(argv[0]);
  test_clumps();
  test_brute();
  test_local();
  if (failures) printf("%d check(s) FAILED\n", failures);
  return failures ? 1 : 0;
}
