/* Damage model (tasks/damage/damage_iact.h):
 *  - the 3x3 symmetric eigen-solver (src/sym3.h, which the artificial stress
 *    of tasks/gradient/gradient_finish.h shares) on diagonal, rotated, repeated and
 *    nearly repeated cases and on random matrices: eigenvalues against the
 *    construction, A = Q L Q^T and Q^T Q = I to 1e-12 relative;
 *  - Young's modulus, damaged pressure and stress;
 *  - a bar pulled at constant strain rate: with steps placed at the flaw
 *    activation times the update reproduces the exact piecewise integral of
 *    d(d^(1/3))/dt = n(t) c_g / R_s with the limiter to 1e-9; with uniform
 *    steps it converges to it at first order; without the limiter active it
 *    matches the continuum Grady-Kipp integral
 *    d^(1/3) = (c_g/R_s) k V eps'^m t^(m+1)/(m+1) (theory/damage.md D7);
 *  - on random stress histories damage never decreases, never exceeds its
 *    limiter, and does not grow in compression;
 *  - the time-step criterion: the step it returns grows d by f (1 - d).
 * Exit 0 pass, 1 fail. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "tasks/damage/damage_iact.h"
#include "tasks/damage/flaws.h"
#include "src/sym3.h"

static int failures = 0;

/** Report one check: measured error against its bound. */
static void check(const char *what, double err, double tol) {
  const int ok = err <= tol && err == err;
  printf("%-58s %10.3e  (tol %.0e)  %s\n", what, err, tol, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

/** Uniform random number in [0, 1) from the flaws generator. */
static double uniform(struct flaws_rng *r) {
  return (double)(flaws_rng_next(r) >> 11) * 0x1.0p-53;
}

/** Random rotation matrix (unit quaternion with random components). */
static void random_rotation(struct flaws_rng *r, double R[3][3]) {
  double q[4], n = 0;
  for (int i = 0; i < 4; i++) {
    q[i] = 2 * uniform(r) - 1;
    n += q[i] * q[i];
  }
  n = sqrt(n);
  const double a = q[0] / n, b = q[1] / n, c = q[2] / n, d = q[3] / n;
  R[0][0] = a * a + b * b - c * c - d * d, R[0][1] = 2 * (b * c - a * d),
  R[0][2] = 2 * (b * d + a * c);
  R[1][0] = 2 * (b * c + a * d), R[1][1] = a * a - b * b + c * c - d * d,
  R[1][2] = 2 * (c * d - a * b);
  R[2][0] = 2 * (b * d - a * c), R[2][1] = 2 * (c * d + a * b),
  R[2][2] = a * a - b * b - c * c + d * d;
}

/** a (6 components) = R diag(l) R^T. */
static void compose(double R[3][3], const double l[3], double a[6]) {
  double m[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      m[i][j] = 0;
      for (int k = 0; k < 3; k++) m[i][j] += R[i][k] * l[k] * R[j][k];
    }
  a[SYM3_XX] = m[0][0], a[SYM3_YY] = m[1][1], a[SYM3_ZZ] = m[2][2];
  a[SYM3_XY] = m[0][1], a[SYM3_XZ] = m[0][2], a[SYM3_YZ] = m[1][2];
}

/** Errors of an eigen-decomposition of a: reconstruction and orthogonality
 *  (relative to the largest |entry|). */
static void decomposition_errors(const double a[6], double *rec, double *orth, double lam[3]) {
  double qf[9], q[3][3];
  sym3_eigen(a, lam, qf);
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) q[r][c] = qf[3 * r + c];
  double b[6];
  compose(q, lam, b);
  double scale = 0;
  for (int k = 0; k < 6; k++) scale = fmax(scale, fabs(a[k]));
  if (scale == 0) scale = 1;
  *rec = 0;
  for (int k = 0; k < 6; k++) *rec = fmax(*rec, fabs(a[k] - b[k]) / scale);
  *orth = 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0;
      for (int k = 0; k < 3; k++) s += q[k][i] * q[k][j];
      *orth = fmax(*orth, fabs(s - (i == j)));
    }
}

