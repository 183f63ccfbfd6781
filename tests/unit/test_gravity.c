/* Gravity accuracy (theory/validation.md, "Gravity accuracy"): tree forces
 * against direct summation.
 *
 * For a uniform sphere, a Plummer sphere and two clustered bodies (two
 * Plummer spheres of different mass and size), N = 20000 each, in an open
 * box split by the real space (src/space.h: top-level grid + octrees), the
 * whole task sequence (gravity_tree_all: up, self and near pairs, long
 * range, down) is compared with gravity_direct:
 *   - relative acceleration error |a - a_dir| / |a_dir|: median < 1e-4 and
 *     99th percentile < 1e-3 at the defaults: theta_cr 0.5, order 5,
 *     (the adaptive criterion, Gravity:epsilon_fmm, on the second step; on
 *     the first step, with no acceleration scale yet, on the scale of
 *     gravity_estimate's cheaper pass; SWIFT's tighter bars:
 *     tests/physics/test_gravity_accuracy.sh);
 *   - with the geometric criterion alone (a run's first step), both fall
 *     monotonically as theta shrinks (0.9, 0.7, 0.5);
 *   - momentum: |sum m a| / sum m |a| at rounding level (the mutual M2L of
 *     Dehnen 2000 conserves momentum exactly; theory/gravity.md);
 *   - potential energy 1/2 sum m pot against direct summation (< 1e-6 at
 *     the defaults);
 * and, once (uniform sphere): the result does not depend on how the work is
 * split into tasks (1 top-level cell vs 4^3), Plummer softening through the
 * softened expansions, the threaded direct sum equals the serial one, the
 * gravitational time step.
 * Exit 0 pass, 1 fail. */
#ifdef HAVE_CONFIG_H
#include "config.h"
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "src/error.h"
#include "tests/helpers/gravity_sets.h"
#include "tasks/gravity/gravity_cpu.h"
#include "src/part.h"
#include "src/space.h"

/** Particles per set. */
#define NPART 20000
/** Box edge; the sets are centred at L/2. */
#define BOX 4.0

static int failures = 0;

/** Record and print one check. */
static void check(int ok, const char *what, double got, double limit) {
  printf("  %-60s %11.3e (limit %.1e) %s\n", what, got, limit, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

/** Uniform random number in [0, 1) (fixed seed: reproducible). */
static double urand(void) {
  return drand48();
}

enum set_kind { SET_UNIFORM, SET_PLUMMER, SET_TWO_BODIES };
static const char *set_name[] = {"uniform sphere", "Plummer sphere", "two clustered bodies"};

/** Fill n particles of the given set (total mass 1). */
static void make_set(struct parts *p, int kind, size_t n) {
  parts_alloc(p, n);
  p->count = n;
  const double c[3] = {0.5 * BOX, 0.5 * BOX, 0.5 * BOX};
  for (size_t i = 0; i < n; i++) {
    double x[3];
    p->m[i] = 1.0 / n;
    if (kind == SET_UNIFORM) {
      gset_place(cbrt(urand()), c, x);
    } else if (kind == SET_PLUMMER) {
      gset_place(gset_plummer_radius(0.2, 1.8), c, x);
    } else {
      gset_two_bodies(i, n, c, x);
    }
    p->x[i] = x[0];
    p->y[i] = x[1];
    p->z[i] = x[2];
    p->h[i] = 1e-3;
    p->id[i] = (int64_t)i;
  }
}

/** Zero the potentials.  The gravitational accelerations ga stay: gravity_up
 *  reads them as the scale of the adaptive criterion (the previous pass) and
 *  zeroes them itself; gravity_direct overwrites them. */
static void zero_acc(struct parts *p) {
  memset(p->pot, 0, p->count * sizeof(double));
}

/** Reference accelerations and potentials of direct summation. */
struct reference {
  double *ax, *ay, *az, *pot; /**< per particle, indexed by particle id (rebuilds reorder) */
  double epot;                /**< potential energy */
};

/** Errors of the current accelerations against the reference. */
struct errors {
  double median, p99, max; /**< relative acceleration errors */
  double momentum;         /**< |sum m a| / sum m |a| */
  double epot;             /**< relative potential energy error */
};

static struct errors measure(const struct parts *p, const struct reference *ref) {
  const size_t n = p->count;
  double *e = error_malloc(n * sizeof *e, "errors");
  double P[3] = {0, 0, 0}, A = 0.0;
  for (size_t i = 0; i < n; i++) {
    const size_t k = (size_t)p->id[i];
    const double d[3] = {p->gax[i] - ref->ax[k], p->gay[i] - ref->ay[k], p->gaz[i] - ref->az[k]};
    const double a =
        sqrt(ref->ax[k] * ref->ax[k] + ref->ay[k] * ref->ay[k] + ref->az[k] * ref->az[k]);
    e[i] = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / a;
    P[0] += p->m[i] * p->gax[i];
    P[1] += p->m[i] * p->gay[i];
    P[2] += p->m[i] * p->gaz[i];
    A += p->m[i] * sqrt(p->gax[i] * p->gax[i] + p->gay[i] * p->gay[i] + p->gaz[i] * p->gaz[i]);
  }
  qsort(e, n, sizeof *e, gset_cmp_double);
  struct errors r;
  r.median = e[n / 2];
  r.p99 = e[(size_t)(0.99 * n)];
  r.max = e[n - 1];
  r.momentum = sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]) / A;
  r.epot = fabs(gravity_potential_energy(p) - ref->epot) / fabs(ref->epot);
  free(e);
  return r;
}

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

