/* Each expansion operator of tasks/gravity/gravity_iact.h against brute
 * force on a few points:
 *   - M2M of two children equals P2M of their union (exact, every order);
 *   - M2P of a cluster against direct summation: the error falls with the
 *     order p as (a/R)^(p+1) (theory/gravity.md, "Accuracy");
 *   - M2L + L2P between two clusters against direct summation: potential
 *     error below ((a+b)/R)^(p+1), acceleration below 2 ((a+b)/R)^p (relative;
 *     the acceleration is the derivative of a degree-p local polynomial);
 *   - the mutual point-cell form (M2P + P2L) against direct summation, and
 *     its momentum balance;
 *   - L2L is exact (a polynomial re-expanded), M2L in both directions at
 *     once equals two one-way M2Ls;
 *   - the derivative tensor against finite differences, Newtonian and
 *     Plummer-softened; the spline kernel: continuity at the support,
 *     force = -dphi/dr, central potential -G m / eps. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tasks/gravity/gravity_iact.h"

static int failures = 0;

/** Record a failed check. */
static void check(int ok, const char *what, double got, double limit) {
  printf("%-58s %12.4e (limit %.3e) %s\n", what, got, limit, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

/** Uniform random number in [0, 1) (drand48, fixed seed: reproducible). */
static double rnd(void) {
  return drand48();
}

/** n particles uniformly in a ball of radius a about c, random masses. */
static void cluster(int n, const double c[3], double a, double *x, double *m) {
  for (int i = 0; i < n; i++) {
    double d[3], r2;
    do {
      for (int k = 0; k < 3; k++) d[k] = 2.0 * rnd() - 1.0;
      r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    } while (r2 > 1.0);
    for (int k = 0; k < 3; k++) x[3 * i + k] = c[k] + a * d[k];
    m[i] = 0.5 + rnd();
  }
}

/** Multipole of particles [i0, i1) about their centre of mass, order p. */
static void make_multipole(const double *x, const double *m, int i0, int i1, int p,
                           struct gravity_multipole *mp) {
  double mt = 0.0, com[3] = {0, 0, 0};
  for (int i = i0; i < i1; i++) {
    mt += m[i];
    for (int k = 0; k < 3; k++) com[k] += m[i] * x[3 * i + k];
  }
  for (int k = 0; k < 3; k++) mp->com[k] = com[k] / mt;
  gravity_multipole_zero(mp);
  mp->r_max = 0.0;
  for (int i = i0; i < i1; i++) {
    double d[3];
    for (int k = 0; k < 3; k++) d[k] = x[3 * i + k] - mp->com[k];
    gravity_p2m(mp, d, m[i], p);
    const double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (r > mp->r_max) mp->r_max = r;
  }
}

/** Direct Newtonian potential and acceleration at y from particles. */
static void direct_at(const double y[3], const double *x, const double *m, int n, double eps2,
                      double *pot, double a[3]) {
  *pot = 0.0;
  a[0] = a[1] = a[2] = 0.0;
  for (int j = 0; j < n; j++) {
    double d[3];
    for (int k = 0; k < 3; k++) d[k] = y[k] - x[3 * j + k];
    const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + eps2;
    const double q = 1.0 / sqrt(r2);
    *pot -= m[j] * q;
    for (int k = 0; k < 3; k++) a[k] -= m[j] * q * q * q * d[k];
  }
}

static double norm3(const double a[3]) {
  return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

/** M2M of two halves equals P2M of the whole, every order. */
static void test_m2m(void) {
  enum { N = 64 };
  double x[3 * N], m[N], c[3] = {0.3, -0.2, 0.1};
  cluster(N, c, 1.0, x, m);
  for (int p = 1; p <= GRAVITY_ORDER_MAX; p++) {
    struct gravity_multipole whole, a, b, shifted;
    make_multipole(x, m, 0, N, p, &whole);
    make_multipole(x, m, 0, N / 3, p, &a);
    make_multipole(x, m, N / 3, N, p, &b);
    gravity_multipole_zero(&shifted);
    double t[3];
    for (int k = 0; k < 3; k++) t[k] = a.com[k] - whole.com[k];
    gravity_m2m(&shifted, &a, t, p);
    for (int k = 0; k < 3; k++) t[k] = b.com[k] - whole.com[k];
    gravity_m2m(&shifted, &b, t, p);
    double err = 0.0, scale = 0.0;
    for (int i = 0; i < GRAVITY_NCOMP(p); i++) {
      err = fmax(err, fabs(shifted.M[i] - whole.M[i]));
      scale = fmax(scale, fabs(whole.M[i]));
    }
    char what[96];
    snprintf(what, sizeof what, "M2M vs P2M of the union, p=%d (max rel)", p);
    check(err / scale < 1e-13, what, err / scale, 1e-13);
    if (p == GRAVITY_ORDER_MAX) {
      const double dip = norm3(whole.M + 1) / whole.M[0];
      check(dip < 1e-14, "dipole about the centre of mass", dip, 1e-14);
    }
  }
}

/** M2P against direct summation: error falls as (a/R)^(p+1). */
static void test_m2p(void) {
  enum { N = 200, NY = 20 };
  double x[3 * N], m[N], c[3] = {0, 0, 0};
  cluster(N, c, 1.0, x, m);
  const double R = 4.0;
  double prev_pot = 1e300, prev_acc = 1e300;
  for (int p = 1; p <= GRAVITY_ORDER_MAX; p++) {
    struct gravity_multipole mp;
    make_multipole(x, m, 0, N, p, &mp);
    const double ratio = mp.r_max / R;
    double epot = 0.0, eacc = 0.0;
    srand48(7);
    for (int s = 0; s < NY; s++) {
      double y[3], u[3] = {0, 0, 0}, dummy;
      cluster(1, u, 1.0, y, &dummy);
      const double ny = norm3(y);
      for (int k = 0; k < 3; k++) y[k] = mp.com[k] + R * y[k] / ny;
      double pd, ad[3], pm = 0.0, am[3] = {0, 0, 0}, Rv[3];
      direct_at(y, x, m, N, 0.0, &pd, ad);
      for (int k = 0; k < 3; k++) Rv[k] = y[k] - mp.com[k];
      gravity_m2p(&mp, Rv, 0.0, p, 1.0, &pm, am);
      double da[3] = {am[0] - ad[0], am[1] - ad[1], am[2] - ad[2]};
      epot = fmax(epot, fabs(pm - pd) / fabs(pd));
      eacc = fmax(eacc, norm3(da) / norm3(ad));
    }
    const double bound = pow(ratio, p + 1);
    char what[96];
    snprintf(what, sizeof what, "M2P potential, p=%d (max rel) < (a/R)^(p+1)", p);
    check(epot < bound && epot < prev_pot, what, epot, bound);
    snprintf(what, sizeof what, "M2P acceleration, p=%d (max rel) < 4 (a/R)^(p+1)", p);
    check(eacc < 4.0 * bound && eacc < prev_acc, what, eacc, 4.0 * bound);
    prev_pot = epot;
    prev_acc = eacc;
  }
}

/** M2L + L2P between two clusters against direct summation, and L2L. */
static void test_m2l_l2p(double eps2) {
  enum { NA = 150, NB = 150 };
  double xa[3 * NA], ma[NA], xb[3 * NB], mb[NB];
  double ca[3] = {0, 0, 0}, cb[3] = {3.0, 2.0, -1.5};
  cluster(NA, ca, 0.6, xa, ma);
  cluster(NB, cb, 0.6, xb, mb);
  double prev_pot = 1e300, prev_acc = 1e300;
  for (int p = 1; p <= GRAVITY_ORDER_MAX; p++) {
    struct gravity_multipole mpa, mpb;
    make_multipole(xa, ma, 0, NA, p, &mpa);
    make_multipole(xb, mb, 0, NB, p, &mpb);
    double R[3];
    for (int k = 0; k < 3; k++) R[k] = mpb.com[k] - mpa.com[k];
    const double theta = (mpa.r_max + mpb.r_max) / norm3(R);
    double D[GRAVITY_ND];
    gravity_derivatives(R, eps2, p, D);
    struct gravity_field fa, fb, fa1, fb1;
    gravity_field_zero(&fa);
    gravity_field_zero(&fb);
    gravity_field_zero(&fa1);
    gravity_field_zero(&fb1);
    gravity_m2l_sym(&fa, &fb, &mpa, &mpb, D, p);
    gravity_m2l(&fb1, &mpa, D, p);
    double Rm[3] = {-R[0], -R[1], -R[2]}, Dm[GRAVITY_ND];
    gravity_derivatives(Rm, eps2, p, Dm);
    gravity_m2l(&fa1, &mpb, Dm, p);
    double esym = 0.0, fscale = 0.0;
    for (int i = 0; i < GRAVITY_NCOMP(p); i++) {
      esym = fmax(esym, fmax(fabs(fa.F[i] - fa1.F[i]), fabs(fb.F[i] - fb1.F[i])));
      fscale = fmax(fscale, fmax(fabs(fa1.F[i]), fabs(fb1.F[i])));
    }
    char what[96];
    snprintf(what, sizeof what, "symmetric M2L vs two one-way M2L, p=%d", p);
    check(esym / fscale < 1e-13, what, esym / fscale, 1e-13);

    /* L2L to a sub-centre of B, then L2P, against L2P about B's centre. */
    double sub[3] = {mpb.com[0] + 0.2, mpb.com[1] - 0.3, mpb.com[2] + 0.1}, t[3];
    for (int k = 0; k < 3; k++) t[k] = sub[k] - mpb.com[k];
    struct gravity_field fc;
    gravity_field_zero(&fc);
    gravity_l2l(&fc, &fb, t, p);

    double epot = 0.0, eacc = 0.0, el2l = 0.0;
    for (int i = 0; i < NB; i++) {
      const double *y = xb + 3 * i;
      double pd, ad[3], pl = 0.0, al[3] = {0, 0, 0}, pc = 0.0, ac[3] = {0, 0, 0}, s[3], sc[3];
      direct_at(y, xa, ma, NA, eps2, &pd, ad);
      for (int k = 0; k < 3; k++) {
        s[k] = y[k] - mpb.com[k];
        sc[k] = y[k] - sub[k];
      }
      gravity_l2p(&fb, s, p, 1.0, &pl, al);
      gravity_l2p(&fc, sc, p, 1.0, &pc, ac);
      double da[3] = {al[0] - ad[0], al[1] - ad[1], al[2] - ad[2]};
      double dc[3] = {al[0] - ac[0], al[1] - ac[1], al[2] - ac[2]};
      epot = fmax(epot, fabs(pl - pd) / fabs(pd));
      eacc = fmax(eacc, norm3(da) / norm3(ad));
      el2l = fmax(el2l, fmax(fabs(pl - pc) / fabs(pl), norm3(dc) / norm3(al)));
    }
    const char *kind = eps2 > 0 ? "Plummer" : "Newton";
    snprintf(what, sizeof what, "L2L exact (%s), p=%d", kind, p);
    check(el2l < 1e-12, what, el2l, 1e-12);
    const double bp = pow(theta, p + 1), ba = pow(theta, p);
    snprintf(what, sizeof what, "M2L+L2P potential (%s), p=%d < theta^(p+1)", kind, p);
    check(epot < bp && epot < prev_pot, what, epot, bp);
    snprintf(what, sizeof what, "M2L+L2P acceleration (%s), p=%d < 2 theta^p", kind, p);
    check(eacc < 2.0 * ba && eacc < prev_acc, what, eacc, 2.0 * ba);
    prev_pot = epot;
    prev_acc = eacc;
  }
}

/** Mutual point-cell interaction (M2P + P2L) against direct summation, and
 *  its momentum balance: m a_point + sum_j m_j a_j = 0 to rounding. */
static void test_m2p_p2l(void) {
  enum { NB = 120 };
  double xb[3 * NB], mb[NB], cb[3] = {0.4, -0.3, 0.2};
  cluster(NB, cb, 0.5, xb, mb);
  const double x[3] = {-2.0, 1.0, 0.5}, m = 0.7;
  double prev_acc = 1e300;
  for (int p = 1; p <= GRAVITY_ORDER_MAX; p++) {
    struct gravity_multipole mp;
    make_multipole(xb, mb, 0, NB, p, &mp);
    const double R[3] = {mp.com[0] - x[0], mp.com[1] - x[1], mp.com[2] - x[2]};
    const double theta = mp.r_max / norm3(R);
    double D[GRAVITY_ND], pot = 0.0, a[3] = {0, 0, 0}, pd, ad[3];
    gravity_derivatives(R, 0.0, p, D);
    struct gravity_field f;
    gravity_field_zero(&f);
    gravity_m2p_p2l(m, &mp, &f, D, p, 1.0, &pot, a);
    direct_at(x, xb, mb, NB, 0.0, &pd, ad);
    const double da[3] = {a[0] - ad[0], a[1] - ad[1], a[2] - ad[2]};
    const double eacc = norm3(da) / norm3(ad), epot = fabs(pot - pd) / fabs(pd);
    /* B's particles from the point, through the local expansion */
    double P[3] = {m * a[0], m * a[1], m * a[2]}, scale = m * norm3(a), eb = 0.0;
    for (int j = 0; j < NB; j++) {
      const double *y = xb + 3 * j;
      const double s[3] = {y[0] - mp.com[0], y[1] - mp.com[1], y[2] - mp.com[2]};
      double pl = 0.0, al[3] = {0, 0, 0}, pj, aj[3];
      gravity_l2p(&f, s, p, 1.0, &pl, al);
      direct_at(y, x, &m, 1, 0.0, &pj, aj);
      const double dj[3] = {al[0] - aj[0], al[1] - aj[1], al[2] - aj[2]};
      eb = fmax(eb, norm3(dj) / norm3(aj));
      for (int k = 0; k < 3; k++) P[k] += mb[j] * al[k];
    }
    char what[96];
    snprintf(what, sizeof what, "M2P (mutual form) potential, p=%d < theta^(p+1)", p);
    check(epot < pow(theta, p + 1), what, epot, pow(theta, p + 1));
    /* acceleration to order p-1, as M2L (the dipole about the centre of
     * mass vanishes: p = 1 and 2 give the same acceleration) */
    snprintf(what, sizeof what, "M2P (mutual form) acceleration, p=%d < 2 theta^p", p);
    check(eacc < 2 * pow(theta, p) && eacc <= prev_acc * (1 + 1e-9), what, eacc, 2 * pow(theta, p));
    /* A point source's expansion about z_B, evaluated r from z_B: the
     * Legendre series of 1/|R - r| with terms r^l / R^(l+1), whose gradients
     * are at most (l+1) r^l / R^(l+2); the omitted l > p sum to at most
     * (p+1) theta^p / (1 - theta) relative to the monopole force. */
    const double bound = (p + 1) * pow(theta, p) / (1.0 - theta);
    snprintf(what, sizeof what, "P2L + L2P acceleration, p=%d < (p+1) theta^p/(1-theta)", p);
    check(eb < bound, what, eb, bound);
    snprintf(what, sizeof what, "point-cell momentum balance, p=%d", p);
    check(norm3(P) / scale < 1e-13, what, norm3(P) / scale, 1e-13);
    prev_acc = eacc;
  }
}

/** Derivative tensor against central finite differences of the order below. */
static void test_derivatives(double eps2) {
  const int q = GRAVITY_ORDER_MAX + 1;
  const double R[3] = {0.7, -1.1, 0.4}, h = 1e-5;
  double D[GRAVITY_ND], Dp[GRAVITY_ND], Dm[GRAVITY_ND];
  gravity_derivatives(R, eps2, q, D);
  const double f0 = 1.0 / sqrt(R[0] * R[0] + R[1] * R[1] + R[2] * R[2] + eps2);
  double err = fabs(D[0] - f0) / f0;
  for (int ax = 0; ax < 3; ax++) {
    double rp[3] = {R[0], R[1], R[2]}, rm[3] = {R[0], R[1], R[2]};
    rp[ax] += h;
    rm[ax] -= h;
    gravity_derivatives(rp, eps2, q - 1, Dp);
    gravity_derivatives(rm, eps2, q - 1, Dm);
    for (int n = 0; n < q; n++)
      for (int nx = n; nx >= 0; nx--)
        for (int ny = n - nx; ny >= 0; ny--) {
          const int nz = n - nx - ny;
          const int i = gravity_index(nx, ny, nz);
          const int j = gravity_index(nx + (ax == 0), ny + (ax == 1), nz + (ax == 2));
          const double fd = (Dp[i] - Dm[i]) / (2 * h);
          err = fmax(err, fabs(fd - D[j]) / (fabs(D[j]) + 1.0));
        }
  }
  char what[96];
  snprintf(what, sizeof what, "derivatives of 1/r vs finite differences (eps2=%g)", eps2);
  check(err < 1e-6, what, err, 1e-6);
}

/** Spline softening kernel: w(0), continuity at H, force = -d phi / dr. */
static void test_spline(void) {
  const double eps = 0.3, H = GRAVITY_SPLINE_H_OVER_EPS * eps;
  double wp, wa, wp2, wa2;
  gravity_softened_kernel(0.0, eps, GRAVITY_SOFTENING_SPLINE, &wp, &wa);
  check(fabs(wp * eps - 1.0) < 1e-14, "spline: central potential = -G m / eps", fabs(wp * eps - 1),
        1e-14);
  gravity_softened_kernel(H * H * (1 - 1e-12), eps, GRAVITY_SOFTENING_SPLINE, &wp, &wa);
  gravity_softened_kernel(H * H * (1 + 1e-12), eps, GRAVITY_SOFTENING_SPLINE, &wp2, &wa2);
  const double jump = fmax(fabs(wp - wp2) / wp2, fabs(wa - wa2) / wa2);
  check(jump < 1e-10, "spline: continuous at the support H = 3 eps", jump, 1e-10);
  double err = 0.0;
  for (int i = 1; i < 100; i++) {
    const double r = 1.2 * H * i / 100.0, h = 1e-6;
    double pp, pm, a;
    gravity_softened_kernel((r + h) * (r + h), eps, GRAVITY_SOFTENING_SPLINE, &pp, &a);
    gravity_softened_kernel((r - h) * (r - h), eps, GRAVITY_SOFTENING_SPLINE, &pm, &a);
    gravity_softened_kernel(r * r, eps, GRAVITY_SOFTENING_SPLINE, &wp, &wa);
    /* phi = -w_pot, |a| = w_acc r = -d(-w_pot)/dr ... i.e. w_acc r = -dw_pot/dr */
    const double fd = -(pp - pm) / (2 * h);
    err = fmax(err, fabs(fd - wa * r) / (wa * r));
  }
  check(err < 1e-6, "spline: acceleration = -d phi / dr", err, 1e-6);
}

int main(void) {
  srand48(12345);
  test_m2m();
  test_m2p();
  test_m2l_l2p(0.0);
  test_m2l_l2p(0.25);
  test_m2p_p2l();
  test_derivatives(0.0);
  test_derivatives(0.3);
  test_spline();
  printf("%d failure(s)\n", failures);
  return failures ? 1 : 0;
}