/** Eigen-solver checks. */
static void test_eigen(void) {
  struct flaws_rng rng;
  flaws_rng_seed(&rng, 42);
  double lam[3], rec, orth;
  /* diagonal: exact */
  const double diag[6] = {-1.5, 0, 0, 7.25, 0, 3.0};
  sym3_eigen(diag, lam, NULL);
  check("diagonal: eigenvalues exact", fabs(lam[0] - 7.25) + fabs(lam[1] - 3) + fabs(lam[2] + 1.5),
        0);

  /* a known tridiagonal matrix: 2 + sqrt 2, 2, 2 - sqrt 2 */
  const double tri[6] = {2, -1, 0, 2, -1, 2};
  sym3_eigen(tri, lam, NULL);
  check("tridiagonal (2,-1): eigenvalues 2 + sqrt2, 2, 2 - sqrt2",
        fabs(lam[0] - (2 + sqrt(2.0))) + fabs(lam[1] - 2) + fabs(lam[2] - (2 - sqrt(2.0))), 1e-14);
  /* NaN input: the sweeps stop at once */
  const double bad[6] = {NAN, 1, 0, 1, 0, 1};
  check("NaN entry: no sweep", sym3_eigen(bad, lam, NULL), 0);

  /* rotated distinct, repeated (double, triple), nearly repeated, with
   * stress-like magnitudes */
  const double cases[][3] = {{3, -1, 2},         {2, 2, 5},      {-4, 1, 1},          {3, 3, 3},
                             {1, 1 + 1e-10, -2}, {0, 0, 1e-300}, {2.5e9, -1e9, 2.5e9}};
  const char *names[] = {"distinct",       "repeated (2,2,5)", "repeated (-4,1,1)",
                         "triple (3,3,3)", "nearly repeated",  "tiny (0,0,1e-300)",
                         "stresses (Pa)"};
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    double worst_l = 0, worst_r = 0, worst_o = 0;
    double sorted[3] = {cases[c][0], cases[c][1], cases[c][2]};
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 2; j++)
        if (sorted[j] < sorted[j + 1]) {
          const double t = sorted[j];
          sorted[j] = sorted[j + 1];
          sorted[j + 1] = t;
        }
    const double scale = fmax(fabs(sorted[0]), fabs(sorted[2]));
    for (int trial = 0; trial < 200; trial++) {
      double R[3][3], a[6];
      random_rotation(&rng, R);
      compose(R, cases[c], a);
      decomposition_errors(a, &rec, &orth, lam);
      for (int i = 0; i < 3; i++) worst_l = fmax(worst_l, fabs(lam[i] - sorted[i]) / scale);
      worst_r = fmax(worst_r, rec);
      worst_o = fmax(worst_o, orth);
    }
    char what[128];
    snprintf(what, sizeof what, "rotated %s: eigenvalues", names[c]);
    check(what, worst_l, 1e-13);
    snprintf(what, sizeof what, "rotated %s: A = Q L Q^T", names[c]);
    check(what, worst_r, 1e-13);
    snprintf(what, sizeof what, "rotated %s: Q^T Q = I", names[c]);
    check(what, worst_o, 1e-13);
  }

  /* random symmetric matrices */
  double worst_r = 0, worst_o = 0, worst_inv = 0, unsorted = 0;
  int max_sweeps = 0;
  for (int trial = 0; trial < 100000; trial++) {
    double a[6];
    for (int k = 0; k < 6; k++) a[k] = 2 * uniform(&rng) - 1;
    if (trial % 3 == 0) a[SYM3_XY] = a[SYM3_XZ] = 0; /* block-diagonal cases */
    decomposition_errors(a, &rec, &orth, lam);
    worst_r = fmax(worst_r, rec);
    worst_o = fmax(worst_o, orth);
    if (lam[0] < lam[1] || lam[1] < lam[2]) unsorted++;
    const double xx = a[SYM3_XX], yy = a[SYM3_YY], zz = a[SYM3_ZZ];
    const double xy = a[SYM3_XY], xz = a[SYM3_XZ], yz = a[SYM3_YZ];
    const double tr = xx + yy + zz;
    const double det =
        xx * (yy * zz - yz * yz) - xy * (xy * zz - yz * xz) + xz * (xy * yz - yy * xz);
    worst_inv =
        fmax(worst_inv, fabs(lam[0] + lam[1] + lam[2] - tr) + fabs(lam[0] * lam[1] * lam[2] - det));
    double l2[3];
    const int sweeps = sym3_eigen(a, l2, NULL);
    if (sweeps > max_sweeps) max_sweeps = sweeps;
  }
  check("random symmetric (1e5): A = Q L Q^T", worst_r, 1e-12);
  check("random symmetric (1e5): Q^T Q = I", worst_o, 1e-12);
  check("random symmetric (1e5): trace and determinant", worst_inv, 1e-12);
  check("random symmetric (1e5): eigenvalues descending (count)", unsorted, 0);
  check("random symmetric (1e5): Jacobi sweeps <= 8", max_sweeps > 8 ? max_sweeps : 0, 0);
  const double zero[6] = {0, 0, 0, 0, 0, 0};
  sym3_eigen(zero, lam, NULL);
  check("zero matrix: eigenvalues 0", fabs(lam[0]) + fabs(lam[1]) + fabs(lam[2]), 0);
}

