/* Equations of state: sound speeds against numerical isentropic
 * derivatives, continuity of the Tillotson pressure across its regions,
 * round trips P(rho, u(rho, P)) = P, the tabulated EOS against the formula
 * it was built from, and the material dispatcher.
 *
 * Tolerances (stated, not tuned):
 *  - c^2 analytic vs numerical dP/drho along the isentrope du = P/rho^2
 *    drho (RK4 with 20 sub-steps, 6th-order central difference with step
 *    h = 1e-4 rho): 1e-6 relative (theory/validation.md, "Tillotson sound
 *    speed"); the method's own error is ~1e-10 (truncation h^6, round-off 1e-16 P/h).
 *  - continuity: the jump of P across a region boundary, over a step of
 *    1e-7 (relative) on each side, is at most 3 times the change of P over
 *    the adjacent step of the same size (a kink passes, a step fails) and at
 *    most 1e-6 of max(|P|, A).
 *  - round trips: bisection to 1e-15 relative in u (or rho); P reproduced
 *    to 1e-9 of the pressure scale max(|P|, rho c^2).
 *  - tables: bilinear interpolation in (ln rho, ln u) within
 *    (h_r^2/8) max|P_rr| + (h_u^2/8) max|P_uu| (second derivatives in ln
 *    rho, ln u, sampled on a 4x finer grid; factor 1.1 for the sampling of
 *    the maxima); monotone wherever the nodes are. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tests/helpers/eos_tables.h"
#include "src/materials/material.h"
#include "src/io/units.h"

static int failures = 0;
static int checks = 0;

/** Count a check; print it when it fails (or always with -v). */
static int verbose = 0;
#define CHECK(cond, ...)                          \
  do {                                            \
    checks++;                                     \
    if (!(cond)) {                                \
      failures++;                                 \
      printf("FAIL %s:%d: ", __FILE__, __LINE__); \
      printf(__VA_ARGS__);                        \
      printf("\n");                               \
    } else if (verbose) {                         \
      printf("ok: ");                             \
      printf(__VA_ARGS__);                        \
      printf("\n");                               \
    }                                             \
  } while (0)

/* ------------------------------------------------------------ materials */

/** Tillotson granite as in SWIFT (Melosh 1989 Table AII.3; Benz & Asphaug). */
static struct eos_tillotson granite(void) {
  struct eos_tillotson p;
  memset(&p, 0, sizeof p);
  p.rho0 = 2680.0;
  p.a = 0.5;
  p.b = 1.3;
  p.A = 1.8e10;
  p.B = 1.8e10;
  p.E0 = 1.6e7;
  p.Eiv = 3.5e6;
  p.Ecv = 1.8e7;
  p.alpha = 5.0;
  p.beta = 5.0;
  return p;
}

/** Basalt of Benz & Asphaug 1999 (theory/validation.md). */
static struct eos_tillotson basalt(void) {
  struct eos_tillotson p = granite();
  p.rho0 = 2700.0;
  p.a = 0.5;
  p.b = 1.5;
  p.A = 2.67e10;
  p.B = 2.67e10;
  p.E0 = 4.87e8;
  p.Eiv = 4.72e6;
  p.Ecv = 1.82e7;
  return p;
}

/* ------------------------------------------------------------ generic EOS */

/** Any EOS through one signature. */
typedef void (*eos_fn)(const void *p, double rho, double u, double *P, double *c2);

#define WRAP(name)                                                                   \
  static void w_##name(const void *p, double rho, double u, double *P, double *c2) { \
    eos_##name##_eval((const struct eos_##name *)p, rho, u, P, c2);                  \
  }
WRAP(ideal_gas)
WRAP(isothermal)
WRAP(polytropic)
WRAP(liquid)
WRAP(murnaghan)
WRAP(tillotson)
WRAP(mie_gruneisen)
WRAP(table)

static double pressure(eos_fn f, const void *p, double rho, double u) {
  double P, c2;
  f(p, rho, u, &P, &c2);
  return P;
}

/** Follow the isentrope du/drho = P/rho^2 from (rho, u) to rho + dr (RK4). */
static double isentrope(eos_fn f, const void *p, double rho, double u, double dr) {
  const int n = 20;
  const double h = dr / n;
  for (int k = 0; k < n; k++) {
    const double k1 = pressure(f, p, rho, u) / (rho * rho);
    const double r2 = rho + 0.5 * h;
    const double k2 = pressure(f, p, r2, u + 0.5 * h * k1) / (r2 * r2);
    const double k3 = pressure(f, p, r2, u + 0.5 * h * k2) / (r2 * r2);
    const double r4 = rho + h;
    const double k4 = pressure(f, p, r4, u + h * k3) / (r4 * r4);
    u += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    rho = r4;
  }
  return u;
}

/** (dP/drho)_s by a 6th-order central difference along the isentrope. */
static double c2_numerical(eos_fn f, const void *p, double rho, double u) {
  const double h = 1e-4 * rho;
  static const double w[7] = {-1.0, 9.0, -45.0, 0.0, 45.0, -9.0, 1.0};
  double s = 0.0;
  for (int k = -3; k <= 3; k++) {
    if (k == 0) continue;
    const double uk = isentrope(f, p, rho, u, k * h);
    s += w[k + 3] * pressure(f, p, rho + k * h, uk);
  }
  return s / (60.0 * h);
}

