/* Solids: the gradient loop, the correction tensor, the Jaumann rate and the
 * strength models (theory/solids.md).
 *  1. gradient sums: symmetric cell loops == gather form by brute force;
 *  2. the corrected velocity gradient reproduces a linear velocity field to
 *     1e-10 on a random distribution (Randles & Libersky 1996), the
 *     uncorrected one does not (its error is printed);
 *  3. a stress under rigid spin keeps |S| (S:dS/dt = 0 to round-off) and
 *     returns to itself after one turn (RK4, error O(dt^4));
 *  4. the J2 radial return puts sqrt(3 J2) on the yield surface of every
 *     strength model, leaves elastic states alone; the yield curves at
 *     known points;
 *  5. the artificial stress of a diagonal tension is -eps sigma/rho^2 on the
 *     tensile axes only, also after a rotation of the frame;
 *  6. the CSPM continuity equation (SPH:continuity_correction) gives the exact
 *     drho/dt = -rho div v of a linear velocity field on a random particle set
 *     with free surfaces, through the extra ghost and the force loops; the
 *     plain SPH continuity sum does not (its error is asserted to be large);
 *  7. Johnson & Cook (1985) fracture: the strain at fracture at known points,
 *     fracture after exactly eps_f of plastic strain, no strength after it,
 *     and the start-up checks of fracture and Johnson-Cook temperature. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tasks/density/density_cpu.h"
#include "tasks/force/force_cpu.h"
#include "src/error.h"
#include "tasks/gradient/gradient_cpu.h"
#include "tasks/gradient/gradient_finish.h"
#include "tasks/hydro_parts.h"
#include "tasks/hydro/kernel.h"
#include "src/materials/material.h"
#include "src/space.h"
#include "src/materials/strength.h"

static double urand(unsigned long long *s) {
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

static int nfail = 0;

/** Report a check: name, value, limit (value must be <= limit). */
static void check_le(const char *what, double value, double limit) {
  const int ok = value <= limit;
  printf("  %-62s %.3e (limit %.1e) %s\n", what, value, limit, ok ? "ok" : "FAIL");
  if (!ok) nfail++;
}

/** A liquid material with strength model st, id 0. */
static void make_table(struct material_table *t, enum material_strength_type st) {
  struct material m;
  char msg[256];
  material_init(&m, 0, "test", EOS_LIQUID);
  if (material_set(&m, "rho0", 1.0, msg, sizeof msg) ||
      material_set(&m, "c0", 1.0, msg, sizeof msg) ||
      material_set(&m, "shear_modulus", 0.22, msg, sizeof msg))
    error_exit("%s", msg);
  m.strength = st;
  if (material_finalize(&m, msg, sizeof msg)) error_exit("%s", msg);
  material_table_init(t);
  material_table_add(t, &m);
}

