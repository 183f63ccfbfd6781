/* Accuracy against cost of the gravity tree, for tools/bench/gravity_accuracy.sh
 * (a measurement, not a test: nothing is asserted).
 *
 *   bench_gravity_accuracy [options] SOURCE
 *
 * SOURCE: initial conditions in HDF5 (the reference impact of
 * theory/validation.md, "Benchmarks",
 * read with ic_read in the file's own units; G = 1: relative errors and
 * times do not depend on G), or a built-in set: plummer2:N (the two
 * clustered Plummer spheres of tests/helpers/gravity_sets.h), plummer:N, uniform:N.
 * Options:
 *   -s EPS      softening (Plummer-equivalent, spline kernel; in the file's
 *               length unit; default: the built-in sets' 0.1 N^(-1/3) x box 1);
 *               -s auto: the median particle spacing (m / rho)^(1/3) of the
 *               file's masses and densities (the reference impact's
 *               "softening = lattice spacing")
 *   -c E,T,P    a configuration: Gravity:epsilon_fmm E, theta_cr T, order P
 *               (repeat; default: the defaults)
 *   -e K        evaluations per configuration (default 2): the first from
 *               ga = 0 (a run's first step), each later one with the
 *               previous one's |ga| as the adaptive criterion's scale
 *   -k K        reference (direct summation) for every K-th particle only
 *               (by id; default 1: every particle)
 *   -r FILE     keep the reference in FILE (read it when it is there and
 *               matches: the direct sum once for many invocations)
 *   -t T        threads of the direct summation (default 2)
 *   -l L        leaf size (default 32, the engine's with gravity on)
 *   -m M        most top-level cells per side (default 16, the engine's)
 *   -g          evaluate on the GPU (gpu_grav_tree_all with the upward pass
 *               and the walks on the device; CUDA builds; the first
 *               evaluation's gravity_estimate runs before, on the host's -t
 *               threads, timed apart), else the CPU's serial
 *               gravity_tree_all (its first evaluation's time includes the
 *               estimate, serial)
 *
 * Prints one line per configuration and evaluation:
 *   mode eps_fmm theta order eval median p90 p99 max seconds m2l/N p2p/N
 * the relative acceleration error |a - a_direct| / |a_direct| over the
 * referenced particles, the time of the evaluation (CPU: the thread's CPU
 * time of the serial tree, which other processes on a shared machine do
 * not inflate; GPU: wall clock), and the CPU walk's M2L and P2P counts per
 * particle. */
#ifdef HAVE_CONFIG_H
#include "config.h"
#endif

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "src/error.h"
#include "tasks/gravity/gravity_cpu.h"
#include "tests/helpers/gravity_sets.h"
#include "src/io/ic.h"
#include "src/io/units.h"
#include "src/part.h"
#include "src/space.h"
#ifdef HAVE_CUDA
#include "src/gpu/gpu.h"
#include "src/gpu/gpu_engine.h"
#include "tasks/gravity/gpu_gravity.h"
#endif

#define MAX_CONFIGS 64

/** One reference entry: a particle's id and its direct-summation acceleration. */
struct ref_entry {
  int64_t id;
  double a[3];
};

/** Work of one thread of the sampled direct summation. */
struct direct_job {
  const struct parts *p;
  const size_t *targets; /**< particle indices */
  struct ref_entry *out;
  size_t k0, k1;
  double eps;
};

static void *direct_run(void *arg) {
  const struct direct_job *job = arg;
  const struct parts *p = job->p;
  for (size_t k = job->k0; k < job->k1; k++) {
    const size_t i = job->targets[k];
    double pot = 0.0, a[3] = {0.0, 0.0, 0.0};
    for (size_t j = 0; j < p->count; j++) {
      if (j == i) continue;
      const double dx[3] = {p->x[i] - p->x[j], p->y[i] - p->y[j], p->z[i] - p->z[j]};
      const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
      gravity_p2p(dx, r2, p->m[j], 1.0, job->eps, GRAVITY_SOFTENING_SPLINE, &pot, a);
    }
    job->out[k].id = p->id[i];
    for (int d = 0; d < 3; d++) job->out[k].a[d] = a[d];
  }
  return NULL;
}

/** Direct summation (G = 1, spline softening eps) at the nt particles
 *  targets[], over nthreads threads. */
