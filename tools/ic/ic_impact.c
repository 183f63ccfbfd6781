/* Two bodies on a collision course: the relative two-body (Kepler) orbit
 * through the contact point, followed backwards in time to the start.
 *
 * At first contact the centres are d_c = R_t + R_i apart, the relative speed
 * is v_c and the angle between the relative velocity and the line of
 * centres is theta (0: head-on).  The relative motion r'' = -mu r / |r|^3,
 * mu = G (M_t + M_i), is a conic (hyperbola, parabola or ellipse, by the
 * sign of E = v^2/2 - mu/r); it is integrated backwards with fourth-order
 * Runge-Kutta steps of 1e-4 of the local dynamical time r / v, with the
 * last step bisected to land on the requested separation, so that every
 * kind of orbit, head-on included, takes the same path.  See
 * theory/planets.md. */
#include <math.h>

#include "src/error.h"
#include "tools/ic/ic_impact.h"

/** Derivative of the state (r, v) of the relative Kepler problem. */
static void imp_deriv(double mu, const double s[6], double d[6]) {
  const double r2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
  const double f = -mu / (r2 * sqrt(r2));
  for (int k = 0; k < 3; k++) d[k] = s[3 + k], d[3 + k] = f * s[k];
}

/** One RK4 step of length dt (negative: backwards). */
static void imp_rk4(double mu, const double s[6], double dt, double out[6]) {
  double k1[6], k2[6], k3[6], k4[6], t[6];
  imp_deriv(mu, s, k1);
  for (int k = 0; k < 6; k++) t[k] = s[k] + 0.5 * dt * k1[k];
  imp_deriv(mu, t, k2);
  for (int k = 0; k < 6; k++) t[k] = s[k] + 0.5 * dt * k2[k];
  imp_deriv(mu, t, k3);
  for (int k = 0; k < 6; k++) t[k] = s[k] + dt * k3[k];
  imp_deriv(mu, t, k4);
  for (int k = 0; k < 6; k++) out[k] = s[k] + dt / 6 * (k1[k] + 2 * k2[k] + 2 * k3[k] + k4[k]);
}

static double imp_norm(const double *v) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

double ic_impact_start(double mu, double d_c, double v_c, double theta, double d0, double t0,
                       double s[6]) {
  /* contact: impactor at d_c (-cos theta, sin theta, 0) from the target,
   * moving along +x, so the angle between -r and v is theta */
  s[0] = -d_c * cos(theta), s[1] = d_c * sin(theta), s[2] = 0;
  s[3] = v_c, s[4] = 0, s[5] = 0;
  if (d0 > 0 && d0 < d_c) error_exit("impact: the initial separation is smaller than R_t + R_i");
  const double E = 0.5 * v_c * v_c - mu / d_c;
  if (d0 > 0 && E < 0) {
    /* bound orbit: the separation must be below the apoapsis */
    const double L = d_c * v_c * sin(theta);
    const double a = -mu / (2 * E), e = sqrt(fmax(0, 1 + 2 * E * L * L / (mu * mu)));
    if (d0 > a * (1 + e))
      error_exit("impact: separation %g m beyond the apoapsis %g m of the bound orbit", d0,
                 a * (1 + e));
  }
  double t = 0;
  for (long it = 0; it < 100000000L; it++) {
    const double r = imp_norm(s), v = imp_norm(s + 3);
    if (d0 > 0 ? r >= d0 * (1 - 1e-13) : t <= -t0 * (1 - 1e-13)) break;
    double dt = -1e-4 * r / fmax(v, sqrt(mu / r));
    if (d0 <= 0 && t + dt < -t0) dt = -t0 - t;
    double n[6];
    imp_rk4(mu, s, dt, n);
    if (d0 > 0 && imp_norm(n) > d0) {
      /* bisect the step so as to land on the separation */
      double lo = 0, hi = dt;
      for (int b = 0; b < 80; b++) {
        const double mid = 0.5 * (lo + hi);
        imp_rk4(mu, s, mid, n);
        if (imp_norm(n) > d0)
          hi = mid;
        else
          lo = mid;
      }
      dt = hi;
      imp_rk4(mu, s, dt, n);
    }
    for (int k = 0; k < 6; k++) s[k] = n[k];
    t += dt;
  }
  return -t;
}