/* ----------------------------------------------------------------------- 1, 2 */
static void test_gradient(void) {
  const size_t n = 3000;
  unsigned long long s = 7;
  struct parts p;
  parts_alloc(&p, n);
  const double box[3] = {1.0, 1.0, 1.0};
  double A[9], b[3];
  for (int k = 0; k < 9; k++) A[k] = 2.0 * urand(&s) - 1.0;
  for (int k = 0; k < 3; k++) b[k] = urand(&s);
  for (size_t i = 0; i < n; i++) {
    p.x[i] = 0.05 + 0.9 * urand(&s);
    p.y[i] = 0.05 + 0.9 * urand(&s);
    p.z[i] = 0.05 + 0.9 * urand(&s);
    p.m[i] = 0.5 + urand(&s);
    p.h[i] = 0.07 + 0.05 * urand(&s);
    p.id[i] = (int64_t)i;
  }
  struct space sp;
  space_init(&sp, &p, box, 0, 50, 8);
  space_rebuild(&sp);
  for (size_t i = 0; i < n; i++) {
    const double x[3] = {p.x[i], p.y[i], p.z[i]};
    double v[3];
    for (int a = 0; a < 3; a++)
      v[a] = b[a] + A[3 * a] * x[0] + A[3 * a + 1] * x[1] + A[3 * a + 2] * x[2];
    p.vpx[i] = v[0], p.vpy[i] = v[1], p.vpz[i] = v[2];
  }
  struct space_pair *pairs;
  const size_t np = space_top_pairs(&sp, &pairs);
  for (size_t i = 0; i < n; i++) hydro_density_reset(&p, i);
  for (int c = 0; c < sp.nr_top; c++) density_self_cpu(&p, &sp.cells[c], NULL);
  for (size_t k = 0; k < np; k++)
    density_pair_cpu(&p, &sp.cells[pairs[k].ci], &sp.cells[pairs[k].cj], pairs[k].shift, NULL);
  for (size_t i = 0; i < n; i++) p.rho[i] += p.m[i] * kernel_W(0.0, p.h[i]);

  /* symmetric loops */
  for (size_t i = 0; i < n; i++) hydro_gradient_reset(&p, i);
  for (int c = 0; c < sp.nr_top; c++) gradient_self_cpu(&p, &sp.cells[c]);
  for (size_t k = 0; k < np; k++)
    gradient_pair_cpu(&p, &sp.cells[pairs[k].ci], &sp.cells[pairs[k].cj], pairs[k].shift);
  /* gather form, brute force */
  double worst = 0.0;
  for (size_t i = 0; i < n; i++) {
    struct gradient_acc a = {{0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0, 0, 0, 0}, 0};
    const double Hi = kernel_gamma * p.h[i];
    for (size_t j = 0; j < n; j++) {
      if (j == i) continue;
      const double dx[3] = {p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]};
      const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
      if (r2 >= Hi * Hi) continue;
      const double dv[3] = {p.vpx[i] - p.vpx[j], p.vpy[i] - p.vpy[j], p.vpz[i] - p.vpz[j]};
      gradient_iact(r2, dx, 1.0 / p.h[i], p.m[j] / p.rho[j], dv, &a);
    }
    const double got[15] = {p.gmxx[i], p.gmxy[i], p.gmxz[i], p.gmyy[i], p.gmyz[i],
                            p.gmzz[i], p.gvxx[i], p.gvxy[i], p.gvxz[i], p.gvyx[i],
                            p.gvyy[i], p.gvyz[i], p.gvzx[i], p.gvzy[i], p.gvzz[i]};
    double scale = 0.0;
    for (int k = 0; k < 6; k++) scale += fabs(a.M[k]);
    for (int k = 0; k < 6; k++) worst = fmax(worst, fabs(got[k] - a.M[k]) / scale);
    double gs = 0.0;
    for (int k = 0; k < 9; k++) gs += fabs(a.G[k]);
    for (int k = 0; k < 9; k++) worst = fmax(worst, fabs(got[6 + k] - a.G[k]) / (gs + 1e-300));
  }
  printf("gradient loop, N = %zu random particles, h varying by 1.7:\n", n);
  check_le("symmetric vs gather, worst relative difference", worst, 1e-12);

  /* corrected and uncorrected gradients of the linear field */
  struct material_table mats;
  make_table(&mats, STRENGTH_ELASTIC);
  struct hydro_props hp = {.gradient_correction = 1};
  double err_c = 0.0, err_u = 0.0, Anorm = 0.0;
  for (int k = 0; k < 9; k++) Anorm = fmax(Anorm, fabs(A[k]));
  for (int pass = 0; pass < 2; pass++) {
    hp.gradient_correction = pass == 0;
    for (size_t i = 0; i < n; i++) {
      /* restore the sums (the extra ghost overwrites gv) */
      const double M[6] = {p.gmxx[i], p.gmxy[i], p.gmxz[i], p.gmyy[i], p.gmyz[i], p.gmzz[i]};
      const double G[9] = {p.gvxx[i], p.gvxy[i], p.gvxz[i], p.gvyx[i], p.gvyy[i],
                           p.gvyz[i], p.gvzx[i], p.gvzy[i], p.gvzz[i]};
      double Minv[9], gv[9];
      if (hp.gradient_correction)
        gradient_invert_sym(M, Minv);
      else
        for (int k = 0; k < 9; k++) Minv[k] = (k % 4 == 0) ? 1.0 : 0.0;
      gradient_apply(G, Minv, gv);
      for (int k = 0; k < 9; k++) {
        const double e = fabs(gv[k] - A[k]) / Anorm;
        if (pass == 0)
          err_c = fmax(err_c, e);
        else
          err_u = fmax(err_u, e);
      }
    }
  }
  /* and through the extra ghost itself (strain rate -> dS/dt of a zero stress) */
  double err_ds = 0.0;
  for (size_t i = 0; i < n; i++) {
    p.mat[i] = 0;
    hp.gradient_correction = 1;
    extra_ghost_part_cpu(&p, i, &hp, &mats);
    const double tr = (A[0] + A[4] + A[8]) / 3.0;
    const double want[6] = {2 * 0.22 * (A[0] - tr), 0.22 * (A[1] + A[3]), 0.22 * (A[2] + A[6]),
                            2 * 0.22 * (A[4] - tr), 0.22 * (A[5] + A[7]), 2 * 0.22 * (A[8] - tr)};
    const double got[6] = {p.dSxx[i], p.dSxy[i], p.dSxz[i], p.dSyy[i], p.dSyz[i], p.dSzz[i]};
    for (int k = 0; k < 6; k++) err_ds = fmax(err_ds, fabs(got[k] - want[k]) / (0.22 * Anorm));
  }
  check_le("linear field, corrected gradient: max |gv - A| / max|A|", err_c, 1e-10);
  printf("  %-62s %.3e (for comparison)\n",
         "linear field, uncorrected gradient: max |gv - A| / max|A|", err_u);
  check_le("linear field, extra ghost: Hooke dS/dt = 2 mu dev(e) exactly", err_ds, 1e-10);
  if (!(err_u > 1e-3)) {
    printf("  FAIL: the uncorrected gradient should be visibly wrong at the free surface\n");
    nfail++;
  }
  material_table_free(&mats);
  free(pairs);
  space_free(&sp);
  parts_free(&p);
}