/** Moduli and damaged stress. */
static void test_moduli(void) {
  const double K = 26.7e9, mu = 22.7e9;
  const double E = damage_young_modulus(K, mu);
  const double nu = (3 * K - 2 * mu) / (2 * (3 * K + mu));
  check("E = 2 mu (1 + nu)", fabs(E - 2 * mu * (1 + nu)) / E, 1e-15);
  check("E(K = mu) = 9/4 mu", fabs(damage_young_modulus(1.0, 1.0) - 2.25), 1e-15);
  check("c_g = 0.4 sqrt((K + 4/3 mu)/rho)",
        fabs(damage_crack_speed(K, mu, 2700) / (0.4 * sqrt((K + 4 * mu / 3) / 2700)) - 1), 1e-15);
  const double S[6] = {1, 0.5, -0.25, -2, 0.125, 1}; /* xx xy xz yy yz zz */
  double s[6];
  damage_stress(0.25, -8.0, S, s); /* tension: P reduced */
  check("damaged stress, P < 0: -(1-d)P + (1-d)S",
        fabs(s[SYM3_XX] - 0.75 * (8 + 1)) + fabs(s[SYM3_YY] - 0.75 * (8 - 2)) +
            fabs(s[SYM3_XY] - 0.75 * 0.5) + fabs(s[SYM3_YZ] - 0.75 * 0.125),
        1e-15);
  damage_stress(0.25, 8.0, S, s); /* compression: P kept */
  check("damaged stress, P > 0: -P + (1-d)S",
        fabs(s[SYM3_XX] - (-8 + 0.75)) + fabs(s[SYM3_ZZ] - (-8 + 0.75)), 1e-15);
}

/** Parameters of the bar. */
struct bar {
  double E, c_g, R_s, rate; /* Young's modulus, crack speed, radius, strain rate */
  const double *eps;        /* thresholds, ascending */
  int32_t n;                /* their number */
};

/** Undamaged stress of the bar at time t (uniaxial stress E eps' t along
 *  the direction R e_x): pressure and deviator. */
static void bar_stress(const struct bar *b, double R[3][3], double t, double *P, double S[6]) {
  const double s = b->E * b->rate * t;
  const double l[3] = {2 * s / 3, -s / 3, -s / 3};
  compose(R, l, S);
  *P = -s / 3;
}

/** Exact d^(1/3)(T) of the bar: piecewise linear between activation times
 *  t_j = eps_j / eps', capped by (j / n)^(1/3) (D4, D6). */
static double bar_exact(const struct bar *b, double T) {
  double x = 0, t = 0;
  for (int32_t j = 0; j <= b->n; j++) {
    const double tn = j < b->n ? fmin(b->eps[j] / b->rate, T) : T;
    if (j > 0) {
      x += j * b->c_g / b->R_s * (tn - t);
      const double cap = damage_cbrt_max(j, b->n);
      if (x > cap) x = cap;
    }
    t = tn;
    if (t >= T) break;
  }
  return x;
}