static void direct_sampled(const struct parts *p, const size_t *targets, size_t nt, double eps,
                           int nthreads, struct ref_entry *out) {
  pthread_t tid[64];
  struct direct_job job[64];
  if (nthreads < 1) nthreads = 1;
  if (nthreads > 64) nthreads = 64;
  for (int t = 0; t < nthreads; t++) {
    job[t] = (struct direct_job){p, targets, out, nt * t / nthreads, nt * (t + 1) / nthreads, eps};
    if (pthread_create(&tid[t], NULL, direct_run, &job[t]) != 0)
      error_exit("bench_gravity_accuracy: cannot start thread %d", t);
  }
  for (int t = 0; t < nthreads; t++) pthread_join(tid[t], NULL);
}

/** Fill p with n particles of a built-in set (box [0, 4]^3, centre 2). */
static void make_builtin(struct parts *p, const char *name, size_t n) {
  parts_alloc(p, n);
  p->count = n;
  srand48(20261203);
  const double c[3] = {2.0, 2.0, 2.0};
  for (size_t i = 0; i < n; i++) {
    double r[3];
    if (strcmp(name, "plummer2") == 0) {
      gset_two_bodies(i, n, c, r);
    } else if (strcmp(name, "plummer") == 0) {
      gset_place(gset_plummer_radius(0.2, 1.8), c, r);
    } else if (strcmp(name, "uniform") == 0) {
      gset_place(cbrt(drand48()), c, r);
    } else {
      error_exit("bench_gravity_accuracy: unknown set '%s' (plummer2, plummer, uniform)", name);
    }
    p->x[i] = r[0], p->y[i] = r[1], p->z[i] = r[2];
    p->m[i] = 1.0 / (double)n;
    p->h[i] = 0.01;
    p->id[i] = (int64_t)i;
  }
}