/* ----------------------------------------------------------------------- 3 */
static double norm6(const double S[6]) {
  return sqrt(2.0 * strength_J2(S));
}

static void test_jaumann_spin(void) {
  const double w[3] = {0.3, -0.7, 1.1}; /* angular velocity */
  const double wn = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  /* v = w x x: dv^a/dx^b = eps_acb w_c */
  const double gv[9] = {0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0};
  double S[6] = {1.0, 0.3, -0.2, -0.4, 0.5, -0.6};
  const double S0[6] = {1.0, 0.3, -0.2, -0.4, 0.5, -0.6};
  double dS[6];
  gradient_stress_rate(gv, S, 0.22, dS);
  double sds = 0.5 * (S[0] * dS[0] + S[3] * dS[3] + S[5] * dS[5]) + S[1] * dS[1] + S[2] * dS[2] +
               S[4] * dS[4];
  printf("Jaumann rate under rigid spin:\n");
  check_le("|S:dS/dt| / (|S| |dS/dt|)", fabs(2 * sds) / (norm6(S) * norm6(dS)), 1e-14);
  const int nsteps = 2000;
  const double T = 2.0 * M_PI / wn, dt = T / nsteps;
  double nmax = 0.0;
  for (int st = 0; st < nsteps; st++) {
    double k1[6], k2[6], k3[6], k4[6], t[6];
    gradient_stress_rate(gv, S, 0.22, k1);
    for (int k = 0; k < 6; k++) t[k] = S[k] + 0.5 * dt * k1[k];
    gradient_stress_rate(gv, t, 0.22, k2);
    for (int k = 0; k < 6; k++) t[k] = S[k] + 0.5 * dt * k2[k];
    gradient_stress_rate(gv, t, 0.22, k3);
    for (int k = 0; k < 6; k++) t[k] = S[k] + dt * k3[k];
    gradient_stress_rate(gv, t, 0.22, k4);
    for (int k = 0; k < 6; k++) S[k] += dt / 6.0 * (k1[k] + 2 * k2[k] + 2 * k3[k] + k4[k]);
    nmax = fmax(nmax, fabs(norm6(S) - norm6(S0)) / norm6(S0));
  }
  double back = 0.0;
  for (int k = 0; k < 6; k++) back = fmax(back, fabs(S[k] - S0[k]));
  check_le("one turn, RK4 2000 steps: max | |S(t)| - |S0| | / |S0|", nmax, 1e-10);
  check_le("one turn: max |S(T) - S0| / |S0|", back / norm6(S0), 1e-8);
}