/** Tree forces of the whole set into p (ax and pot zeroed first), passes
 *  times in a row as on consecutive steps.  fresh: start with ga = 0, as on
 *  the first step of a run (no scale for the adaptive criterion: geometric
 *  only); else the adaptive criterion uses |ga| of the previous pass. */
static void tree(struct parts *p, struct space *s, const struct gravity_props *gp, int fresh,
                 int passes) {
  static struct gravity_cell *gc = NULL;
  static int cap = 0;
  gc = gravity_cells_reserve(gc, &cap, s->cells_capacity);
  if (fresh) {
    memset(p->gax, 0, p->count * sizeof(double));
    memset(p->gay, 0, p->count * sizeof(double));
    memset(p->gaz, 0, p->count * sizeof(double));
  }
  for (int pass = 0; pass < passes; pass++) {
    zero_acc(p);
    gravity_tree_all(p, s->cells, s->nr_top, gc, gp);
  }
}

/** Direct summation into a reference (nthreads: as gravity_direct). */
static void reference_make(struct parts *p, double eps, int softening, int nthreads,
                           struct reference *ref) {
  const size_t n = p->count;
  zero_acc(p);
  gravity_direct(p, 1.0, eps, softening, nthreads);
  ref->ax = error_malloc(n * sizeof(double), "ref");
  ref->ay = error_malloc(n * sizeof(double), "ref");
  ref->az = error_malloc(n * sizeof(double), "ref");
  ref->pot = error_malloc(n * sizeof(double), "ref");
  for (size_t i = 0; i < n; i++) {
    const size_t k = (size_t)p->id[i];
    ref->ax[k] = p->gax[i];
    ref->ay[k] = p->gay[i];
    ref->az[k] = p->gaz[i];
    ref->pot[k] = p->pot[i];
  }
  ref->epot = gravity_potential_energy(p);
}

static void reference_free(struct reference *ref) {
  free(ref->ax);
  free(ref->ay);
  free(ref->az);
  free(ref->pot);
}