/** Integrate the bar with the model's update from 0 to T in steps: the
 *  activation times (when at_flaws) or nsteps uniform steps. */
static double bar_run(const struct bar *b, double R[3][3], double T, int at_flaws, int nsteps) {
  double x = 0, t = 0;
  int32_t n_act = 0, j = 0;
  for (int k = 0; t < T; k++) {
    double tn;
    if (at_flaws) {
      /* next step starts just after the next activation time */
      while (j < b->n && b->eps[j] / b->rate * (1 + 1e-13) <= t) j++;
      tn = j < b->n ? fmin(b->eps[j] / b->rate * (1 + 1e-13), T) : T;
    } else {
      tn = k + 1 == nsteps ? T : T * (k + 1) / nsteps;
    }
    double P, S[6];
    bar_stress(b, R, t, &P, S);
    damage_grady_kipp_update(P, S, b->E, b->c_g, b->R_s, b->eps, b->n, tn - t, &x, &n_act);
    t = tn;
  }
  return x;
}

/** Bar pulled at constant strain rate. */
static void test_bar(void) {
  struct flaws_rng rng;
  flaws_rng_seed(&rng, 7);
  double R[3][3];
  random_rotation(&rng, R);
  /* basalt (theory/validation.md): K = A = 26.7 GPa, mu = 22.7 GPa, rho 2700;
   * Nakamura's Weibull k = 5e34 m^-3, m = 8, a 1 mm^3 particle with the
   * 60 weakest flaws of its own volume */
  const double K = 26.7e9, mu = 22.7e9, rho = 2700, k = 5e34, m = 8, V = 1e-9;
  enum { NF = 60 };
  double eps[NF];
  for (int j = 0; j < NF; j++) eps[j] = flaws_threshold(j + 1, k, m, V);
  struct bar b = {damage_young_modulus(K, mu),
                  damage_crack_speed(K, mu, rho),
                  damage_radius_volume(rho * V, rho),
                  1e4,
                  eps,
                  NF};
  /* to the time when 40 flaws are active: d^(1/3) rises, is capped,
   * rises again; the limiter is reached */
  const double T = 0.5 * (eps[39] + eps[40]) / b.rate;
  const double exact = bar_exact(&b, T);
  const double run = bar_run(&b, R, T, 1, 0);
  printf("bar: d^(1/3)(T) exact %.12f, steps at activations %.12f\n", exact, run);
  check("bar, steps at activation times: d^(1/3) = exact integral", fabs(run - exact), 1e-9);
  check("bar: the limiter is reached (d^(1/3) = (40/60)^(1/3))", fabs(exact - cbrt(40.0 / 60)),
        1e-12);
  /* uniform steps: first-order convergence to the exact value, at a time
   * before the limiter binds (there the error would vanish) */
  const double T2 = 0.5 * (eps[3] + eps[4]) / b.rate;
  const double ex2 = bar_exact(&b, T2);
  /* explicit steps activate a flaw at the first step start after its time,
   * never before and at most dt late: 0 <= exact - run <= n(T) c_g/R_s dt */
  const int32_t n2 = damage_count_below(eps, NF, b.rate * T2);
  double err[3];
  int outside = 0;
  for (int r = 0; r < 3; r++) {
    const int nsteps = 400 << (2 * r);
    err[r] = ex2 - bar_run(&b, R, T2, 0, nsteps);
    if (!(err[r] >= 0 && err[r] <= n2 * b.c_g / b.R_s * T2 / nsteps)) outside++;
  }
  printf("bar, uniform steps 400/1600/6400: errors %.3e %.3e %.3e (exact %.6f, %d flaws)\n", err[0],
         err[1], err[2], ex2, (int)n2);
  check("bar, uniform steps: 0 <= exact - run <= n c_g dt / R_s (violations)", outside, 0);
  check("bar, uniform steps: error shrinks with dt (violations)",
        (err[1] < err[0]) + (err[2] < err[1]) == 2 ? 0 : 1, 0);
  check("bar, 6400 uniform steps: relative error", err[2] / ex2, 1e-3);

  /* continuum Grady-Kipp integral (D7): a large crack radius keeps d far
   * below its limiter; n* = k V (eps' T)^m = 1000 of 2000 flaws active */
  enum { NB = 2000 };
  static double big[NB];
  const double V3 = 1e-6;
  for (int j = 0; j < NB; j++) big[j] = flaws_threshold(j + 1, k, m, V3);
  struct bar c = {b.E, b.c_g, 10.0, 1e3, big, NB};
  const double nstar = 1000.0;
  const double T3 = pow(nstar / (k * V3), 1 / m) / c.rate;
  const double gk = c.c_g / c.R_s * k * V3 * pow(c.rate, m) * pow(T3, m + 1) / (m + 1);
  const double run3 = bar_run(&c, R, T3, 1, 0);
  printf("Grady-Kipp: d^(1/3) continuum %.9e, model %.9e, limiter %.3f\n", gk, run3,
         damage_cbrt_max(1000, NB));
  /* the discrete sum of (t - t_j) falls short of the integral by
   * (1/2 + zeta(-1/m) n*^(-1/m)) t (Euler-Maclaurin with the j^(1/m)
   * singularity), a relative shortfall in (0, (m+1)/(2 n*)) (D7) */
  const double shortfall = 1 - run3 / gk;
  check("bar vs continuum Grady-Kipp: shortfall outside (0, (m+1)/(2n*))",
        shortfall > 0 && shortfall < (m + 1) / (2 * nstar) ? 0 : fabs(shortfall), 0);
}

