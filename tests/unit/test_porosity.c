/* Porosity models (src/materials/porosity*.h, theory/porosity.md):
 *  - P-alpha crush curve: continuity at p_e, p_t, p_s, monotone, its slope
 *    against centred differences;
 *  - the rate PA6 is tangent to the crush curve: for a state on the curve,
 *    d(alpha)/dt = alpha_cc'(P) dP/dt with dP/dt measured by a finite
 *    difference of P = P_s(alpha rho, u)/alpha along (rho', u', alpha'),
 *    for a Murnaghan and a Tillotson matrix (u-dependent); same for the
 *    elastic branch PA7;
 *  - a porous particle compressed at a constant rate (Murnaghan matrix,
 *    adiabatic du = P/rho^2 drho; Tillotson matrix): alpha(P) follows the
 *    crush curve at every step, the error falls at first order with the step
 *    (forward Euler), alpha never increases, 1 <= alpha <= alpha_0; with the
 *    projection PA10, alpha = 1 exactly at full compaction and P equals the
 *    solid EOS;
 *  - epsilon-alpha: alpha and slope continuous at eps_e, eps_x, eps_c; the
 *    slope against centred differences; integrating EA5 under compression
 *    follows the analytic expressions of each regime (written again here),
 *    converging at first order; unloading and reloading leave alpha
 *    unchanged until the strain passes its minimum;
 *  - porosity_check_ic; parameter parsing and the one-line errors.
 * Exit 0 pass, 1 fail. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "src/materials/eos_murnaghan.h"
#include "src/materials/eos_tillotson.h"
#include "src/error.h"
#include "src/materials/material.h"
#include "src/io/params.h"
#include "src/materials/porosity.h"
#include "src/io/units.h"

static int failures = 0;

/** Report one check: measured error against its bound. */
static void check(const char *what, double err, double tol) {
  const int ok = err <= tol && err == err;
  printf("%-66s %10.3e  (tol %.0e)  %s\n", what, err, tol, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

/** Report one yes/no check. */
static void check_true(const char *what, int ok) {
  printf("%-66s %s\n", what, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

/* ------------------------------------------------------------ matrices */

/** Matrix EOS used by the tests: Murnaghan or Tillotson, with the partial
 *  derivatives the caller of porosity_palpha_dalpha_dt must provide. */
struct matrix {
  int tillotson;             /**< 1: Tillotson, 0: Murnaghan */
  struct eos_murnaghan murn; /**< Murnaghan parameters */
  struct eos_tillotson till; /**< Tillotson parameters */
};

/** P_s(rho_s, u), dP_s/drho_s and dP_s/du (compressed Tillotson branch:
 *  these tests stay at rho_s >= rho0). */
static void matrix_eval(const struct matrix *m, double rho_s, double u, double *P, double *dr,
                        double *du) {
  if (m->tillotson) {
    eos_tillotson_compressed(&m->till, rho_s, u, P, dr, du);
  } else {
    double c2;
    eos_murnaghan_eval(&m->murn, rho_s, u, P, &c2);
    *dr = c2; /* barotropic: (dP/drho)_u = c^2 */
    *du = 0.0;
  }
}

/** Bulk pressure PA1. */
static double bulk_pressure(const struct matrix *m, double rho, double u, double alpha) {
  double P, dr, du;
  matrix_eval(m, alpha * rho, u, &P, &dr, &du);
  return porosity_pressure(alpha, P);
}

static struct matrix murnaghan(void) {
  struct matrix m;
  memset(&m, 0, sizeof m);
  m.murn.rho0 = 2700.0, m.murn.K0 = 2.0e10, m.murn.n = 4.0, m.murn.eta_limit = 0.0;
  return m;
}

/** Basalt (Benz & Asphaug 1999, Table II). */
static struct matrix tillotson(void) {
  struct matrix m;
  memset(&m, 0, sizeof m);
  m.tillotson = 1;
  struct eos_tillotson *t = &m.till;
  t->rho0 = 2700.0, t->A = 2.67e10, t->B = 2.67e10, t->E0 = 4.87e8, t->Eiv = 4.72e6;
  t->Ecv = 1.82e7, t->a = 0.5, t->b = 1.5, t->alpha = 5.0, t->beta = 5.0;
  return m;
}

/** P-alpha parameters of the tests (a steep two-branch curve). */
static struct porosity palpha_params(double c_s, double c_e) {
  struct porosity por;
  char msg[256];
  porosity_init(&por, POROSITY_PALPHA);
  porosity_set(&por, "test", "alpha_0", 1.8, msg, sizeof msg);
  porosity_set(&por, "test", "alpha_t", 1.3, msg, sizeof msg);
  porosity_set(&por, "test", "p_e", 1.0e6, msg, sizeof msg);
  porosity_set(&por, "test", "p_t", 5.0e7, msg, sizeof msg);
  porosity_set(&por, "test", "p_s", 2.0e8, msg, sizeof msg);
  porosity_set(&por, "test", "n1", 6.0, msg, sizeof msg);
  porosity_set(&por, "test", "n2", 3.0, msg, sizeof msg);
  porosity_set(&por, "test", "c_s", c_s, msg, sizeof msg);
  porosity_set(&por, "test", "c_e", c_e, msg, sizeof msg);
  if (porosity_finalize(&por, "test", msg, sizeof msg)) {
    printf("palpha_params: %s\n", msg);
    exit(1);
  }
  return por;
}

/* ------------------------------------------------------------ P-alpha */

static void test_crush_curve(void) {
  const struct porosity por = palpha_params(0.0, 0.0);
  const struct porosity_palpha *p = &por.palpha;
  const double tiny = 1e-9;
  check("crush curve: alpha(p_e+) = alpha_e",
        fabs(porosity_palpha_crush_alpha(p, p->p_e * (1 + tiny)) - p->alpha_e), 1e-8);
  check("crush curve: continuous at p_t",
        fabs(porosity_palpha_crush_alpha(p, p->p_t * (1 - tiny)) -
             porosity_palpha_crush_alpha(p, p->p_t * (1 + tiny))),
        1e-8);
  check("crush curve: alpha(p_s-) = 1",
        fabs(porosity_palpha_crush_alpha(p, p->p_s * (1 - tiny)) - 1.0), 1e-8);
  double prev = p->alpha_e, worst = 0.0, worst_slope = 0.0;
  for (int i = 0; i <= 2000; i++) {
    const double P = p->p_e + (p->p_s - p->p_e) * i / 2000.0;
    const double a = porosity_palpha_crush_alpha(p, P);
    worst = fmax(worst, a - prev);
    prev = a;
    if (i > 0 && i < 2000 && fabs(P - p->p_t) > 1e-3 * p->p_t) { /* kink at p_t */
      const double h = 1e-4 * (p->p_s - p->p_e) / 2000.0;
      const double fd =
          (porosity_palpha_crush_alpha(p, P + h) - porosity_palpha_crush_alpha(p, P - h)) / (2 * h);
      const double s = porosity_palpha_crush_slope(p, P);
      /* relative to the steepest slope (at p_e): the differences lose all
       * digits where the slope vanishes at p_s */
      worst_slope =
          fmax(worst_slope, fabs(s - fd) / fabs(porosity_palpha_crush_slope(p, p->p_e * 1.000001)));
    }
  }
  check("crush curve: non-increasing (largest rise)", worst, 0.0);
  check("crush curve: slope against centred differences (relative)", worst_slope, 1e-5);
  /* the defaults give the quadratic curve of Jutzi et al. 2008 eq. 8 */
  struct porosity q;
  char msg[256];
  porosity_init(&q, POROSITY_PALPHA);
  porosity_set(&q, "q", "alpha_0", 2.0, msg, sizeof msg);
  porosity_set(&q, "q", "p_e", 1e6, msg, sizeof msg);
  porosity_set(&q, "q", "p_s", 1e8, msg, sizeof msg);
  porosity_finalize(&q, "q", msg, sizeof msg);
  double e = 0.0;
  for (int i = 0; i <= 100; i++) {
    const double P = 1e6 + (1e8 - 1e6) * i / 100.0;
    const double x = (1e8 - P) / (1e8 - 1e6);
    e = fmax(e, fabs(porosity_palpha_crush_alpha(&q.palpha, P) - (1.0 + (2.0 - 1.0) * x * x)));
  }
  check("crush curve: defaults = quadratic curve (Jutzi 2008 eq. 8)", e, 1e-14);
}

/** For a state on the given branch, compare dalpha/dt with slope * dP/dt,
 *  dP/dt from a centred difference of PA1 along (rho', u', alpha'). */
static double tangent_error(const struct porosity_palpha *p, const struct matrix *m, double rho,
                            double u, double alpha, double drho, double du, int elastic) {
  double Ps, dr, dPdu;
  matrix_eval(m, alpha * rho, u, &Ps, &dr, &dPdu);
  const double da = porosity_palpha_dalpha_dt(p, rho, drho, du, alpha, Ps, dr, dPdu);
  const double h = 1e-6;
  const double Pp = bulk_pressure(m, rho + h * drho, u + h * du, alpha + h * da);
  const double Pm = bulk_pressure(m, rho - h * drho, u - h * du, alpha - h * da);
  const double dPdt = (Pp - Pm) / (2 * h);
  const double P = Ps / alpha;
  const double s = elastic ? porosity_palpha_elastic_slope(p, alpha, alpha * rho * dr)
                           : porosity_palpha_crush_slope(p, P);
  if (!(da < 0.0)) return 1.0; /* compression must compact */
  return fabs(da - s * dPdt) / fabs(da);
}

/** rho such that a particle of distention alpha has bulk pressure P. */
static double rho_at(const struct matrix *m, double u, double alpha, double P) {
  double lo = 0.5 * 2700.0 / alpha, hi = 2.0 * 2700.0 / alpha;
  for (int it = 0; it < 200; it++) {
    const double mid = 0.5 * (lo + hi);
    if (bulk_pressure(m, mid, u, alpha) < P)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

static void test_tangent(void) {
  const struct porosity por = palpha_params(0.0, 0.0);
  const struct porosity_palpha *p = &por.palpha;
  const double Ps[3] = {2e7, 8e7, 1.5e8};
  for (int k = 0; k < 2; k++) {
    const struct matrix m = k ? tillotson() : murnaghan();
    const double u = k ? 2.0e5 : 0.0, du = k ? 3.0e4 : 0.0;
    double worst = 0.0;
    for (int i = 0; i < 3; i++) {
      const double alpha = porosity_palpha_crush_alpha(p, Ps[i]);
      const double rho = rho_at(&m, u, alpha, Ps[i]);
      worst = fmax(worst, tangent_error(p, &m, rho, u, alpha, 0.7 * rho, du, 0));
    }
    char what[96];
    snprintf(what, sizeof what, "PA6 tangent to the crush curve (%s matrix)",
             k ? "Tillotson" : "Murnaghan");
    check(what, worst, 1e-6);
  }
  /* elastic branch: c_e < c_s, below p_e */
  const struct porosity pe = palpha_params(5000.0, 3000.0);
  const struct matrix m = tillotson();
  const double alpha = 1.7, rho = rho_at(&m, 1e5, alpha, 3e5);
  check("PA6 with the elastic slope PA7 (P < p_e, Tillotson)",
        tangent_error(&pe.palpha, &m, rho, 1e5, alpha, 0.5 * rho, 2e3, 1), 1e-6);
  double Ps1, dr, dPdu;
  matrix_eval(&m, alpha * rho, 1e5, &Ps1, &dr, &dPdu);
  check_true("no compaction under expansion (drho/dt < 0)",
             porosity_palpha_dalpha_dt(&pe.palpha, rho, -rho, 0.0, alpha, Ps1, dr, dPdu) == 0.0);
  check("h(alpha): 1 at alpha = 1, c_e/c_s at alpha_e",
        fabs(porosity_palpha_sound_ratio(&pe.palpha, 1.0) - 1.0) +
            fabs(porosity_palpha_sound_ratio(&pe.palpha, pe.palpha.alpha_e) - 0.6),
        1e-15);
}

/** Result of one compression run. */
struct run {
  double err;      /**< largest |alpha - alpha_cc(P)| / (alpha_e - 1) for p_e < P < p_s */
  double rise;     /**< largest increase of alpha in one step */
  double lo, hi;   /**< smallest and largest alpha */
  double alpha;    /**< final alpha */
  double P, P_sol; /**< final bulk pressure, and the solid EOS at the final rho */
};

/** Return a state above the crush curve to it (PA10) with the steps of
 *  porosity_palpha_return_step, re-evaluating the matrix EOS, until the
 *  iterate stops changing or the bracket is below 1e-14 alpha. */
static double project(const struct porosity_palpha *p, const struct matrix *m, double rho, double u,
                      double alpha, int *iters) {
  double Ps, dr, du;
  matrix_eval(m, alpha * rho, u, &Ps, &dr, &du);
  if (!porosity_palpha_above_curve(p, Ps / alpha, alpha)) return alpha;
  double lo = 1.0, hi = alpha;
  for (int k = 0; k < 200; k++) {
    const double a = porosity_palpha_return_step(p, rho, alpha, Ps, dr, &lo, &hi);
    if (k + 1 > *iters) *iters = k + 1;
    if (a == alpha) return a;
    if (hi - lo <= 1e-14 * hi) return lo;
    alpha = a;
    matrix_eval(m, alpha * rho, u, &Ps, &dr, &du);
  }
  return lo;
}

/** Compress a particle at drho/dt = rho (unit strain rate) to rho_s =
 *  1.03 rho0 with n forward Euler steps, du/dt = P/rho^2 drho/dt.  mode 0:
 *  the rate PA6 alone, from a state on the crush curve at P = 2e6 Pa.
 *  mode 1: the return PA10 alone after each step at fixed alpha; mode 2:
 *  PA6 and PA10; both from alpha_0 at u = 100 J/kg (P < p_e; the first step
 *  jumps over p_e, which the rate alone cannot follow). */
static struct run compress(const struct porosity_palpha *p, const struct matrix *m, int n, int mode,
                           int *iters) {
  const int with_projection = mode > 0, with_rate = mode != 1;
  struct run r = {0.0, 0.0, INFINITY, -INFINITY, 0.0, 0.0, 0.0};
  double u = 100.0, alpha = p->alpha_0, rho = 2700.0 / alpha;
  if (!with_projection) {
    alpha = porosity_palpha_crush_alpha(p, 2.0e6);
    rho = rho_at(m, u, alpha, 2.0e6);
  }
  const double rho_end = 2700.0 * 1.03, dt = log(rho_end / rho) / n;
  for (int i = 0; i < n; i++) {
    double Ps, dr, du;
    matrix_eval(m, alpha * rho, u, &Ps, &dr, &du);
    const double P = Ps / alpha, drho = rho, dudt = P / (rho * rho) * drho;
    const double da =
        with_rate ? porosity_palpha_dalpha_dt(p, rho, drho, dudt, alpha, Ps, dr, du) : 0.0;
    const double old = alpha;
    alpha = porosity_clamp_alpha(alpha + dt * da, p->alpha_0);
    rho += dt * drho;
    u += dt * dudt;
    if (with_projection) alpha = project(p, m, rho, u, alpha, iters);
    const double Pn = bulk_pressure(m, rho, u, alpha);
    r.rise = fmax(r.rise, alpha - old);
    r.lo = fmin(r.lo, alpha), r.hi = fmax(r.hi, alpha);
    if (Pn > p->p_e && Pn < p->p_s)
      r.err = fmax(r.err, fabs(alpha - porosity_palpha_crush_alpha(p, Pn)) / (p->alpha_e - 1.0));
  }
  double Ps, dr, du;
  matrix_eval(m, rho, u, &Ps, &dr, &du);
  r.alpha = alpha;
  r.P = bulk_pressure(m, rho, u, alpha);
  r.P_sol = Ps;
  return r;
}

static void test_compression(void) {
  const struct porosity por = palpha_params(0.0, 0.0);
  const struct porosity_palpha *p = &por.palpha;
  for (int k = 0; k < 2; k++) {
    const struct matrix m = k ? tillotson() : murnaghan();
    const char *name = k ? "Tillotson" : "Murnaghan";
    char what[128];
    double first = 0.0;
    int iters = 0;
    for (int n = 16000; n <= 64000; n *= 2) {
      const struct run r = compress(p, &m, n, 0, &iters);
      snprintf(what, sizeof what, "%s, PA6, %d steps: |alpha - alpha_cc(P)| / (alpha_e - 1)", name,
               n);
      /* one step at fixed alpha raises P by at most K dt (K: the matrix
       * bulk modulus at rho0), the crush curve then lags by |alpha_cc'| K dt */
      const double K = k ? m.till.A : m.murn.K0;
      const double dt =
          log(1.03 * 2700.0 / rho_at(&m, 100.0, porosity_palpha_crush_alpha(p, 2e6), 2e6)) / n;
      const double bound =
          fabs(porosity_palpha_crush_slope(p, p->p_e * 1.000001)) * K * dt / (p->alpha_e - 1.0);
      check(what, r.err, bound);
      if (n == 16000) first = r.err;
      snprintf(what, sizeof what, "%s, PA6, %d steps: alpha never increases, in [1, alpha_0]", name,
               n);
      check_true(what, r.rise <= 0.0 && r.lo >= 1.0 && r.hi <= p->alpha_0);
      if (n == 64000) {
        snprintf(what, sizeof what, "%s, PA6: convergence order from 16000 to 64000 steps (1)",
                 name);
        check(what, fabs(0.5 * log2(first / r.err) - 1.0), 0.2);
      }
    }
    for (int mode = 1; mode <= 2; mode++) {
      const int n = 4000;
      const char *how = mode == 1 ? "PA10" : "PA6 + PA10";
      iters = 0;
      const struct run r = compress(p, &m, n, mode, &iters);
      const double K = k ? m.till.A : m.murn.K0, dt = log(1.03 * p->alpha_0) / n;
      const double bound =
          fabs(porosity_palpha_crush_slope(p, p->p_e * 1.000001)) * K * dt / (p->alpha_e - 1.0);
      snprintf(what, sizeof what, "%s, %s, %d steps: alpha - crush curve", name, how, n);
      check(what, r.err, mode == 1 ? 1e-9 : bound);
      snprintf(what, sizeof what, "%s, %s, %d steps: alpha never increases", name, how, n);
      check_true(what, r.rise <= 0.0 && r.lo >= 1.0 && r.hi <= p->alpha_0);
      snprintf(what, sizeof what, "%s, %s, %d steps: alpha = 1 at full compaction", name, how, n);
      check(what, fabs(r.alpha - 1.0), 0.0);
      snprintf(what, sizeof what, "%s, %s, %d steps: P = solid EOS (relative)", name, how, n);
      check(what, fabs(r.P - r.P_sol) / r.P_sol, 1e-15);
      snprintf(what, sizeof what, "%s, %s: iterations of the return PA10 (at most)", name, how);
      check(what, iters, 20);
    }
  }
}

/* ------------------------------------------------------------ eps-alpha */

static struct porosity epsalpha_params(void) {
  struct porosity por;
  char msg[256];
  porosity_init(&por, POROSITY_EPSALPHA);
  porosity_set(&por, "e", "alpha_0", 2.0, msg, sizeof msg);
  porosity_set(&por, "e", "eps_e", -0.01, msg, sizeof msg);
  porosity_set(&por, "e", "eps_x", -0.3, msg, sizeof msg);
  porosity_set(&por, "e", "kappa", 0.98, msg, sizeof msg);
  porosity_set(&por, "e", "chi", 0.5, msg, sizeof msg);
  if (porosity_finalize(&por, "e", msg, sizeof msg)) {
    printf("epsalpha_params: %s\n", msg);
    exit(1);
  }
  return por;
}

/** The analytic alpha(eps) of CMW11 written independently of the header:
 *  returns the regime (0 elastic, 1 exponential, 2 power law, 3 compacted). */
static int analytic(double eps, double *alpha) {
  const double a0 = 2.0, ee = -0.01, ex = -0.3, k = 0.98, chi = 0.5;
  const double ae = a0 * exp(chi * k * ee), ax = ae * exp(k * (ex - ee));
  const double ec = ex - 2.0 * (ax - 1.0) / (k * ax);
  if (eps >= ee) return *alpha = a0 * exp(chi * k * fmin(eps, 0.0)), 0;
  if (eps >= ex) return *alpha = ae * exp(k * (eps - ee)), 1;
  if (eps > ec) return *alpha = 1.0 + (ax - 1.0) * pow((eps - ec) / (ex - ec), 2), 2;
  return *alpha = 1.0, 3;
}

static void test_epsalpha(void) {
  const struct porosity por = epsalpha_params();
  const struct porosity_epsalpha *p = &por.epsalpha;
  const double t = 1e-10;
  double e = 0.0;
  const double at[3] = {p->eps_e, p->eps_x, p->eps_c};
  for (int i = 0; i < 3; i++)
    e = fmax(e, fabs(porosity_epsalpha_alpha(p, at[i] * (1 - t)) -
                     porosity_epsalpha_alpha(p, at[i] * (1 + t))));
  check("eps-alpha: alpha continuous at eps_e, eps_x, eps_c", e, 1e-9);
  check("eps-alpha: slope continuous at eps_x and 0 at eps_c",
        fabs(porosity_epsalpha_slope(p, p->eps_x * (1 - t)) -
             porosity_epsalpha_slope(p, p->eps_x * (1 + t))) +
            fabs(porosity_epsalpha_slope(p, p->eps_c * (1 - t))),
        1e-8);
  double es = 0.0;
  for (int i = 1; i < 1000; i++) {
    const double eps = -1.2 * i / 1000.0, h = 1e-7;
    const double fd =
        (porosity_epsalpha_alpha(p, eps + h) - porosity_epsalpha_alpha(p, eps - h)) / (2 * h);
    if (fabs(eps - p->eps_e) > 2 * h && fabs(eps - p->eps_c) > 2 * h)
      es = fmax(es, fabs(porosity_epsalpha_slope(p, eps) - fd));
  }
  check("eps-alpha: slope against centred differences", es, 1e-6);
  /* compress to eps = -0.6, unload to -0.5, reload to -1.2, with EA5 */
  double prev = 0.0;
  for (int n = 4000; n <= 16000; n *= 2) {
    double eps = 0.0, alpha = p->alpha_0, err[4] = {0, 0, 0, 0}, rise = 0.0, unload = 0.0;
    const double dt = 1.2 / n;
    const int n1 = n / 2, n2 = n1 + n / 12, n3 = n2 + n / 12 + n / 2;
    for (int i = 0; i < n3; i++) {
      const double rate = i < n1 || i >= n2 ? -1.0 : 1.0;
      const double da = porosity_epsalpha_dalpha_dt(p, eps, rate, alpha);
      const double old = alpha;
      alpha = porosity_clamp_alpha(alpha + dt * da, p->alpha_0);
      eps += dt * rate;
      rise = fmax(rise, alpha - old);
      double a;
      const int reg = analytic(eps, &a);
      if (i < n1 || eps < -0.6 + 2 * dt)
        err[reg] = fmax(err[reg], fabs(alpha - a));
      else
        unload = fmax(unload, fabs(alpha - old));
    }
    const char *names[4] = {"elastic", "exponential", "power law", "compacted"};
    char what[128];
    for (int r = 0; r < 4; r++) {
      snprintf(what, sizeof what, "eps-alpha, %d steps, %s regime: alpha - analytic", n, names[r]);
      check(what, err[r], 4.0 / n);
    }
    snprintf(what, sizeof what, "eps-alpha, %d steps: alpha never increases", n);
    check_true(what, rise <= 0.0);
    snprintf(what, sizeof what, "eps-alpha, %d steps: unload/reload above eps_min: alpha fixed", n);
    check(what, unload, 0.0);
    const double worst = fmax(fmax(err[0], err[1]), err[2]);
    if (n == 4000) prev = worst;
    if (n == 16000) {
      check("eps-alpha: convergence order from 4000 to 16000 steps (1)",
            fabs(0.5 * log2(prev / worst) - 1.0), 0.2);
    }
  }
}

/* ------------------------------------------------------------ ICs, params */

static void test_ic(void) {
  check("porosity_check_ic: rho alpha = rho_s", porosity_check_ic(1500.0, 1.8, 2700.0, 1e-12), 0.0);
  check("porosity_check_ic: 1% off is reported",
        fabs(porosity_check_ic(1500.0, 1.8 * 1.01, 2700.0, 1e-3) - 0.01), 1e-12);
  check_true("porosity_check_ic: alpha < 1 is reported",
             porosity_check_ic(3000.0, 0.9, 2700.0, 1.0) > 0.0);
}

/** Expect porosity_set + finalize of one bad value to fail with a message
 *  naming the material and the key. */
static void expect_error(const char *key, double value, const char *expect_key) {
  struct porosity por = palpha_params(0.0, 0.0);
  porosity_init(&por, POROSITY_PALPHA);
  char msg[256] = "";
  const char *keys[5] = {"alpha_0", "p_e", "p_t", "p_s", "alpha_t"};
  const double vals[5] = {1.8, 1e6, 5e7, 2e8, 1.3};
  for (int i = 0; i < 5; i++) porosity_set(&por, "rock", keys[i], vals[i], msg, sizeof msg);
  int bad = porosity_set(&por, "rock", key, value, msg, sizeof msg);
  if (!bad) bad = porosity_finalize(&por, "rock", msg, sizeof msg);
  char want[64];
  snprintf(want, sizeof want, "key 'porosity: %s'", expect_key);
  const int ok = bad && strstr(msg, "material 'rock'") && strstr(msg, want) && !strchr(msg, '\n');
  printf("  %s\n", msg);
  char what[96];
  snprintf(what, sizeof what, "error for %s = %g names material and %s", key, value, expect_key);
  check_true(what, ok);
}

static void test_params(void) {
  expect_error("p_t", 3e8, "p_t");
  expect_error("p_t", 5e5, "p_t");
  expect_error("alpha_e", 2.5, "alpha_e");
  expect_error("alpha_t", 1.9, "alpha_t");
  expect_error("n1", -1.0, "n1");
  expect_error("c_e", 3000.0, "c_e");
  expect_error("p_s", 5e5, "p_s");
  expect_error("bogus", 1.0, "bogus");
  struct porosity por;
  char msg[256];
  porosity_init(&por, POROSITY_PALPHA);
  porosity_set(&por, "rock", "alpha_0", 2.0, msg, sizeof msg);
  check_true("missing p_e is reported", porosity_finalize(&por, "rock", msg, sizeof msg) &&
                                            strstr(msg, "'porosity: p_e' is required"));
  porosity_init(&por, POROSITY_EPSALPHA);
  porosity_set(&por, "sand", "alpha_0", 1.2, msg, sizeof msg);
  porosity_set(&por, "sand", "eps_e", -0.01, msg, sizeof msg);
  porosity_set(&por, "sand", "eps_x", -0.5, msg, sizeof msg);
  porosity_set(&por, "sand", "kappa", 0.98, msg, sizeof msg);
  check_true("eps-alpha: eps_x beyond full compaction is reported",
             porosity_finalize(&por, "sand", msg, sizeof msg) && strstr(msg, "'porosity: eps_x'"));
  /* YAML sub-mapping */
  char path[] = "/tmp/test_porosity_XXXXXX";
  const int fd = mkstemp(path);
  FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
  if (!f) {
    check_true("temporary YAML file", 0);
    return;
  }
  fprintf(f,
          "rock:\n  porosity: {model: palpha, alpha_0: 2.0, p_e: 1e6, p_s: 6.8e7, "
          "p_t: 2e7, alpha_t: 1.5, n1: 12, n2: 3}\n");
  fclose(f);
  struct params *pr = params_read_tree(path);
  const struct param_node *node =
      param_node_get(param_node_get(params_section(pr, ""), "rock"), "porosity");
  porosity_from_node(&por, "rock", pr, node);
  params_free(pr);
  unlink(path);
  check_true("YAML porosity: sub-mapping read (model, p_t, n1, derived alpha_e)",
             por.model == POROSITY_PALPHA && por.palpha.p_t == 2e7 && por.palpha.n1 == 12 &&
                 por.palpha.alpha_e == 2.0 && porosity_alpha_0(&por) == 2.0);
  /* through the material library: the porosity: key of a material entry */
  char lib[] = "/tmp/test_porosity_lib_XXXXXX";
  const int fl = mkstemp(lib);
  FILE *g = fl >= 0 ? fdopen(fl, "w") : NULL;
  if (!g) {
    check_true("temporary library file", 0);
    return;
  }
  fprintf(g,
          "porous_rock:\n  eos: murnaghan\n  rho0: 2700\n  K0: 2e10\n  n: 4\n"
          "  porosity: {model: epsalpha, alpha_0: 1.5, eps_e: -1e-4, eps_x: -0.2, kappa: 0.98}\n"
          "solid_rock:\n  eos: murnaghan\n  rho0: 2700\n  K0: 2e10\n  n: 4\n"
          "crushable:\n  eos: murnaghan\n  rho0: 2700\n  K0: 2e10\n  n: 4\n"
          "  porosity: {model: palpha, alpha_0: 2, p_e: 1e6, p_s: 2e8, c_s: 3000, c_e: 2000}\n");
  fclose(g);
  struct material_table t;
  material_table_init(&t);
  struct material mat;
  material_from_library(&mat, lib, "porous_rock", 0);
  material_table_add(&t, &mat);
  material_from_library(&mat, lib, "solid_rock", 1);
  material_table_add(&t, &mat);
  material_from_library(&mat, lib, "crushable", 2);
  material_table_add(&t, &mat);
  unlink(lib);
  check_true("library: porosity of each material (epsalpha, none, palpha)",
             t.mats[0].porosity.model == POROSITY_EPSALPHA &&
                 t.mats[0].porosity.epsalpha.alpha_0 == 1.5 &&
                 t.mats[1].porosity.model == POROSITY_NONE &&
                 porosity_alpha_0(&t.mats[1].porosity) == 1.0 &&
                 t.mats[2].porosity.model == POROSITY_PALPHA);
  struct unit_system cgs;
  units_init_cgs(&cgs);
  material_table_convert_units(&t, &cgs);
  const struct porosity_palpha *pc = &t.mats[2].porosity.palpha;
  check("units: p_e, p_s in barye and c_s, c_e in cm/s (relative)",
        fabs(pc->p_e / 1e7 - 1) + fabs(pc->p_s / 2e9 - 1) + fabs(pc->c_s / 3e5 - 1) +
            fabs(pc->c_e / 2e5 - 1) + fabs(t.mats[0].porosity.epsalpha.kappa / 0.98 - 1),
        1e-14);
  material_table_free(&t);
}

int main(int argc, char **argv) {
  (void)argc;
  error_init(argv[0]);
  test_crush_curve();
  test_tangent();
  test_compression();
  test_epsalpha();
  test_ic();
  test_params();
  if (failures) printf("%d check(s) FAILED\n", failures);
  return failures ? 1 : 0;
}