/* ----------------------------------------------------------------------- 4 */
static void test_yield(void) {
  printf("yield surfaces and the radial return:\n");
  unsigned long long s = 3;
  const enum material_strength_type models[] = {STRENGTH_VON_MISES, STRENGTH_DRUCKER_PRAGER,
                                                STRENGTH_MOHR_COULOMB, STRENGTH_COLLINS,
                                                STRENGTH_JOHNSON_COOK};
  double worst = 0.0, moved = 0.0;
  int nret = 0;
  for (size_t mi = 0; mi < sizeof models / sizeof models[0]; mi++) {
    struct material m;
    material_init(&m, 0, "y", EOS_LIQUID);
    m.strength = models[mi];
    m.shear_modulus = 10.0;
    m.yield_stress = 1.0;
    m.yield_stress_max = 3.0;
    m.friction_intact = 1.2;
    m.friction_damaged = 0.6;
    m.cohesion_damaged = 0.1;
    m.melt_energy = 0.0;
    m.jc_A = 1.0, m.jc_B = 0.5, m.jc_C = 0.02, m.jc_m = 1.0, m.jc_n = 0.3;
    m.jc_strain_rate_ref = 1.0, m.T_ref = 300.0, m.T_melt = 1000.0, m.specific_heat = 100.0;
    for (int trial = 0; trial < 2000; trial++) {
      const struct strength_state st = {
          4.0 * urand(&s) - 1.0, 1.0, 30000.0 * urand(&s), urand(&s), 10.0 * urand(&s), urand(&s)};
      const double Y = strength_yield(&m, &st);
      double S[6];
      for (int k = 0; k < 6; k++) S[k] = 4.0 * urand(&s) - 2.0;
      S[5] = -S[0] - S[3];
      const double S0[6] = {S[0], S[1], S[2], S[3], S[4], S[5]};
      const double seq0 = sqrt(3.0 * strength_J2(S));
      const double dep = strength_radial_return(S, Y, m.shear_modulus);
      const double seq = sqrt(3.0 * strength_J2(S));
      if (seq0 > Y) {
        nret++;
        worst = fmax(worst, fabs(seq - Y) / fmax(Y, 1e-300));
        worst = fmax(worst, fabs(dep - (seq0 - Y) / (3.0 * m.shear_modulus)) / dep);
        /* the direction of S is kept: S = (Y / seq0) S0 */
        for (int k = 0; k < 6; k++) worst = fmax(worst, fabs(S[k] - S0[k] * Y / seq0) / seq0);
      } else {
        for (int k = 0; k < 6; k++) moved = fmax(moved, fabs(S[k] - S0[k]));
        moved = fmax(moved, dep);
      }
    }
  }
  printf("  %d of 10000 random stresses beyond the yield surface\n", nret);
  check_le("after the return: | sqrt(3 J2) - Y | / Y, direction, d eps_p", worst, 1e-13);
  check_le("elastic states unchanged", moved, 0.0);
  /* the curves at known points */
  double e = 0.0;
  e = fmax(e, fabs(strength_drucker_prager_yield(1.0, 1.2, 3.0, 1.0) - 2.2));
  e = fmax(e, fabs(strength_drucker_prager_yield(1.0, 1.2, 3.0, 10.0) - 3.0));
  e = fmax(e, fabs(strength_drucker_prager_yield(1.0, 1.2, 3.0, -5.0) - 0.0));
  e = fmax(e, fabs(strength_mohr_coulomb_yield(1.0, 1.2, 0.0, 10.0) - 13.0));
  /* Collins: Y_i(0) = Y0, Y_i -> Y_M as P -> infinity, slope mu_i at P = 0 */
  e = fmax(e, fabs(strength_collins_yield(1.0, 1.2, 3.0, 0.1, 0.6, 0.0, 0.0) - 1.0));
  e = fmax(e,
           fabs(strength_collins_yield(1.0, 1.2, 3.0, 0.1, 0.6, 1e12, 0.0) - 3.0) / 1e-9 * 1e-12);
  e = fmax(
      e,
      fabs((strength_collins_yield(1.0, 1.2, 3.0, 0.1, 0.6, 1e-7, 0.0) - 1.0) / 1e-7 - 1.2) * 1e-6);
  e = fmax(e, fabs(strength_collins_yield(1.0, 1.2, 3.0, 0.1, 0.6, 1.0, 1.0) - 0.7));
  /* Johnson-Cook: at T_melt no strength; at T_ref, rate_ref, eps_p = 1: A + B */
  e = fmax(
      e, fabs(strength_johnson_cook_yield(1.0, 0.5, 0.02, 1.0, 0.3, 1.0, 300, 1000, 1.0, 1.0, 300) -
              1.5));
  e = fmax(e, fabs(strength_johnson_cook_yield(1.0, 0.5, 0.02, 1.0, 0.3, 1.0, 300, 1000, 1.0, 1.0,
                                               1000)));
  e = fmax(e, fabs(strength_johnson_cook_yield(1.0, 0.0, 0.02, 1.0, 0.3, 1.0, 300, 1000, 0.0,
                                               exp(1.0), 300) -
                   1.02));
  check_le("yield curves at known points (DP, MC, Collins, JC)", e, 1e-12);
}

