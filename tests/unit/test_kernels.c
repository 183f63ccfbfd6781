/* Kernel sums (theory/validation.md, "Kernel sums"): for every 3D kernel of tasks/hydro/kernel.h
 *  - int W dV = 1 and int grad W dV = 0 to 1e-6, as sums over a fine cubic
 *    lattice whose origin is offset from the kernel centre (so symmetry
 *    alone cannot make the gradient sum vanish);
 *  - the same normalisation from an accurate radial quadrature (1e-12), and
 *    gamma = H/h = 1/(2 sigma) from the kernel's second moment (Dehnen & Aly
 *    2012, Sec. 2.1), against the tabulated constant (1e-9);
 *  - dw/dq, dW/dr and dW/dh against centred finite differences;
 *  - the compiled-in generic functions against the per-kernel ones, and the
 *    neighbour number (4 pi/3)(gamma eta)^3 against a count of lattice points.
 * Exit 0 pass, 1 fail. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tasks/hydro/kernel.h"

static int failures = 0;

/** Report one check: name, measured value, bound. */
static void check(const char *kname, const char *what, double err, double tol) {
  const int ok = err <= tol && err == err;
  printf("%-15s %-34s %10.3e  (tol %.0e)  %s\n", kname, what, err, tol, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

/** Lattice sums of W and grad W for H = 1: spacing 1/n, origin offset. */
static void lattice_sums(enum kernel_type t, int n, double sum[4]) {
  const double d = 1.0 / n, off[3] = {0.3137 * d, 0.1729 * d, 0.4271 * d};
  double s0 = 0, sx = 0, sy = 0, sz = 0;
  for (int i = -n - 1; i <= n + 1; i++)
    for (int j = -n - 1; j <= n + 1; j++)
      for (int k = -n - 1; k <= n + 1; k++) {
        const double x = i * d + off[0], y = j * d + off[1], z = k * d + off[2];
        const double r = sqrt(x * x + y * y + z * z);
        if (r >= 1.0) continue;
        double w, dw;
        kernel_eval_type(t, r, &w, &dw);
        s0 += w;
        sx += dw * x / r;
        sy += dw * y / r;
        sz += dw * z / r;
      }
  const double d3 = d * d * d;
  sum[0] = s0 * d3;
  sum[1] = sx * d3;
  sum[2] = sy * d3;
  sum[3] = sz * d3;
}

/** Radial moments int_0^1 4 pi q^(2+p) w(q) dq by Simpson's rule on a grid
 *  containing every break point of the splines (0.2, 0.5, 0.6): exact up to
 *  rounding for the piecewise polynomials integrated here. */
static double radial_moment(enum kernel_type t, int p) {
  const int m = 20000;
  const double dq = 1.0 / m;
  double s = 0;
  for (int i = 0; i <= m; i++) {
    const double q = i * dq;
    double w, dw;
    kernel_eval_type(t, q, &w, &dw);
    const double f = 4.0 * M_PI * pow(q, 2 + p) * w;
    s += f * (i == 0 || i == m ? 1.0 : (i % 2 ? 4.0 : 2.0));
  }
  return s * dq / 3.0;
}

/** Largest |analytic - finite difference| of dw/dq, dW/dr and dW/dh over
 *  random points, relative to the largest |derivative| seen. */
static void finite_differences(enum kernel_type t, const char *kname) {
  const double e = 1e-5;
  double err_q = 0, max_q = 0, err_r = 0, max_r = 0, err_h = 0, max_h = 0;
  srand(7);
  for (int k = 0; k < 2000; k++) {
    const double q = 0.001 + 0.997 * rand() / (double)RAND_MAX;
    double w, dw, wp, dwp, wm, dwm;
    kernel_eval_type(t, q, &w, &dw);
    kernel_eval_type(t, q + e, &wp, &dwp);
    kernel_eval_type(t, q - e, &wm, &dwm);
    err_q = fmax(err_q, fabs(dw - (wp - wm) / (2 * e)));
    max_q = fmax(max_q, fabs(dw));
    /* dimensional: h in [0.5, 2], r = q gamma h */
    const double h = 0.5 + 1.5 * rand() / (double)RAND_MAX, r = q * kernel_type_gamma(t) * h;
    double W, dWr, dWh, Wp, Wm, tmp1, tmp2;
    kernel_eval_r_type(t, r, 1.0 / h, &W, &dWr, &dWh);
    const double er = e * h;
    kernel_eval_r_type(t, r + er, 1.0 / h, &Wp, &tmp1, &tmp2);
    kernel_eval_r_type(t, r - er, 1.0 / h, &Wm, &tmp1, &tmp2);
    err_r = fmax(err_r, fabs(dWr - (Wp - Wm) / (2 * er)));
    max_r = fmax(max_r, fabs(dWr));
    kernel_eval_r_type(t, r, 1.0 / (h + er), &Wp, &tmp1, &tmp2);
    kernel_eval_r_type(t, r, 1.0 / (h - er), &Wm, &tmp1, &tmp2);
    err_h = fmax(err_h, fabs(dWh - (Wp - Wm) / (2 * er)));
    max_h = fmax(max_h, fabs(dWh));
  }
  check(kname, "dw/dq vs finite difference", err_q / max_q, 1e-8);
  check(kname, "dW/dr vs finite difference", err_r / max_r, 1e-8);
  check(kname, "dW/dh vs finite difference", err_h / max_h, 1e-8);
}

int main(void) {
  for (int t = 0; t < KERNEL_NR_TYPES; t++) {
    const enum kernel_type kt = (enum kernel_type)t;
    const char *kname = kernel_type_name(kt);
    double sum[4];
    lattice_sums(kt, 64, sum);
    check(kname, "lattice |sum W dV - 1|", fabs(sum[0] - 1.0), 1e-6);
    check(kname, "lattice |sum grad W dV| (H = 1)",
          sqrt(sum[1] * sum[1] + sum[2] * sum[2] + sum[3] * sum[3]), 1e-6);
    check(kname, "radial |int W dV - 1|", fabs(radial_moment(kt, 0) - 1.0), 1e-12);
    /* sigma^2 = (1/3) int r^2 W dV, h = 2 sigma, gamma = H / h (H = 1) */
    const double sigma = sqrt(radial_moment(kt, 2) / 3.0);
    check(kname, "|gamma - 1/(2 sigma)| / gamma",
          fabs(kernel_type_gamma(kt) - 0.5 / sigma) / kernel_type_gamma(kt), 1e-9);
    double w1, dw1;
    kernel_eval_type(kt, 1.0, &w1, &dw1);
    check(kname, "w(1), w'(1)", fabs(w1) + fabs(dw1), 0.0);
    finite_differences(kt, kname);
  }

  /* the compiled-in kernel under its generic names */
  double err = 0;
  for (int k = 0; k <= 1000; k++) {
    const double r = 2.5 * k / 1000.0, h = 1.1;
    double W, dWr, dWh, W2, dWr2, dWh2;
    kernel_eval_r(r, 1.0 / h, &W, &dWr, &dWh);
    kernel_eval_r_type(KERNEL_TYPE, r, 1.0 / h, &W2, &dWr2, &dWh2);
    err = fmax(err, fabs(W - W2) + fabs(dWr - dWr2) + fabs(dWh - dWh2));
    err = fmax(err, fabs(kernel_W(r, h) - W) + fabs(kernel_dW_dr(r, h) - dWr) +
                        fabs(kernel_dW_dh(r, h) - dWh));
  }
  check(kernel_name, "generic == per-kernel functions", err, 1e-14);
  check(kernel_name, "kernel_gamma == table", fabs(kernel_gamma - kernel_type_gamma(KERNEL_TYPE)),
        0.0);

  /* N_ngb = (4 pi / 3)(gamma eta)^3 is the mean number of particles of a
   * unit lattice within H = gamma eta of a point placed at random (the mean
   * over uniformly random centres is exactly the volume of the sphere) */
  const double eta = 5.0, H = kernel_gamma * eta;
  const int n = (int)H + 2, nsamples = 400;
  double mean = 0;
  srand(11);
  for (int s = 0; s < nsamples; s++) {
    const double c[3] = {rand() / (double)RAND_MAX, rand() / (double)RAND_MAX,
                         rand() / (double)RAND_MAX};
    long count = 0;
    for (int i = -n; i <= n; i++)
      for (int j = -n; j <= n; j++)
        for (int k = -n; k <= n; k++) {
          const double x = i - c[0], y = j - c[1], z = k - c[2];
          if (x * x + y * y + z * z < H * H) count++;
        }
    mean += (double)count / nsamples;
  }
  check(kernel_name, "N_ngb vs mean lattice count (rel.)",
        fabs(kernel_ngb_number(eta) - mean) / mean, 2e-3);

  printf("%s\n", failures ? "FAIL" : "PASS");
  return failures ? 1 : 0;
}
