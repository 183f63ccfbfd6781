/* Timing of the gravity tree for tools/bench/gravity.sh (not a test: speed
 * is never asserted).  bench_gravity N [SET]: N particles of a Plummer
 * sphere (SET plummer, default) or a uniform sphere (uniform), the space
 * with leaves of 32 and at most 4^3 top-level cells, the defaults of
 * gravity (theta 0.5, GRAVITY_ORDER_DEFAULT, epsilon_fmm); one untimed pass (the first
 * step: no acceleration scale), then prints "N seconds" for the second
 * (wall clock) and, on stderr, its CPU time and interaction counts. */
#ifdef HAVE_CONFIG_H
#include "config.h"
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "src/error.h"
#include "tasks/gravity/gravity_cpu.h"
#include "src/part.h"
#include "src/space.h"

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  if (argc < 2 || atol(argv[1]) < 1) error_exit("usage: bench_gravity N [plummer|uniform]");
  const size_t n = (size_t)atol(argv[1]);
  const int uniform = argc > 2 && strcmp(argv[2], "uniform") == 0;
  struct parts p;
  parts_alloc(&p, n);
  p.count = n;
  srand48(1);
  for (size_t i = 0; i < n; i++) {
    double r;
    if (uniform) {
      r = cbrt(drand48());
    } else {
      do r = 0.2 / sqrt(pow(drand48() + 1e-300, -2.0 / 3.0) - 1.0);
      while (r >= 1.8);
    }
    const double z = 2.0 * drand48() - 1.0, ph = 2.0 * M_PI * drand48(), s = sqrt(1.0 - z * z);
    p.x[i] = 2.0 + r * s * cos(ph);
    p.y[i] = 2.0 + r * s * sin(ph);
    p.z[i] = 2.0 + r * z;
    p.m[i] = 1.0 / n;
    p.h[i] = 1e-3;
    p.id[i] = (int64_t)i;
  }
  struct space s;
  const double L[3] = {4.0, 4.0, 4.0};
  space_init(&s, &p, L, 0, 32, 4);
  space_rebuild(&s);
  struct gravity_props gp;
  const double eps = 0.1 * cbrt(1.0 / n);
  gravity_props_set(&gp, 1.0, 0.5, eps, GRAVITY_SOFTENING_SPLINE, GRAVITY_ORDER_DEFAULT);
  gp.epsilon_fmm = GRAVITY_EPSILON_FMM_DEFAULT;
  struct gravity_cell *gc = NULL;
  int cap = 0;
  gc = gravity_cells_reserve(gc, &cap, s.cells_capacity);
  gravity_tree_all(&p, s.cells, s.nr_top, gc, &gp);
  struct gravity_counters cnt;
  gravity_counters_get(&cnt, 1);
  const double t0 = now();
  const clock_t c0 = clock();
  gravity_tree_all(&p, s.cells, s.nr_top, gc, &gp);
  const double cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
  printf("%zu %.4f\n", n, now() - t0);
  gravity_counters_get(&cnt, 0);
  /* diagnostics on stderr: CPU time and work per particle */
  fprintf(stderr,
          "# cpu %.4f s, per particle: %.1f P2P pairs, %.2f M2L, %.2f M2P, %.2f MAC tests\n", cpu,
          (double)cnt.p2p / n, (double)cnt.m2l / n, (double)cnt.m2p / n, (double)cnt.mac / n);
  free(gc);
  space_free(&s);
  parts_free(&p);
  return 0;
}