/* ----------------------------------------------------------------------- 5 */
static void test_artificial_stress(void) {
  printf("artificial stress:\n");
  /* principal stresses sigma = diag(2, -1, 0.5) - P, P = 0; rho = 2 */
  const double c = cos(0.7), s = sin(0.7), c2 = cos(0.3), s2 = sin(0.3);
  /* rotation Q = Rz(0.7) Rx(0.3) */
  const double Rz[9] = {c, -s, 0, s, c, 0, 0, 0, 1}, Rx[9] = {1, 0, 0, 0, c2, -s2, 0, s2, c2};
  double Q[9];
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++)
      Q[3 * a + b] = Rz[3 * a] * Rx[b] + Rz[3 * a + 1] * Rx[3 + b] + Rz[3 * a + 2] * Rx[6 + b];
  const double lam[3] = {2.0, -1.0, 0.5}, rl[3] = {-0.2 * 2.0 / 4.0, 0.0, -0.2 * 0.5 / 4.0};
  static const int ia[6] = {0, 0, 0, 1, 1, 2}, ib[6] = {0, 1, 2, 1, 2, 2};
  double sig[6], want[6];
  for (int k = 0; k < 6; k++) {
    sig[k] = want[k] = 0.0;
    for (int l = 0; l < 3; l++) {
      sig[k] += Q[3 * ia[k] + l] * lam[l] * Q[3 * ib[k] + l];
      want[k] += Q[3 * ia[k] + l] * rl[l] * Q[3 * ib[k] + l];
    }
  }
  /* S = deviatoric part, P = -tr/3 */
  const double P = -(sig[0] + sig[3] + sig[5]) / 3.0;
  const double S[6] = {sig[0] + P, sig[1], sig[2], sig[3] + P, sig[4], sig[5] + P};
  double R[6];
  gradient_artificial_stress(S, P, 2.0, 0.2, R);
  double e = 0.0;
  for (int k = 0; k < 6; k++) e = fmax(e, fabs(R[k] - want[k]));
  check_le("rotated diagonal tension: |R - Q diag(-eps sigma'/rho^2) Q^T|", e, 1e-14);
}

/* ----------------------------------------------------------------------- 6 */
/** drho/dt of a linear velocity field v = b + A x on n random particles in a
 *  cube (a third of them within one kernel radius of a face), masses and h
 *  varying: plain continuity sum vs CSPM, both through the real loops. */