/** CPU time of the calling thread in seconds. */
static double thread_cpu(void) {
  struct timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

/** Percentile q (0..1) of the sorted e[0..n). */
static double pct(const double *e, size_t n, double q) {
  if (n == 0) return 0.0;
  size_t k = (size_t)(q * (double)(n - 1) + 0.5);
  return e[k < n ? k : n - 1];
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  double eps = -1.0, cfg[MAX_CONFIGS][3];
  int ncfg = 0, nevals = 2, stride = 1, nthreads = 2, leaf = 32, max_top = 16, gpu = 0;
  const char *cache = NULL, *source = NULL;
  for (int a = 1; a < argc; a++) {
    const int more = a + 1 < argc;
    if (strcmp(argv[a], "-s") == 0 && more) {
      eps = strcmp(argv[++a], "auto") == 0 ? 0.0 : atof(argv[a]);
      if (!(eps >= 0.0)) error_exit("bench_gravity_accuracy: -s wants a softening > 0 or auto");
    } else if (strcmp(argv[a], "-c") == 0 && more) {
      if (ncfg == MAX_CONFIGS) error_exit("bench_gravity_accuracy: at most %d -c", MAX_CONFIGS);
      double *c = cfg[ncfg++];
      if (sscanf(argv[++a], "%lf,%lf,%lf", c, c + 1, c + 2) != 3)
        error_exit("bench_gravity_accuracy: -c wants EPS_FMM,THETA,ORDER, got '%s'", argv[a]);
    } else if (strcmp(argv[a], "-e") == 0 && more) {
      nevals = atoi(argv[++a]);
    } else if (strcmp(argv[a], "-k") == 0 && more) {
      stride = atoi(argv[++a]);
    } else if (strcmp(argv[a], "-r") == 0 && more) {
      cache = argv[++a];
    } else if (strcmp(argv[a], "-t") == 0 && more) {
      nthreads = atoi(argv[++a]);
    } else if (strcmp(argv[a], "-l") == 0 && more) {
      leaf = atoi(argv[++a]);
    } else if (strcmp(argv[a], "-m") == 0 && more) {
      max_top = atoi(argv[++a]);
    } else if (strcmp(argv[a], "-g") == 0) {
      gpu = 1;
    } else if (argv[a][0] != '-' && source == NULL) {
      source = argv[a];
    } else {
      error_exit(
          "usage: bench_gravity_accuracy [-s EPS] [-c E,T,P]... [-e K] [-k K] [-r FILE] "
          "[-t T] [-l L] [-m M] [-g] IC.hdf5|plummer2:N|plummer:N|uniform:N");
    }
  }
  if (source == NULL) error_exit("bench_gravity_accuracy: no source (IC file or set:N)");
  if (stride < 1 || nevals < 1) error_exit("bench_gravity_accuracy: -k and -e want >= 1");
  if (ncfg == 0) {
    cfg[0][0] = GRAVITY_EPSILON_FMM_DEFAULT, cfg[0][1] = 0.5, cfg[0][2] = GRAVITY_ORDER_DEFAULT;
    ncfg = 1;
  }
#ifndef HAVE_CUDA
  if (gpu) error_exit("bench_gravity_accuracy: -g needs a CUDA build");
#endif

  /* the particles and the space (box from the file, else [0, 4]^3) */
  struct parts p;
  double box[3] = {4.0, 4.0, 4.0};
  const char *colon = strchr(source, ':');
  if (colon && strstr(source, ".hdf5") == NULL) {
    char name[64];
    snprintf(name, sizeof name, "%.*s", (int)(colon - source), source);
    const size_t n = (size_t)atol(colon + 1);
    if (n < 2) error_exit("bench_gravity_accuracy: '%s': N >= 2 wanted", source);
    make_builtin(&p, name, n);
    if (eps < 0.0) eps = 0.1 * cbrt(1.0 / (double)n);
  } else {
    struct unit_system us;
    units_init_si(&us);
    struct ic_info info;
    struct unit_system file_us;
    /* read once to learn the file's units, then in them (G = 1) */
    ic_read(source, &us, NULL, 0, &p, &info);
    file_us = info.file_units;
    parts_free(&p);
    ic_read(source, &file_us, NULL, 0, &p, &info);
    if (info.has_box_size)
      for (int d = 0; d < 3; d++) box[d] = info.box_size[d];
    if (eps == 0.0) {
      double *sp = error_malloc(p.count * sizeof(double), "spacings");
      for (size_t i = 0; i < p.count; i++) sp[i] = p.rho[i] > 0.0 ? cbrt(p.m[i] / p.rho[i]) : 0.0;
      qsort(sp, p.count, sizeof(double), cmp_double);
      eps = pct(sp, p.count, 0.5);
      free(sp);
      if (!(eps > 0.0)) error_exit("bench_gravity_accuracy: -s auto: %s has no densities", source);
    }
    if (eps < 0.0) error_exit("bench_gravity_accuracy: -s EPS (softening) wanted with a file");
  }
  const size_t n = p.count;
  struct space s;
  space_init(&s, &p, box, 0, leaf, max_top);
  if (space_rebuild(&s) != 0) error_exit("bench_gravity_accuracy: particles outside the box");

  /* the reference: every stride-th particle by id */
  size_t nt = 0;
  size_t *targets = error_malloc(n * sizeof(size_t), "targets");
  for (size_t i = 0; i < n; i++)
    if (p.id[i] % stride == 0) targets[nt++] = i;
  struct ref_entry *ref = error_malloc((nt ? nt : 1) * sizeof *ref, "reference");
  int have = 0;
  if (cache) {
    FILE *f = fopen(cache, "rb");
    if (f) {
      size_t hdr[2] = {0, 0};
      double feps = 0.0;
      if (fread(hdr, sizeof hdr, 1, f) == 1 && fread(&feps, sizeof feps, 1, f) == 1 &&
          hdr[0] == n && hdr[1] == nt && feps == eps && fread(ref, sizeof *ref, nt, f) == nt) {
        have = 1;
        for (size_t k = 0; k < nt; k++)
          if (ref[k].id != p.id[targets[k]]) have = 0;
      }
      fclose(f);
    }
  }
  double t0 = error_walltime();
  if (!have) {
    direct_sampled(&p, targets, nt, eps, nthreads, ref);
    if (cache) {
      FILE *f = fopen(cache, "wb");
      const size_t hdr[2] = {n, nt};
      if (!f || fwrite(hdr, sizeof hdr, 1, f) != 1 || fwrite(&eps, sizeof eps, 1, f) != 1 ||
          fwrite(ref, sizeof *ref, nt, f) != nt)
        error_exit("bench_gravity_accuracy: cannot write %s", cache);
      fclose(f);
    }
  }
  printf(
      "# %s: N = %zu, softening %g (spline), %d top-level cells, %d cells, leaves <= %d; "
      "reference: %zu particles (1 in %d), %s %.1f s\n",
      source, n, eps, s.nr_top, s.nr_cells, leaf, nt, stride,
      have ? "read from the cache in" : "direct summation", error_walltime() - t0);
  printf("# mode eps_fmm theta order eval median p90 p99 max seconds m2l/N p2p/N\n");
  fflush(stdout);

  int cap = 0;
  struct gravity_cell *gc = gravity_cells_reserve(NULL, &cap, s.cells_capacity);
  memset(gc, 0, (size_t)cap * sizeof *gc);
  double *err = error_malloc((nt ? nt : 1) * sizeof(double), "errors");
#ifdef HAVE_CUDA
  struct gpu *g = NULL;
  struct gpu_grav *gg = NULL;
  struct gpu_grav_host h;
  struct gravity_gpu_rec rec;
  memset(&h, 0, sizeof h);
  memset(&rec, 0, sizeof rec);
  h.built_rebuild = -1;
  if (gpu) {
    char why[256];
    g = gpu_init(0, why, sizeof why);
    if (!g) error_exit("bench_gravity_accuracy: no GPU (%s)", why);
    gg = gpu_grav_new(g);
  }
#endif
  for (int c = 0; c < ncfg; c++) {
    struct gravity_props gp;
    gravity_props_set(&gp, 1.0, cfg[c][1], eps, GRAVITY_SOFTENING_SPLINE, (int)cfg[c][2]);
    gp.epsilon_fmm = cfg[c][0];
#ifdef HAVE_CUDA
    if (gpu) gpu_grav_tree_all(gg, &h, &rec, &p, &s, gc, &gp, 0, 1, 1); /* warm-up */
#endif
    /* a run's first step: no previous acceleration */
    memset(p.gax, 0, n * sizeof(double));
    memset(p.gay, 0, n * sizeof(double));
    memset(p.gaz, 0, n * sizeof(double));
    if (gpu) {
      /* the host's estimate on the -t threads as in the engine, outside the
       * GPU's timed evaluation (gpu_grav_tree_all would run it serially) */
      const double te = error_walltime();
      if (gravity_estimate(&p, s.cells, s.nr_top, gc, &gp, nthreads))
        printf("# first evaluation's gravity_estimate on the host: %.3f s wall, %d threads\n",
               error_walltime() - te, nthreads);
    }
    for (int ev = 1; ev <= nevals; ev++) {
      struct gravity_counters cnt;
      gravity_counters_get(&cnt, 1);
      t0 = gpu ? error_walltime() : thread_cpu();
#ifdef HAVE_CUDA
      if (gpu)
        gpu_grav_tree_all(gg, &h, &rec, &p, &s, gc, &gp, 0, 1, 1);
      else
#endif
        gravity_tree_all(&p, s.cells, s.nr_top, gc, &gp);
      const double dt = (gpu ? error_walltime() : thread_cpu()) - t0;
      gravity_counters_get(&cnt, 0);
      for (size_t k = 0; k < nt; k++) {
        const size_t i = targets[k];
        const double *r = ref[k].a;
        const double d[3] = {p.gax[i] - r[0], p.gay[i] - r[1], p.gaz[i] - r[2]};
        err[k] = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) /
                 sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
      }
      qsort(err, nt, sizeof(double), cmp_double);
      printf("%s %g %g %d %d %.3e %.3e %.3e %.3e %.4f %.2f %.1f\n", gpu ? "gpu" : "cpu",
             gp.epsilon_fmm, gp.theta, gp.order, ev, pct(err, nt, 0.5), pct(err, nt, 0.9),
             pct(err, nt, 0.99), nt ? err[nt - 1] : 0.0, dt, (double)cnt.m2l / (double)n,
             (double)cnt.p2p / (double)n);
      fflush(stdout);
    }
  }
#ifdef HAVE_CUDA
  if (gpu) {
    gravity_gpu_rec_free(&rec);
    gpu_grav_host_free(&h);
    gpu_grav_free(gg);
    gpu_free(g);
  }
#endif
  free(err);
  free(gc);
  free(ref);
  free(targets);
  space_free(&s);
  parts_free(&p);
  return 0;
}