/** Random stress histories: damage monotone, below its limiter, no growth
 *  in compression; saturation under sustained tension. */
static void test_monotone(void) {
  struct flaws_rng rng;
  flaws_rng_seed(&rng, 2024);
  const double E = damage_young_modulus(26.7e9, 22.7e9), c_g = 2000, R_s = 1e-3;
  long decreases = 0, above = 0, grew_in_compression = 0, n_act_down = 0;
  for (int part = 0; part < 2000; part++) {
    const int32_t n = 1 + (int32_t)flaws_rng_below(&rng, 20);
    double eps[20];
    for (int j = 0; j < n; j++) eps[j] = 1e-4 * (1 + 3 * uniform(&rng));
    for (int j = 1; j < n; j++) /* sort */
      for (int i = j; i > 0 && eps[i] < eps[i - 1]; i--) {
        const double t = eps[i];
        eps[i] = eps[i - 1];
        eps[i - 1] = t;
      }
    double x = 0;
    int32_t n_act = 0;
    for (int step = 0; step < 200; step++) {
      double P = (2 * uniform(&rng) - 1) * 2e7, S[6];
      for (int c = 0; c < 6; c++) S[c] = (2 * uniform(&rng) - 1) * 1e7;
      const int compress = step % 5 == 0;
      if (compress) { /* all principal stresses negative */
        P = 5e7;
        for (int c = 0; c < 6; c++) S[c] *= 0.1;
      }
      const double dt = 1e-8 * uniform(&rng);
      const double x0 = x;
      const int32_t a0 = n_act;
      damage_grady_kipp_update(P, S, E, c_g, R_s, eps, n, dt, &x, &n_act);
      if (x < x0) decreases++;
      if (n_act < a0) n_act_down++;
      if (x > damage_cbrt_max(n_act, n) || x > 1.0) above++;
      if (compress && x != x0) grew_in_compression++;
    }
  }
  check("random histories: damage decreases (count)", decreases, 0);
  check("random histories: n_act decreases (count)", n_act_down, 0);
  check("random histories: d^(1/3) above (n_act/n_tot)^(1/3) (count)", above, 0);
  check("random histories: growth in compression (count)", grew_in_compression, 0);

  /* sustained tension beyond every threshold: d reaches exactly 1 */
  const double eps[3] = {1e-4, 2e-4, 3e-4}, S[6] = {0, 0, 0, 0, 0, 0};
  double x = 0;
  int32_t n_act = 0;
  for (int step = 0; step < 100; step++)
    damage_grady_kipp_update(-1e9, S, E, c_g, R_s, eps, 3, 1e-7, &x, &n_act);
  check("sustained tension: d = 1, all flaws active", fabs(x - 1) + (3 - n_act), 0);
  /* no flaws: no damage */
  x = 0, n_act = 0;
  damage_grady_kipp_update(-1e9, S, E, c_g, R_s, eps, 0, 1e-3, &x, &n_act);
  check("no flaws: no damage", x + n_act, 0);
}

