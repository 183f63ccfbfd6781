/* The smoothing-length iteration's first-order step (SPH:h_taylor,
 * tasks/ghost/ghost_iact.h, theory/sph.md section 2).
 *
 * On a perturbed cubic lattice, for particles in its middle: the root h* of
 * n(h) h^3 = eta^3 by bisection on the brute-force sums; from h0 = h* (1 +
 * e), ghost_h_iterate must take the Newton step as GHOST_H_TAYLOR when
 * |e| is below sqrt(tol / 6), and the sums corrected to first order, n +
 * dn/dh dh and rho + drho/dh dh (what ghost_part_step does), must equal
 * the sums computed again at the new h within tol, while the sums left
 * uncorrected must not (the correction does the work), and the new h must
 * pass the iteration's own convergence test with the sums computed again.
 * A larger step must not be taken so (GHOST_H_AGAIN), nor any with taylor
 * 0.  Exit 0 pass, 1 fail. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tasks/density/density_iact.h"
#include "tasks/ghost/ghost_iact.h"
#include "tasks/hydro/kernel.h"

#define SIDE 14
#define NP (SIDE * SIDE * SIDE)

static double X[NP][3], M[NP];
static int failures = 0;

static void check(const char *what, int ok) {
  printf("%-72s %s\n", what, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

/** Particle i's sums at h, the self term included (as the ghost has them). */
static void sums(int i, double h, struct density_acc *a) {
  *a = (struct density_acc){0, 0, 0, 0, 0, {0, 0, 0}};
  const double hinv = 1.0 / h, H = kernel_gamma * h, dv[3] = {0, 0, 0};
  for (int j = 0; j < NP; j++) {
    if (j == i) continue;
    const double dx[3] = {X[i][0] - X[j][0], X[i][1] - X[j][1], X[i][2] - X[j][2]};
    const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
    if (r2 < H * H) density_iact(r2, dx, hinv, M[j], dv, a);
  }
  density_self_term(hinv, M[i], a);
}

static double f_of(int i, double h, double eta) {
  struct density_acc a;
  sums(i, h, &a);
  return a.wcount * h * h * h - eta * eta * eta;
}

int main(void) {
  const double eta = 1.2348, tol = 1e-4, taylor = sqrt(tol / 6.0);
  srand(11);
  int n = 0;
  for (int a = 0; a < SIDE; a++)
    for (int b = 0; b < SIDE; b++)
      for (int c = 0; c < SIDE; c++, n++) {
        const int ijk[3] = {a, b, c};
        for (int k = 0; k < 3; k++) X[n][k] = ijk[k] + 0.4 * ((double)rand() / RAND_MAX - 0.5);
        M[n] = 1.0 + 0.2 * ((double)rand() / RAND_MAX - 0.5);
      }
  const double eps[] = {2e-3, -2e-3, 3.5e-3, -3.5e-3, 1e-3, -1e-3};
  const int neps = (int)(sizeof eps / sizeof eps[0]);
  int tested = 0, taken = 0, again_large = 0, again_off = 0, converged_after = 0;
  double err_n = 0, err_rho = 0, raw_n2 = 0, cor_n2 = 0;
  for (int i = 0; i < NP; i++) {
    const double c = 0.5 * (SIDE - 1);
    if (fabs(X[i][0] - c) > 2 || fabs(X[i][1] - c) > 2 || fabs(X[i][2] - c) > 2) continue;
    /* the root by bisection */
    double lo = 0.5 * eta, hi = 2.5 * eta;
    for (int it = 0; it < 200; it++) {
      const double mid = 0.5 * (lo + hi);
      if (f_of(i, mid, eta) < 0.0)
        lo = mid;
      else
        hi = mid;
    }
    const double hstar = 0.5 * (lo + hi);
    for (int e = 0; e < neps; e++) {
      const double h0 = hstar * (1.0 + eps[e]);
      struct density_acc a0, a1;
      sums(i, h0, &a0);
      double h = h0, blo = 0.0, bhi = 1e300;
      const int r =
          ghost_h_iterate(&h, &blo, &bhi, a0.wcount, a0.wcount_dh, eta, tol, taylor, 1e30);
      tested++;
      if (r != GHOST_H_TAYLOR) continue;
      taken++;
      const double dh = h - h0;
      const double n_cor = a0.wcount + a0.wcount_dh * dh, rho_cor = a0.rho + a0.rho_dh * dh;
      sums(i, h, &a1);
      const double en = fabs(n_cor - a1.wcount) / a1.wcount;
      const double er = fabs(rho_cor - a1.rho) / a1.rho;
      const double raw = (a0.wcount - a1.wcount) / a1.wcount;
      if (en > err_n) err_n = en;
      if (er > err_rho) err_rho = er;
      raw_n2 += raw * raw;
      cor_n2 += en * en;
      /* the new h passes the iteration's own test with the sums redone */
      const double f1 = a1.wcount * h * h * h - eta * eta * eta;
      converged_after += fabs(f1) <= 3.0 * eta * eta * eta * tol;
    }
    /* a step beyond the bound is iterated as before */
    {
      const double h0 = hstar * 1.02;
      struct density_acc a0;
      sums(i, h0, &a0);
      double h = h0, blo = 0.0, bhi = 1e300;
      again_large += ghost_h_iterate(&h, &blo, &bhi, a0.wcount, a0.wcount_dh, eta, tol, taylor,
                                     1e30) == GHOST_H_AGAIN;
      h = h0, blo = 0.0, bhi = 1e300;
      sums(i, hstar * 1.002, &a0);
      h = hstar * 1.002;
      again_off += ghost_h_iterate(&h, &blo, &bhi, a0.wcount, a0.wcount_dh, eta, tol, 0.0, 1e30) ==
                   GHOST_H_AGAIN;
    }
  }
  const int centres = tested / neps;
  printf(
      "kernel %s, eta %g, tol %g: the first-order step up to %.3g relative; %d particles, %d "
      "starts\n",
      kernel_name, eta, tol, taylor, centres, tested);
  printf(
      "taken %d of %d; largest error of the corrected sums: n %.3e, rho %.3e; rms of n "
      "uncorrected %.3e, corrected %.3e\n",
      taken, tested, err_n, err_rho, sqrt(raw_n2 / (taken ? taken : 1)),
      sqrt(cor_n2 / (taken ? taken : 1)));
  char line[200];
  snprintf(line, sizeof line, "every start within the bound takes the first-order step (%d of %d)",
           taken, tested);
  check(line, centres > 50 && taken == tested);
  snprintf(line, sizeof line, "corrected n and rho equal the sums redone within tol (%.1e, %.1e)",
           err_n, err_rho);
  check(line, err_n <= tol && err_rho <= tol);
  snprintf(line, sizeof line, "the correction does the work (rms %.1e against %.1e uncorrected)",
           sqrt(cor_n2 / (taken ? taken : 1)), sqrt(raw_n2 / (taken ? taken : 1)));
  check(line, cor_n2 <= 0.01 * raw_n2 && raw_n2 > 0.0);
  snprintf(line, sizeof line, "the new h converged by the iteration's own test (%d of %d)",
           converged_after, taken);
  check(line, converged_after == taken);
  snprintf(line, sizeof line, "a 2%% step is iterated (%d of %d); taylor 0: never taken (%d of %d)",
           again_large, centres, again_off, centres);
  check(line, again_large == centres && again_off == centres);
  printf("test_ghost_taylor: %s\n", failures ? "FAIL" : "PASS");
  return failures ? 1 : 0;
}