static void test_cspm_continuity(void) {
  const size_t n = 2000;
  unsigned long long s = 11;
  struct parts p;
  parts_alloc(&p, n);
  const double box[3] = {1.0, 1.0, 1.0};
  double A[9], b[3];
  for (int k = 0; k < 9; k++) A[k] = 2.0 * urand(&s) - 1.0;
  for (int k = 0; k < 3; k++) b[k] = urand(&s);
  const double divA = A[0] + A[4] + A[8];
  for (size_t i = 0; i < n; i++) {
    p.x[i] = 0.05 + 0.9 * urand(&s);
    p.y[i] = 0.05 + 0.9 * urand(&s);
    p.z[i] = 0.05 + 0.9 * urand(&s);
    p.m[i] = 0.5 + urand(&s);
    p.h[i] = 0.07 + 0.05 * urand(&s);
    p.id[i] = (int64_t)i;
    const double x[3] = {p.x[i], p.y[i], p.z[i]};
    double v[3];
    for (int a = 0; a < 3; a++)
      v[a] = b[a] + A[3 * a] * x[0] + A[3 * a + 1] * x[1] + A[3 * a + 2] * x[2];
    p.vpx[i] = v[0], p.vpy[i] = v[1], p.vpz[i] = v[2];
    p.cs[i] = 1.0, p.f_gradh[i] = 1.0, p.balsara[i] = 1.0, p.mat[i] = 0;
  }
  struct space sp;
  space_init(&sp, &p, box, 0, 50, 8);
  space_rebuild(&sp);
  struct space_pair *pairs;
  const size_t np = space_top_pairs(&sp, &pairs);
  for (size_t i = 0; i < n; i++) hydro_density_reset(&p, i);
  for (int c = 0; c < sp.nr_top; c++) density_self_cpu(&p, &sp.cells[c], NULL);
  for (size_t k = 0; k < np; k++)
    density_pair_cpu(&p, &sp.cells[pairs[k].ci], &sp.cells[pairs[k].cj], pairs[k].shift, NULL);
  for (size_t i = 0; i < n; i++) p.rho[i] += p.m[i] * kernel_W(0.0, p.h[i]);

  struct material_table mats;
  make_table(&mats, STRENGTH_ELASTIC);
  struct hydro_props hp = {
      .alpha = 1.0, .beta = 2.0, .continuity = 1, .solids = 1, .gradient_correction = 1};
  double err[2] = {0.0, 0.0}, err_edge[2] = {0.0, 0.0}, err_in[2] = {0.0, 0.0}, scale = 0.0;
  for (size_t i = 0; i < n; i++) scale = fmax(scale, fabs(p.rho[i] * divA));
  for (int pass = 0; pass < 2; pass++) {
    hp.continuity_cspm = pass;
    for (size_t i = 0; i < n; i++) {
      hydro_force_reset(&p, i);
      hydro_gradient_reset(&p, i);
    }
    if (pass) {
      for (int c = 0; c < sp.nr_top; c++) gradient_self_cpu(&p, &sp.cells[c]);
      for (size_t k = 0; k < np; k++)
        gradient_pair_cpu(&p, &sp.cells[pairs[k].ci], &sp.cells[pairs[k].cj], pairs[k].shift);
      for (size_t i = 0; i < n; i++) extra_ghost_part_cpu(&p, i, &hp, &mats);
    }
    for (int c = 0; c < sp.nr_top; c++) force_self_cpu(&p, &sp.cells[c], &hp);
    for (size_t k = 0; k < np; k++)
      force_pair_cpu(&p, &sp.cells[pairs[k].ci], &sp.cells[pairs[k].cj], pairs[k].shift, &hp);
    for (size_t i = 0; i < n; i++) {
      const double e = fabs(p.drho_dt[i] + p.rho[i] * divA) / scale;
      err[pass] = fmax(err[pass], e);
      const double H = kernel_gamma * p.h[i];
      const int edge = fmin(fmin(fmin(p.x[i], p.y[i]), p.z[i]),
                            1.0 - fmax(fmax(p.x[i], p.y[i]), p.z[i])) < 0.05 + H;
      if (edge)
        err_edge[pass] = fmax(err_edge[pass], e);
      else
        err_in[pass] = fmax(err_in[pass], e);
    }
  }
  printf("continuity equation, linear velocity field, N = %zu random particles in a cube:\n", n);
  check_le("CSPM drho/dt: max |drho/dt + rho div v| / max|rho div v|", err[1], 1e-10);
  printf("  %-62s %.3e near a face, %.3e inside\n",
         "plain SPH drho/dt: max |drho/dt + rho div v| / max|rho div v|", err_edge[0], err_in[0]);
  if (!(err[0] > 0.1)) {
    printf("  FAIL: the plain continuity sum should be visibly wrong (> 0.1) on this set\n");
    nfail++;
  }
  material_table_free(&mats);
  free(pairs);
  space_free(&sp);
  parts_free(&p);
}