/** Time-step criterion. */
static void test_timestep(void) {
  const double f = 0.1, rate = 3e6;
  check("timestep: saturated particle not limited",
        isinf(damage_timestep(cbrt(0.5), 2, 4, rate, f)) ? 0 : 1, 0);
  check("timestep: no growth, no limit", isinf(damage_timestep(0.3, 2, 4, 0.0, f)) ? 0 : 1, 0);
  check("timestep: limiter within reach, no limit",
        isinf(damage_timestep(cbrt(0.49), 2, 4, rate, f)) ? 0 : 1, 0);
  const double x = cbrt(0.2);
  const double dt = damage_timestep(x, 9, 10, rate, f);
  const double x1 = x + rate * dt, d1 = x1 * x1 * x1;
  check("timestep: d grows by f in the step", fabs((d1 - 0.2) - f), 1e-14);
  /* near the limiter 1 the step does not shrink with 1 - d: the particle
   * saturates in one more step (no pinning) */
  check("timestep: no limit within f of full damage",
        isinf(damage_timestep(cbrt(0.95), 10, 10, rate, f)) ? 0 : 1, 0);
}

/** The per-particle wrapper against the direct call. */
static void test_wrapper(void) {
  struct material mat;
  char msg[256];
  material_init(&mat, 3, "basalt", EOS_MURNAGHAN);
  material_set(&mat, "rho0", 2700, msg, sizeof msg);
  material_set(&mat, "K0", 26.7e9, msg, sizeof msg);
  material_set(&mat, "n", 5.5, msg, sizeof msg);
  material_set(&mat, "shear_modulus", 22.7e9, msg, sizeof msg);
  material_set(&mat, "bulk_modulus", 26.7e9, msg, sizeof msg);
  material_set(&mat, "weibull_k", 5e34, msg, sizeof msg);
  material_set(&mat, "weibull_m", 8, msg, sizeof msg);
  const int ok = material_finalize(&mat, msg, sizeof msg) == 0;
  if (!ok) printf("material: %s\n", msg);
  const double eps[6] = {9e9, 1e-5, 2e-5, 4e-5, 8e-5, 9e9}; /* slice [1, 5) */
  const double S[6] = {1e6, 2e5, 0, -5e5, 1e5, -5e5};       /* xx xy xz yy yz zz */
  double x1 = 0.1, x2 = 0.1, d = 0;
  int32_t a1 = 1, a2 = 1;
  const double r1 =
      damage_update_particle(&mat, 2650, 2e-3, -3e6, S, eps, 1, 4, 1e-8, &x1, &a1, &d);
  const double r2 = damage_grady_kipp_update(-3e6, S, damage_young_modulus(26.7e9, 22.7e9),
                                             damage_crack_speed(26.7e9, 22.7e9, 2650), 2e-3,
                                             eps + 1, 4, 1e-8, &x2, &a2);
  check("wrapper = direct update (and d = dcbrt^3)",
        ok && r1 > 0 ? fabs(x1 - x2) + fabs(r1 - r2) / r2 + (a1 != a2) + fabs(d - x1 * x1 * x1) : 1,
        0);
  mat.weibull_k = 0;
  x1 = 0.1;
  damage_update_particle(&mat, 2650, 2e-3, -3e6, S, eps, 1, 4, 1e-8, &x1, &a1, &d);
  check("wrapper: no Weibull parameters, no damage", fabs(x1 - 0.1), 0);
}

int main(void) {
  test_eigen();
  test_wrapper();
  test_moduli();
  test_bar();
  test_monotone();
  test_timestep();
  if (failures) printf("%d check(s) FAILED\n", failures);
  return failures ? 1 : 0;
}