/** Compare the analytic c^2 with the numerical one at (rho, u). */
static void check_c2(const char *what, eos_fn f, const void *p, double rho, double u) {
  double P, c2;
  f(p, rho, u, &P, &c2);
  const double num = c2_numerical(f, p, rho, u);
  const double rel = fabs(c2 - num) / fabs(num);
  CHECK(rel <= 1e-6 && c2 > 0.0,
        "%s: rho %g u %g: P %.6g, c2 analytic %.12g numerical %.12g (rel %.2e)", what, rho, u, P,
        c2, num, rel);
}

/* ------------------------------------------------------------ Tillotson */

static void test_tillotson_c2(const char *name, const struct eos_tillotson *p) {
  const double r0 = p->rho0, Eiv = p->Eiv, Ecv = p->Ecv;
  const struct {
    double eta, u;
    enum eos_tillotson_region region;
  } states[] = {
      {1.2, 1e6, EOS_TILLOTSON_COMPRESSED},
      {1.5, 5e7, EOS_TILLOTSON_COMPRESSED},
      {2.5, 1e8, EOS_TILLOTSON_COMPRESSED},
      {0.95, 0.2 * Eiv, EOS_TILLOTSON_COMPRESSED}, /* cold expanded */
      {0.8, 2.0 * Ecv, EOS_TILLOTSON_EXPANDED},
      {0.5, 1.5 * Ecv, EOS_TILLOTSON_EXPANDED},
      {0.2, 3.0 * Ecv, EOS_TILLOTSON_EXPANDED},
      {0.9, 0.5 * (Eiv + Ecv), EOS_TILLOTSON_HYBRID},
      {0.7, Eiv + 0.25 * (Ecv - Eiv), EOS_TILLOTSON_HYBRID},
      {0.95, Eiv + 0.8 * (Ecv - Eiv), EOS_TILLOTSON_HYBRID},
  };
  for (size_t k = 0; k < sizeof states / sizeof states[0]; k++) {
    const double rho = states[k].eta * r0, u = states[k].u;
    char what[96];
    snprintf(what, sizeof what, "Tillotson %s region %d", name, (int)states[k].region);
    CHECK(eos_tillotson_region(p, rho, u) == states[k].region, "%s: state %zu in its region", what,
          k);
    /* the whole stencil must stay in the region (the EOS is smooth only there) */
    for (int s = -3; s <= 3; s += 6) {
      const double us = isentrope(w_tillotson, p, rho, u, s * 1e-4 * rho);
      CHECK(eos_tillotson_region(p, rho + s * 1e-4 * rho, us) == states[k].region,
            "%s: stencil of state %zu stays in its region", what, k);
    }
    check_c2(what, w_tillotson, p, rho, u);
  }
}

/** Jump of P across x (rho or u) against the change over the adjacent steps. */
static void check_continuity(const char *what, const struct eos_tillotson *p, double rho, double u,
                             int along_rho) {
  const double d = 1e-7;
  double P[4];
  for (int k = 0; k < 4; k++) {
    const double f = 1.0 + d * (2.0 * k - 3.0); /* -3d, -d, +d, +3d */
    P[k] =
        along_rho ? eos_tillotson_pressure(p, rho * f, u) : eos_tillotson_pressure(p, rho, u * f);
  }
  const double jump = fabs(P[2] - P[1]);
  const double slope = fmax(fabs(P[1] - P[0]), fabs(P[3] - P[2]));
  const double scale = fmax(fabs(P[1]), p->A);
  CHECK(jump <= 3.0 * slope + 1e-14 * scale && jump <= 1e-6 * scale,
        "%s: P %.10g | %.10g across rho %g u %g (jump %.3g, neighbour step %.3g)", what, P[1], P[2],
        rho, u, jump, slope);
}

/** The test above can fail: interpolating c_c^2 and c_e^2 linearly in the
 *  hybrid region (as SWIFT and miluphcuda do) is not the sound speed of T3
 *  and misses the numerical derivative by far more than 1e-6. */
static void test_tillotson_hybrid_discriminates(const struct eos_tillotson *p) {
  const double rho = 0.9 * p->rho0, u = 0.5 * (p->Eiv + p->Ecv);
  double Pc, drc, duc, Pe, dre, due;
  eos_tillotson_compressed(p, rho, u, &Pc, &drc, &duc);
  eos_tillotson_expanded(p, rho, u, &Pe, &dre, &due);
  const double c2c = drc + Pc / (rho * rho) * duc, c2e = dre + Pe / (rho * rho) * due;
  const double lin = 0.5 * (c2c + c2e);
  const double num = c2_numerical(w_tillotson, p, rho, u);
  CHECK(fabs(lin - num) > 1e-3 * num,
        "linear interpolation of c^2 in the hybrid region (%.8g) differs from (dP/drho)_s (%.8g)",
        lin, num);
}