/* ----------------------------------------------------------------------- 7 */
/** Johnson & Cook (1985) fracture (theory/solids.md E6f) with the 2024-T351
 *  constants of examples/materials.yml (D1 0.13, D2 0.13, D3 -1.5, D4 0.011,
 *  D5 0): the strain at fracture at known points, the accumulation of D to
 *  fracture at exactly eps_f, no strength after it, and the start-up checks. */
static void test_jc_fracture(void) {
  printf("Johnson-Cook fracture:\n");
  const double D1 = 0.13, D2 = 0.13, D3 = -1.5, D4 = 0.011, D5 = 0.0;
  double e = 0.0;
  /* pure shear (s* = 0), reference rate, room temperature: D1 + D2 */
  e = fmax(
      e, fabs(strength_johnson_cook_failure_strain(D1, D2, D3, D4, D5, 1.0, 0.0, 1.0, 0.0) - 0.26));
  /* uniaxial tension (s* = 1/3): D1 + D2 exp(-0.5) */
  const double ef_t = D1 + D2 * exp(-0.5);
  e = fmax(e,
           fabs(strength_johnson_cook_failure_strain(D1, D2, D3, D4, D5, 1.0, 1.0 / 3.0, 1.0, 0.0) -
                ef_t));
  /* rate e^2 times the reference: factor 1 + 2 D4; below the reference: 1 */
  e = fmax(e,
           fabs(strength_johnson_cook_failure_strain(D1, D2, D3, D4, D5, 1.0, 0.0, exp(2.0), 0.0) -
                0.26 * (1.0 + 2.0 * D4)));
  e = fmax(e, fabs(strength_johnson_cook_failure_strain(D1, D2, D3, D4, D5, 1.0, 0.0, 0.01, 0.0) -
                   0.26));
  /* temperature factor 1 + D5 T*, T* clipped to [0, 1] */
  e = fmax(e, fabs(strength_johnson_cook_failure_strain(D1, D2, D3, D4, 0.5, 1.0, 0.0, 1.0, 3.0) -
                   0.26 * 1.5));
  /* a fit with eps_f <= 0 fractures at once (floor 1e-6) */
  e = fmax(e,
           fabs(strength_johnson_cook_failure_strain(-0.5, 0.1, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0) -
                1e-6));
  check_le("strain at fracture at known points", e, 1e-15);

  /* uniaxial tension at the reference rate and temperature: D reaches 1 when
   * the plastic strain reaches eps_f, not before */
  struct material m;
  char msg[256];
  material_init(&m, 0, "al", EOS_LIQUID);
  m.strength = STRENGTH_JOHNSON_COOK;
  m.shear_modulus = 26e9;
  m.jc_A = 265e6, m.jc_B = 426e6, m.jc_C = 0.015, m.jc_m = 1.0, m.jc_n = 0.34;
  m.jc_strain_rate_ref = 1.0, m.T_ref = 293.0, m.T_melt = 775.0, m.specific_heat = 875.0;
  m.jc_D1 = D1, m.jc_D2 = D2, m.jc_D3 = D3, m.jc_D4 = D4, m.jc_D5 = D5;
  const double seq = 300e6, P = -seq / 3.0; /* s* = -P / seq = 1/3 */
  const int n = 1000;
  const double deps = ef_t / n;
  double D = 0.0;
  int steps = 0;
  while (D < 1.0 && steps < 2 * n) {
    D = strength_jc_damage_update(&m, D, deps, seq, P, 2710.0, 0.0, 1.0);
    steps++;
  }
  printf("  fractured after %d of %d increments of eps_f / %d\n", steps, n, n);
  check_le("| steps to fracture - eps_f / d eps_p |", fabs((double)(steps - n)), 1.0);
  check_le("D capped at 1", D - 1.0, 0.0);
  const struct strength_state intact = {0.0, 2710.0, 0.0, 0.1, 1.0, 0.999};
  const struct strength_state broken = {0.0, 2710.0, 0.0, 0.1, 1.0, 1.0};
  const double Y0 = strength_yield(&m, &intact), Y1 = strength_yield(&m, &broken);
  printf("  yield stress at D = 0.999: %.4g Pa, at D = 1: %.4g Pa\n", Y0, Y1);
  check_le("no strength once fractured (D = 1)", Y1, 0.0);
  check_le("full strength before (D < 1): | Y / (A + B eps_p^n) - 1 |",
           fabs(Y0 / (265e6 + 426e6 * pow(0.1, 0.34)) - 1.0), 1e-14);
  m.jc_D1 = m.jc_D2 = 0.0;
  check_le("no fracture without D1, D2", strength_jc_fracture(&m) ? 1.0 : 0.0, 0.0);

  /* start-up checks: fracture needs Johnson-Cook strength; Johnson-Cook with
   * Mie-Grueneisen needs specific_heat (its temperature starts at 0 K) */
  int bad = 0;
  struct material v;
  material_init(&v, 0, "vm", EOS_LIQUID);
  if (material_set(&v, "rho0", 2710.0, msg, sizeof msg) ||
      material_set(&v, "c0", 5000.0, msg, sizeof msg) ||
      material_set(&v, "shear_modulus", 26e9, msg, sizeof msg) ||
      material_set(&v, "yield_stress", 3e8, msg, sizeof msg) ||
      material_set(&v, "jc_D1", 0.13, msg, sizeof msg))
    error_exit("%s", msg);
  v.strength = STRENGTH_VON_MISES;
  if (material_finalize(&v, msg, sizeof msg) == 0) bad++;
  printf("  von Mises with jc_D1: %s\n", msg);
  struct material g;
  material_init(&g, 0, "mg", EOS_MIE_GRUNEISEN);
  if (material_set(&g, "rho0", 2710.0, msg, sizeof msg) ||
      material_set(&g, "c0", 6320.0, msg, sizeof msg) ||
      material_set(&g, "s", 1.337, msg, sizeof msg) ||
      material_set(&g, "Gamma0", 2.1, msg, sizeof msg) ||
      material_set(&g, "cv", 875.0, msg, sizeof msg) ||
      material_set(&g, "shear_modulus", 26e9, msg, sizeof msg) ||
      material_set(&g, "jc_A", 265e6, msg, sizeof msg) ||
      material_set(&g, "T_melt", 775.0, msg, sizeof msg))
    error_exit("%s", msg);
  g.strength = STRENGTH_JOHNSON_COOK;
  if (material_finalize(&g, msg, sizeof msg) == 0) bad++;
  printf("  Mie-Grueneisen + Johnson-Cook without specific_heat: %s\n", msg);
  if (material_set(&g, "specific_heat", 875.0, msg, sizeof msg)) error_exit("%s", msg);
  if (material_finalize(&g, msg, sizeof msg) != 0) bad++;
  /* spall_pressure needs Johnson-Cook fracture */
  if (material_set(&g, "spall_pressure", 1.2e9, msg, sizeof msg)) error_exit("%s", msg);
  if (material_finalize(&g, msg, sizeof msg) == 0) bad++;
  printf("  spall_pressure without fracture: %s\n", msg);
  if (material_set(&g, "jc_D1", 0.13, msg, sizeof msg)) error_exit("%s", msg);
  if (material_finalize(&g, msg, sizeof msg) != 0) bad++;
  check_le("start-up checks reject the three bad materials, accept the good ones", bad, 0.0);
}

int main(int argc, char **argv) {
  (void)argc;
  error_init(argv[0]);
  test_gradient();
  test_jaumann_spin();
  test_yield();
  test_artificial_stress();
  test_cspm_continuity();
  test_jc_fracture();
  printf("%s\n", nfail ? "FAIL" : "PASS");
  return nfail ? 1 : 0;
}