/** One set: accuracy at the default, monotone in theta, conservation. */
static void test_set(int kind, double eps, double eps_fmm) {
  struct parts p;
  struct space s;
  make_set(&p, kind, NPART);
  const double L[3] = {BOX, BOX, BOX};
  space_init(&s, &p, L, 0, 32, 4);
  if (space_rebuild(&s) != 0) error_exit("test_gravity: particles outside the box");
  printf("%s: N = %zu, %d top-level cells, %d cells, eps = %g\n", set_name[kind], p.count, s.nr_top,
         s.nr_cells, eps);

  double t0 = now();
  struct reference ref;
  reference_make(&p, eps, GRAVITY_SOFTENING_SPLINE, 2, &ref);
  printf("  direct summation: %.2f s\n", now() - t0);

  /* geometric criterion alone (epsilon_fmm 0), as on a run's first step */
  const double thetas[3] = {0.9, 0.7, 0.5};
  struct errors e[3];
  for (int t = 0; t < 3; t++) {
    struct gravity_props gp;
    gravity_props_set(&gp, 1.0, thetas[t], eps, GRAVITY_SOFTENING_SPLINE, GRAVITY_ORDER_DEFAULT);
    t0 = now();
    tree(&p, &s, &gp, 1, 1);
    e[t] = measure(&p, &ref);
    printf(
        "  geometric theta %.1f p %d: %.2f s, |da|/|a| median %.2e p99 %.2e max %.2e, momentum "
        "%.1e,"
        " E_pot %.1e\n",
        thetas[t], gp.order, now() - t0, e[t].median, e[t].p99, e[t].max, e[t].momentum, e[t].epot);
  }
  /* The defaults: theta_cr 0.5, order 5, adaptive criterion epsilon_fmm,
   * on the second step: the pass at theta 0.5 above was the first. */
  struct gravity_props gp;
  gravity_props_set(&gp, 1.0, 0.5, eps, GRAVITY_SOFTENING_SPLINE, GRAVITY_ORDER_DEFAULT);
  gp.epsilon_fmm = eps_fmm;
  t0 = now();
  tree(&p, &s, &gp, 0, 1);
  const struct errors ed = measure(&p, &ref);
  printf(
      "  default (theta 0.5, p %d, epsilon_fmm %g, 2nd step): %.2f s, median "
      "%.2e p99 %.2e max %.2e, momentum %.1e, E_pot %.1e\n",
      gp.order, gp.epsilon_fmm, now() - t0, ed.median, ed.p99, ed.max, ed.momentum, ed.epot);
  check(ed.median < 1e-4, "median relative force error (defaults)", ed.median, 1e-4);
  check(ed.p99 < 1e-3, "99th percentile (defaults)", ed.p99, 1e-3);
  check(e[1].median < e[0].median && e[2].median < e[1].median,
        "median falls as theta shrinks 0.9 -> 0.7 -> 0.5 (ratio)", e[2].median / e[0].median, 1);
  check(e[1].p99 < e[0].p99 && e[2].p99 < e[1].p99,
        "99th percentile falls as theta shrinks (ratio)", e[2].p99 / e[0].p99, 1);
  /* The defaults on a run's first step: no acceleration scale yet. */
  t0 = now();
  tree(&p, &s, &gp, 1, 1);
  const struct errors ef = measure(&p, &ref);
  printf("  default, 1st step (no previous accelerations): %.2f s, median %.2e p99 %.2e max %.2e\n",
         now() - t0, ef.median, ef.p99, ef.max);
  check(ef.median < 1e-4, "median relative force error (defaults, first step)", ef.median, 1e-4);
  check(ef.p99 < 1e-3, "99th percentile (defaults, first step)", ef.p99, 1e-3);
  double mom = fmax(ed.momentum, ef.momentum);
  for (int t = 0; t < 3; t++) mom = fmax(mom, e[t].momentum);
  check(mom < 1e-12, "momentum |sum m a| / sum m |a| (every run)", mom, 1e-12);
  check(ed.epot < 1e-6, "potential energy relative error (defaults)", ed.epot, 1e-6);

  if (kind == SET_UNIFORM) {
    /* The same forces whatever the split into tasks: one top-level cell
     * (everything in one self task) against 4^3 (pairs and long range). */
    struct space s1;
    space_init(&s1, &p, L, 0, 32, 1);
    space_rebuild(&s1);
    tree(&p, &s1, &gp, 0, 1);
    const struct errors e1 = measure(&p, &ref);
    printf("  1 top-level cell: median %.2e p99 %.2e\n", e1.median, e1.p99);
    check(e1.median < 1e-4 && e1.p99 < 1e-3, "one top-level cell: 99th percentile", e1.p99, 1e-3);
    space_free(&s1);
    space_rebuild(&s); /* s1's rebuild reordered the particles */

    /* Plummer softening, large enough to matter, through softened expansions. */
    const double epl = 0.05;
    reference_free(&ref);
    reference_make(&p, epl, GRAVITY_SOFTENING_PLUMMER, 2, &ref);
    gravity_props_set(&gp, 1.0, 0.5, epl, GRAVITY_SOFTENING_PLUMMER, GRAVITY_ORDER_DEFAULT);
    gp.epsilon_fmm = eps_fmm;
    tree(&p, &s, &gp, 1, 2);
    const struct errors ep = measure(&p, &ref);
    printf("  Plummer eps %.2f: median %.2e p99 %.2e momentum %.1e\n", epl, ep.median, ep.p99,
           ep.momentum);
    check(ep.median < 1e-4 && ep.p99 < 1e-3, "Plummer softening: 99th percentile", ep.p99, 1e-3);

    /* Serial (symmetric) and threaded (gather) direct sums agree. */
    struct parts q;
    make_set(&q, SET_PLUMMER, 3000);
    zero_acc(&q);
    gravity_direct(&q, 1.0, epl, GRAVITY_SOFTENING_PLUMMER, 2);
    double *qa = error_malloc(3 * q.count * sizeof(double), "test");
    for (size_t i = 0; i < q.count; i++) {
      qa[3 * i] = q.gax[i];
      qa[3 * i + 1] = q.gay[i];
      qa[3 * i + 2] = q.gaz[i];
    }
    zero_acc(&q);
    gravity_direct(&q, 1.0, epl, GRAVITY_SOFTENING_PLUMMER, 1);
    double d = 0.0;
    for (size_t i = 0; i < q.count; i++) {
      const double *r = qa + 3 * i;
      const double dd[3] = {q.gax[i] - r[0], q.gay[i] - r[1], q.gaz[i] - r[2]};
      d = fmax(d, sqrt(dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]) /
                      sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]));
    }
    check(d < 1e-10, "direct summation: serial = threaded", d, 1e-10);
    free(qa);
    parts_free(&q);

    /* Time step sqrt(2 eta eps / |a|). */
    const double a[3] = {3.0, 0.0, 4.0};
    const double dt = gravity_timestep(a, 0.01, 0.025);
    const double dt_err = fabs(dt - sqrt(2 * 0.025 * 0.01 / 5.0));
    check(dt_err < 1e-15, "time step sqrt(2 eta eps/|a|)", dt_err, 1e-15);
  }
  reference_free(&ref);
  space_free(&s);
  parts_free(&p);
}

int main(int argc, char **argv) {
  /* optional argument: epsilon_fmm other than the default (exploration) */
  const double eps_fmm = argc > 1 ? atof(argv[1]) : GRAVITY_EPSILON_FMM_DEFAULT;
  srand48(20260101);
  test_set(SET_UNIFORM, 0.005, eps_fmm);
  test_set(SET_PLUMMER, 0.002, eps_fmm);
  test_set(SET_TWO_BODIES, 0.002, eps_fmm);
  printf("%d failure(s)\n", failures);
  return failures ? 1 : 0;
}