static void test_tillotson_continuity(const char *name, const struct eos_tillotson *p) {
  char what[96];
  const double etas[] = {0.3, 0.6, 0.9, 0.99};
  for (size_t k = 0; k < 4; k++) {
    const double rho = etas[k] * p->rho0;
    snprintf(what, sizeof what, "Tillotson %s u = Eiv", name);
    check_continuity(what, p, rho, p->Eiv, 0);
    snprintf(what, sizeof what, "Tillotson %s u = Ecv", name);
    check_continuity(what, p, rho, p->Ecv, 0);
  }
  const double us[] = {0.0, 0.5 * p->Eiv, 0.5 * (p->Eiv + p->Ecv), 2.0 * p->Ecv, 10.0 * p->Ecv};
  for (size_t k = 0; k < 5; k++) {
    snprintf(what, sizeof what, "Tillotson %s rho = rho0", name);
    if (us[k] == 0.0) {
      /* u = 0: relative steps in u are meaningless; check along rho */
      check_continuity(what, p, p->rho0, 0.0, 1);
    } else {
      check_continuity(what, p, p->rho0, us[k], 1);
    }
  }
}

/* ------------------------------------------------------------ round trips */

/** u with P(rho, u) = P by bisection on [lo, hi] (P increasing in u). */
static double invert_u(eos_fn f, const void *p, double rho, double P, double lo, double hi) {
  for (int k = 0; k < 200 && hi - lo > 1e-15 * fabs(hi); k++) {
    const double mid = 0.5 * (lo + hi);
    if (pressure(f, p, rho, mid) < P)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

/** rho with P(rho, u) = P by bisection on [lo, hi] (P increasing in rho). */
static double invert_rho(eos_fn f, const void *p, double u, double P, double lo, double hi) {
  for (int k = 0; k < 200 && hi - lo > 1e-15 * fabs(hi); k++) {
    const double mid = 0.5 * (lo + hi);
    if (pressure(f, p, mid, u) < P)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

/** P(rho, u(rho, P)) = P over a set of states (energy-dependent EOS). */
static void round_trip_u(const char *what, eos_fn f, const void *p, const double *rho,
                         const double *u, int n, double u_hi) {
  for (int k = 0; k < n; k++) {
    double P, c2;
    f(p, rho[k], u[k], &P, &c2);
    const double ui = invert_u(f, p, rho[k], P, 0.0, u_hi);
    const double P2 = pressure(f, p, rho[k], ui);
    CHECK(fabs(P2 - P) <= 1e-9 * fmax(fabs(P), rho[k] * fabs(c2)) &&
              fabs(ui - u[k]) <= 1e-6 * u[k] + 1e-6,
          "%s round trip: rho %g u %g -> P %.10g -> u %.10g -> P %.10g", what, rho[k], u[k], P, ui,
          P2);
  }
}

/** P(rho(P), u) = P (barotropic EOS). */
static void round_trip_rho(const char *what, eos_fn f, const void *p, const double *rho, int n,
                           double rho_lo, double rho_hi) {
  for (int k = 0; k < n; k++) {
    double P, c2;
    f(p, rho[k], 1e5, &P, &c2);
    const double ri = invert_rho(f, p, 1e5, P, rho_lo, rho_hi);
    const double P2 = pressure(f, p, ri, 1e5);
    CHECK(fabs(P2 - P) <= 1e-9 * fmax(fabs(P), rho[k] * fabs(c2)) &&
              fabs(ri - rho[k]) <= 1e-9 * rho[k],
          "%s round trip: rho %g -> P %.10g -> rho %.12g -> P %.10g", what, rho[k], P, ri, P2);
  }
}

/* ------------------------------------------------------------ other EOS */

static void test_other_eos(void) {
  struct eos_ideal_gas ig = {5.0 / 3.0, 0.0, 0.0};
  struct eos_isothermal iso = {300.0, 0.0};
  struct eos_polytropic poly = {1.4, 1.0, 1e5};
  struct eos_liquid liq = {1010.0, 852.0, 0.0, 0.0};
  /* water by its compressibility modulus K0 = 2.2 GPa (c0 = sqrt(K0/rho0)) */
  struct eos_liquid water = {1000.0, 0.0, 2.2e9, 0.0};
  struct eos_murnaghan mur = {2700.0, 3.5e10, 4.0, 0.0};
  struct eos_mie_gruneisen mg = {2710.0, 6320.0, 1.337, 2.1, 0.0};

  check_c2("ideal gas", w_ideal_gas, &ig, 1.3, 2.5e5);
  check_c2("isothermal", w_isothermal, &iso, 1e-14, 0.0);
  check_c2("polytropic", w_polytropic, &poly, 2.0, 0.0);
  check_c2("liquid", w_liquid, &liq, 1100.0, 0.0);
  check_c2("liquid (tension)", w_liquid, &liq, 950.0, 0.0);
  check_c2("Murnaghan", w_murnaghan, &mur, 3000.0, 0.0);
  check_c2("Murnaghan (tension)", w_murnaghan, &mur, 2500.0, 0.0);
  check_c2("Mie-Grueneisen (compression)", w_mie_gruneisen, &mg, 3500.0, 1e6);
  check_c2("Mie-Grueneisen (strong compression)", w_mie_gruneisen, &mg, 5000.0, 3e7);
  check_c2("Mie-Grueneisen (tension)", w_mie_gruneisen, &mg, 2500.0, 1e5);
  check_c2("Mie-Grueneisen (strong expansion)", w_mie_gruneisen, &mg, 2000.0, 1e6);
  /* Tillotson water with SWIFT's low-density ramp of P_c (eta 0.875..0.925):
   * the derivative of the ramp factor is part of c^2 */
  {
    struct eos_tillotson w = granite();
    w.rho0 = 998.0;
    w.a = 0.7;
    w.b = 0.15;
    w.A = 2.18e9;
    w.B = 1.325e10;
    w.E0 = 7.0e6;
    w.Eiv = 4.19e5;
    w.Ecv = 2.69e6;
    w.alpha = 10.0;
    w.beta = 5.0;
    w.eta_min = 0.925;
    w.eta_zero = 0.875;
    check_c2("Tillotson water (low-density ramp)", w_tillotson, &w, 0.92 * w.rho0, 4e5);
    check_c2("Tillotson water (hybrid, ramped P_c)", w_tillotson, &w, 0.9 * w.rho0, 1.5e6);
  }

  /* the Mie-Grueneisen Hugoniot: at u = e_H = P_H mu / (2 rho0 (1 + mu)) the
   * pressure is P_H itself; the cubic P_H agrees with the closed form
   * rho0 c0^2 mu (1+mu)/(1-(s-1)mu)^2 to O(mu^4): at mu = 1e-3 to ~1e-8 */
  {
    const double mu = 1e-3, rho = mg.rho0 * (1.0 + mu);
    const double exact =
        mg.rho0 * mg.c0 * mg.c0 * mu * (1.0 + mu) / pow(1.0 - (mg.s - 1.0) * mu, 2);
    const double eH = exact * mu / (2.0 * mg.rho0 * (1.0 + mu));
    const double P = eos_mie_gruneisen_pressure(&mg, rho, eH);
    CHECK(fabs(P - exact) <= 1e-7 * exact, "Mie-Grueneisen on its Hugoniot: P %.12g vs P_H %.12g",
          P, exact);
  }
  /* Mie-Grueneisen in expansion (MG3): P = a0 mu + Gamma0 rho0 u exactly, so
   * the tension stays bounded by a0 as the material expands */
  {
    const double a0 = mg.rho0 * mg.c0 * mg.c0;
    const double rho = 0.5 * mg.rho0, u = 2e5;
    const double P = eos_mie_gruneisen_pressure(&mg, rho, u);
    const double want = a0 * (-0.5) + mg.Gamma0 * mg.rho0 * u;
    CHECK(fabs(P - want) <= 1e-12 * a0, "Mie-Grueneisen expanded (MG3): P %.12g vs %.12g", P, want);
    const double P10 = eos_mie_gruneisen_pressure(&mg, 0.1 * mg.rho0, 0.0);
    CHECK(fabs(P10 + 0.9 * a0) <= 1e-12 * a0, "Mie-Grueneisen at rho0/10: P %.6g a0 (want -0.9)",
          P10 / a0);
  }
  /* Gray et al. 2001 rubber: c0 = 852 m/s gives K = rho0 c0^2 */
  {
    double P, c2;
    eos_liquid_eval(&liq, liq.rho0, 0.0, &P, &c2);
    CHECK(P == 0.0 && fabs(sqrt(c2) - 852.0) < 1e-12, "liquid: P(rho0) = %g, c = %g", P, sqrt(c2));
  }

  /* water given by K0: P = (K0/rho0)(rho - rho0) exactly (to round-off),
   * c = sqrt(K0/rho0) = 1483.2397 m/s, the same state as c0 given directly */
  {
    double P, c2, Pc, c2c;
    const double c0 = sqrt(2.2e9 / 1000.0);
    const struct eos_liquid by_c0 = {1000.0, c0, 0.0, 0.0};
    eos_liquid_eval(&water, 1010.0, 0.0, &P, &c2);
    eos_liquid_eval(&by_c0, 1010.0, 0.0, &Pc, &c2c);
    CHECK(fabs(P - 2.2e7) <= 1e-9 * 2.2e7, "liquid by K0: P(1.01 rho0) = %.12g, want 2.2e7", P);
    CHECK(fabs(sqrt(c2) - 1483.2396974191) <= 1e-9, "liquid by K0: c = %.12g, want 1483.2396974191",
          sqrt(c2));
    CHECK(fabs(eos_liquid_sound_speed(&water, 900.0, 0.0) - c0) <= 1e-12 * c0,
          "liquid by K0: sound speed %.12g vs %.12g", eos_liquid_sound_speed(&water, 900.0, 0.0),
          c0);
    CHECK(fabs(P - Pc) <= 1e-9 * fabs(Pc) && fabs(c2 - c2c) <= 1e-12 * c2c,
          "liquid by K0 vs by c0: P %.12g / %.12g, c^2 %.12g / %.12g", P, Pc, c2, c2c);
    const char *key = NULL;
    CHECK(eos_liquid_check(&water, &key) == NULL, "liquid by K0 rejected");
    const struct eos_liquid both = {1000.0, c0, 2.2e9, 0.0}, none = {1000.0, 0.0, 0.0, 0.0};
    CHECK(eos_liquid_check(&both, &key) != NULL, "liquid with both c0 and K0 accepted");
    CHECK(eos_liquid_check(&none, &key) != NULL, "liquid with neither c0 nor K0 accepted");
    check_c2("liquid by K0", w_liquid, &water, 1050.0, 0.0);
    const double rw[] = {950.0, 1000.0, 1100.0};
    round_trip_rho("liquid by K0", w_liquid, &water, rw, 3, 500.0, 2000.0);
  }

  const double rho[] = {0.5, 1.0, 3.0}, u[] = {1e3, 2e5, 7e6};
  round_trip_u("ideal gas", w_ideal_gas, &ig, rho, u, 3, 1e9);
  const double rmg[] = {2000.0, 2710.0, 4000.0}, umg[] = {1e4, 1e6, 2e7};
  round_trip_u("Mie-Grueneisen", w_mie_gruneisen, &mg, rmg, umg, 3, 1e9);
  const double rl[] = {900.0, 1010.0, 1200.0};
  round_trip_rho("liquid", w_liquid, &liq, rl, 3, 500.0, 2000.0);
  const double rm[] = {2000.0, 2700.0, 4000.0};
  round_trip_rho("Murnaghan", w_murnaghan, &mur, rm, 3, 1000.0, 8000.0);
  const double rp[] = {0.1, 1.0, 10.0};
  round_trip_rho("polytropic", w_polytropic, &poly, rp, 3, 1e-3, 100.0);
  round_trip_rho("isothermal", w_isothermal, &iso, rp, 3, 1e-3, 100.0);
}

static void test_tillotson_round_trips(const char *name, const struct eos_tillotson *p) {
  /* P increases with u in every region for these materials (checked here
   * along the bracket by the bisection's own result) */
  const double rho[] = {1.2 * p->rho0, 0.95 * p->rho0, 0.9 * p->rho0,
                        0.6 * p->rho0, 0.5 * p->rho0,  2.0 * p->rho0};
  const double u[] = {1e6,          0.5 * p->Eiv, 0.5 * (p->Eiv + p->Ecv), 0.3 * (p->Eiv + p->Ecv),
                      2.0 * p->Ecv, 1e8};
  char what[64];
  snprintf(what, sizeof what, "Tillotson %s", name);
  round_trip_u(what, w_tillotson, p, rho, u, 6, 1e10);
}

/* ------------------------------------------------------------ tables */

static void test_table(void) {
  const struct eos_tillotson g = granite();
  struct eos_table t;
  const int nr = 48, nu = 48;
  const double r0 = g.rho0, r1 = 3.0 * g.rho0, u0 = 1e4, u1 = 1e8;
  table_from_tillotson(&t, &g, nr, nu, r0, r1, u0, u1);

  /* bound: second derivatives in ln rho and ln u on a 4x finer grid */
  const int nf = 4 * (nr - 1) + 1, nfu = 4 * (nu - 1) + 1;
  const double hr = t.dln_rho / 4, hu = t.dln_u / 4;
  double maxrr = 0.0, maxuu = 0.0, maxerr = 0.0, where_r = 0, where_u = 0;
  int monotone = 1;
  for (int i = 1; i < nf - 1; i++)
    for (int j = 1; j < nfu - 1; j++) {
      const double lr = t.ln_rho_min + i * hr, lu = t.ln_u_min + j * hu;
      const double Pc = eos_tillotson_pressure(&g, exp(lr), exp(lu));
      const double Prr = (eos_tillotson_pressure(&g, exp(lr + hr), exp(lu)) - 2 * Pc +
                          eos_tillotson_pressure(&g, exp(lr - hr), exp(lu))) /
                         (hr * hr);
      const double Puu = (eos_tillotson_pressure(&g, exp(lr), exp(lu + hu)) - 2 * Pc +
                          eos_tillotson_pressure(&g, exp(lr), exp(lu - hu))) /
                         (hu * hu);
      maxrr = fmax(maxrr, fabs(Prr));
      maxuu = fmax(maxuu, fabs(Puu));
      /* error at the centres of the fine sub-cells */
      const double rc = exp(lr + 0.5 * hr), uc = exp(lu + 0.5 * hu);
      const double err = fabs(eos_table_pressure(&t, rc, uc) - eos_tillotson_pressure(&g, rc, uc));
      if (err > maxerr) {
        maxerr = err;
        where_r = rc;
        where_u = uc;
      }
      /* monotone in rho and in u along the fine grid */
      const double Pi = eos_table_pressure(&t, exp(lr), exp(lu));
      if (eos_table_pressure(&t, exp(lr + hr), exp(lu)) < Pi ||
          eos_table_pressure(&t, exp(lr), exp(lu + hu)) < Pi)
        monotone = 0;
    }
  const double bound = 1.1 * (t.dln_rho * t.dln_rho / 8 * maxrr + t.dln_u * t.dln_u / 8 * maxuu);
  CHECK(maxerr <= bound,
        "table %dx%d of Tillotson granite: max |P_table - P| = %.4g Pa at (%g, %g) "
        "<= bound %.4g Pa",
        nr, nu, maxerr, where_r, where_u, bound);
  int nodes_monotone = 1;
  for (int i = 0; i < nr; i++)
    for (int j = 0; j < nu; j++) {
      if (i + 1 < nr && t.P[(i + 1) * nu + j] < t.P[i * nu + j]) nodes_monotone = 0;
      if (j + 1 < nu && t.P[i * nu + j + 1] < t.P[i * nu + j]) nodes_monotone = 0;
    }
  CHECK(nodes_monotone, "Tillotson granite nodes are monotone in rho and u (compressed region)");
  CHECK(monotone, "the interpolated table is monotone in rho and u");
  /* round trips through the table (P increases with u at fixed rho) */
  {
    const double rr[] = {1.1 * r0, 2.0 * r0, 2.9 * r0}, ur[] = {3e4, 1e6, 5e7};
    round_trip_u("table", w_table, &t, rr, ur, 3, u1);
  }
  /* exact at the nodes */
  CHECK(eos_table_pressure(&t, exp(t.ln_rho_min + 5 * t.dln_rho), exp(t.ln_u_min + 7 * t.dln_u)) ==
                t.P[5 * nu + 7] ||
            fabs(eos_table_pressure(&t, exp(t.ln_rho_min + 5 * t.dln_rho),
                                    exp(t.ln_u_min + 7 * t.dln_u)) -
                 t.P[5 * nu + 7]) <= 1e-12 * fabs(t.P[5 * nu + 7]),
        "table reproduces its nodes");
  /* the bisection of node arrays (eos_table_search, for axes of any spacing)
   * gives the division's cells and weights on log-spaced nodes: the same
   * values inside and (clamped) outside the grid, to rounding */
  {
    double rn[48], un[48];
    for (int i = 0; i < nr; i++) rn[i] = exp(t.ln_rho_min + i * t.dln_rho);
    for (int j = 0; j < nu; j++) un[j] = exp(t.ln_u_min + j * t.dln_u);
    struct eos_table tn;
    table_from_tillotson_nodes(&tn, &g, rn, nr, un, nu, 0.0);
    tn.rho_extrapolate = 0;
    double worst = 0.0;
    for (int k = 0; k < 4000; k++) {
      const double rc = 0.5 * r0 * pow(2.4 * r1 / r0, (k * 0.6180339887) - floor(k * 0.6180339887));
      const double uc = 0.3 * u0 * pow(4.0 * u1 / u0, (k * 0.7548776662) - floor(k * 0.7548776662));
      const double a = eos_table_pressure(&t, rc, uc), b = eos_table_pressure(&tn, rc, uc);
      worst = fmax(worst, fabs(a - b) / fmax(fabs(a), 1.0));
    }
    CHECK(worst <= 1e-12,
          "bisection of the nodes = division of the log grid, in and outside it (max rel %.2g)",
          worst);
    free((void *)tn.P);
    free((void *)tn.c2);
    free((void *)tn.ln_rho);
    free((void *)tn.ln_u);
  }
  /* the error falls as h^2: halve the spacing, error / 4 (within 30%) */
  {
    struct eos_table t2;
    table_from_tillotson(&t2, &g, 2 * nr - 1, 2 * nu - 1, r0, r1, u0, u1);
    double e1 = 0.0, e2 = 0.0;
    for (int k = 0; k < 2000; k++) {
      const double rc = r0 * pow(r1 / r0, (k * 0.6180339887) - floor(k * 0.6180339887));
      const double uc = u0 * pow(u1 / u0, (k * 0.7548776662) - floor(k * 0.7548776662));
      const double P = eos_tillotson_pressure(&g, rc, uc);
      e1 = fmax(e1, fabs(eos_table_pressure(&t, rc, uc) - P));
      e2 = fmax(e2, fabs(eos_table_pressure(&t2, rc, uc) - P));
    }
    CHECK(e2 < e1 / 4 * 1.3 && e2 > e1 / 4 / 1.3,
          "table error falls as h^2: %.4g -> %.4g (ratio %.2f, expected 4)", e1, e2, e1 / e2);
    free((void *)t2.P);
    free((void *)t2.c2);
  }

  /* a file in (rho, u) without sound speeds: loaded table equals the nodes,
   * and the c^2 differenced at load is within O(h^2) of Tillotson's */
  char fname[] = "/tmp/test_eos_XXXXXX";
  const int fd = mkstemp(fname);
  FILE *f = fdopen(fd, "w");
  fprintf(f, "# Tillotson granite, compressed\n%d %d\n", nr, nu);
  for (int i = 0; i < nr; i++)
    for (int j = 0; j < nu; j++)
      fprintf(f, "%.17g %.17g %.17g\n", exp(t.ln_rho_min + i * t.dln_rho),
              exp(t.ln_u_min + j * t.dln_u), t.P[i * nu + j]);
  fclose(f);
  struct eos_table lt;
  memset(&lt, 0, sizeof lt);
  material_eos_table_load(&lt, fname, 0);
  unlink(fname);
  CHECK(lt.n_rho == nr && lt.n_u == nu && fabs(lt.dln_rho - t.dln_rho) < 1e-12 &&
            fabs(lt.ln_u_min - t.ln_u_min) < 1e-12,
        "loaded grid %dx%d", lt.n_rho, lt.n_u);
  double maxd = 0.0, maxc = 0.0;
  for (int k = 0; k < nr * nu; k++) maxd = fmax(maxd, fabs(lt.P[k] - t.P[k]) / fabs(t.P[k]));
  for (int i = 1; i < nr - 1; i++)
    for (int j = 1; j < nu - 1; j++)
      maxc = fmax(maxc, fabs(lt.c2[i * nu + j] - t.c2[i * nu + j]) / t.c2[i * nu + j]);
  CHECK(maxd <= 1e-15, "loaded table pressures equal the file (max rel %.2g)", maxd);
  /* centred differences: relative error ~ h^2 |P'''| / (6 P') ~ h^2 with
   * h = dln ~ 0.2 (u) -> a few percent at most */
  CHECK(maxc <= 0.05,
        "c^2 differenced at load within 5%% of the analytic one (max rel %.3g, "
        "dln_u = %.3f)",
        maxc, t.dln_u);

  /* a (rho, T) table of an ideal gas with cv: u = cv T (1 + 0.01 i); the
   * rows are resampled on a common log-u grid.  P = (gamma-1) rho u =
   * C exp(x + y) in x = ln rho, y = ln u, so the relative error of the
   * resampling (linear in ln u between the source nodes, spacing h_T) is at
   * most e^{h_T} h_T^2 / 8, and that of the bilinear interpolation at most
   * e^{h_r + h_u} (h_r^2 + h_u^2) / 8 (second derivatives = P, largest at
   * the far corner of a cell); the bound is their sum. */
  {
    const double cv = 718.0, gam = 1.4;
    const int mr = 10, mt = 30;
    char f2[] = "/tmp/test_eos_XXXXXX";
    const int fd2 = mkstemp(f2);
    FILE *g2 = fdopen(fd2, "w");
    fprintf(g2, "%d %d\n", mr, mt);
    for (int i = 0; i < mr; i++)
      for (int j = 0; j < mt; j++) {
        const double rho = 0.1 * pow(100.0, i / (mr - 1.0)), T = 10.0 * pow(1e3, j / (mt - 1.0));
        /* a density-dependent factor makes the u ranges of the rows differ */
        const double u = cv * T * (1.0 + 0.01 * i);
        fprintf(g2, "%.17g %.17g %.17g %.17g\n", rho, T, u, (gam - 1.0) * rho * u);
      }
    fclose(g2);
    struct eos_table tt;
    memset(&tt, 0, sizeof tt);
    material_eos_table_load(&tt, f2, 1);
    unlink(f2);
    double worst = 0.0;
    for (int k = 0; k < 500; k++) {
      const double rho = 0.1 * pow(100.0, (k * 0.618034) - floor(k * 0.618034));
      const double lu =
          tt.ln_u_min + (tt.n_u - 1) * tt.dln_u * ((k * 0.7548777) - floor(k * 0.7548777));
      const double u = exp(lu);
      const double P = (gam - 1.0) * rho * u;
      worst = fmax(worst, fabs(eos_table_pressure(&tt, rho, u) - P) / P);
    }
    const double hT = log(1e3) / (mt - 1), hr2 = tt.dln_rho, hu2 = tt.dln_u;
    const double bound2 = exp(hT) * hT * hT / 8 + exp(hr2 + hu2) * (hr2 * hr2 + hu2 * hu2) / 8;
    CHECK(worst <= bound2 && eos_table_has_temperature(&tt),
          "(rho, T) table of an ideal gas: max rel error %.3g <= %.3g", worst, bound2);
    /* temperature: T = u / (cv (1 + 0.01 i)) at a node row */
    const double rho_node = exp(tt.ln_rho_min), u_node = exp(tt.ln_u_min + 3 * tt.dln_u);
    const double T = eos_table_temperature(&tt, rho_node, u_node);
    CHECK(fabs(T - u_node / cv) <= 0.02 * T, "(rho, T) table: temperature %g vs %g", T,
          u_node / cv);
    free((void *)tt.P);
    free((void *)tt.c2);
    free((void *)tt.T);
  }
  free((void *)lt.P);
  free((void *)lt.c2);
  free((void *)t.P);
  free((void *)t.c2);
}

/* ------------------------------------------------------------ dispatcher */

static void test_dispatch(void) {
  char msg[256];
  struct material m;
  material_init(&m, 103, "basalt", EOS_TILLOTSON);
  const struct eos_tillotson b = basalt();
  m.eos.tillotson = b;
  CHECK(material_finalize(&m, msg, sizeof msg) == 0, "finalize basalt: %s", msg);
  CHECK(m.rho0 == 2700.0, "rho0 copied from the EOS");
  CHECK(fabs(m.cs_min - 0.1 * sqrt(b.A / b.rho0)) < 1e-12, "default cs_min %g", m.cs_min);
  CHECK(fabs(m.bulk_modulus - b.A) <= 1e-9 * b.A, "bulk modulus %g = A at rho0, u = 0",
        m.bulk_modulus);
  double P, cs, P2, c2;
  material_eos(&m, 3000.0, 1e6, &P, &cs);
  eos_tillotson_eval(&b, 3000.0, 1e6, &P2, &c2);
  CHECK(P == P2 && cs == sqrt(c2), "material_eos = eos_tillotson_eval");
  /* deep tension: c^2 < cs_min^2, floor applies */
  eos_tillotson_eval(&b, 0.45 * b.rho0, 0.0, &P2, &c2);
  material_eos(&m, 0.45 * b.rho0, 0.0, &P, &cs);
  CHECK(c2 < m.cs_min * m.cs_min && cs == m.cs_min, "cs floor in tension: c2 %g -> cs %g", c2, cs);
}

/** A miluphcuda table (3 header lines, rows rho e P T cs, %.9e as
 *  tools/eos_tables.py writes) of the ideal gas, nodes from rho(i), e(j). */
static void write_miluphcuda_table(const char *path, const double *rho, int nr, const double *e,
                                   int ne) {
  FILE *f = fopen(path, "w");
  fprintf(f, "# test_eos\n# ideal gas\n# rho e P T cs\n");
  for (int i = 0; i < nr; i++)
    for (int j = 0; j < ne; j++)
      fprintf(f, "%.9e %.9e %.9e %.9e %.9e\n", rho[i], e[j], 2.0 / 3.0 * rho[i] * e[j],
              e[j] / 1000.0, sqrt(10.0 / 9.0 * e[j]));
  fclose(f);
}

/* format miluphcuda: log-spaced nodes written with 10 digits keep the
 * division of the log grid (no node arrays), other spacings get them */
static void test_table_miluphcuda_axes(void) {
  enum { NR = 30, NE = 40 };
  double rho[NR], e[NE];
  for (int i = 0; i < NR; i++) rho[i] = pow(1e4, i / (NR - 1.0));
  for (int j = 0; j < NE; j++) e[j] = 1e4 * pow(1e4, j / (NE - 1.0));
  char fname[] = "/tmp/test_eos_milu_XXXXXX";
  close(mkstemp(fname));
  for (int linear = 0; linear < 2; linear++) {
    if (linear)
      for (int j = 0; j < NE; j++) e[j] = 1e4 + j * (1e8 - 1e4) / (NE - 1.0);
    write_miluphcuda_table(fname, rho, NR, e, NE);
    struct eos_table t;
    memset(&t, 0, sizeof t);
    material_eos_table_load_miluphcuda(&t, fname, NR, NE);
    CHECK(!t.ln_rho && (linear ? t.ln_u != NULL : !t.ln_u), "miluphcuda table, %s energies: %s",
          linear ? "linear" : "log-spaced",
          linear ? "bisection of the energy nodes" : "the division of the log grid");
    /* in cgs (node arrays shifted by the units): P x 10, c x 100 at the
     * converted states, inside, beyond the densities (linear in rho) and
     * above the last energy (gamma_vapor) */
    struct material m;
    char msg[256] = "";
    material_init(&m, 0, "milu", EOS_TABLE);
    m.eos.table = t;
    CHECK(material_set(&m, "rho0", 100.0, msg, sizeof msg) == 0 &&
              material_set(&m, "gamma_vapor", 1.4, msg, sizeof msg) == 0 &&
              material_finalize(&m, msg, sizeof msg) == 0,
          "table material: %s", msg);
    struct material_table mt;
    material_table_init(&mt);
    material_table_add(&mt, &m);
    const double states[4][2] = {{37.0, 3.3e6}, {2e4, 3.3e6}, {0.4, 5.5e5}, {37.0, 2e8}};
    double P_si[4], c_si[4];
    for (int k = 0; k < 4; k++)
      material_eos(&mt.mats[0], states[k][0], states[k][1], &P_si[k], &c_si[k]);
    const struct unit_system cgs = {1.0, 1.0, 1.0, 1.0, 1.0, 0.0};
    material_table_convert_units(&mt, &cgs);
    double worst = 0.0;
    for (int k = 0; k < 4; k++) {
      double P, c;
      material_eos(&mt.mats[0], 1e-3 * states[k][0], 1e4 * states[k][1], &P, &c);
      worst = fmax(worst, fmax(fabs(P / (10 * P_si[k]) - 1), fabs(c / (100 * c_si[k]) - 1)));
    }
    CHECK(worst < 1e-12 && fabs(P_si[3] - 0.4 * 37.0 * 2e8) < 1e-9 * P_si[3],
          "miluphcuda table, %s energies, in cgs: P and c as in SI (max rel %.2g)",
          linear ? "linear" : "log-spaced", worst);
    material_table_free(&mt);
  }
  unlink(fname);
}

int main(int argc, char **argv) {
  verbose = argc > 1 && strcmp(argv[1], "-v") == 0;
  const struct eos_tillotson g = granite(), b = basalt();
  test_tillotson_c2("granite", &g);
  test_tillotson_c2("basalt", &b);
  test_tillotson_hybrid_discriminates(&g);
  test_tillotson_hybrid_discriminates(&b);
  test_tillotson_continuity("granite", &g);
  test_tillotson_continuity("basalt", &b);
  test_tillotson_round_trips("granite", &g);
  test_tillotson_round_trips("basalt", &b);
  test_other_eos();
  test_table();
  test_table_miluphcuda_axes();
  test_dispatch();
  printf("test_eos: %d checks, %d failed\n", checks, failures);
  return failures ? 1 : 0;
}
