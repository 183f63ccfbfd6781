/* The time step of one particle (tasks/kick/timestep.h, issue 19 item 2):
 * the one function that the CPU kick, the CUDA kick and the dt_min message
 * call.
 *  - the Courant condition 2 C H / v_sig alone when nothing else limits;
 *  - kick2_part adds ga to a (replacing a in a gravity-only run) and takes
 *    the acceleration criterion of the sum;
 *  - the gravitational criterion sqrt(2 eta eps_i / |ga|) with the
 *    absolute softening, and with eps_i = softening_h_factor h_i when the
 *    softening is tied to h (once applied by the CPU kick alone);
 *  - without hydrodynamics only the gravitational criterion;
 *  - with CSPM continuity the Courant step times sqrt(lambda_min(M)) of a
 *    truncated kernel (M = diag(1, 1, 0.25), rotated: 0.5), none for a
 *    full one (M = I), none without the option or where M is singular;
 *  - without the stress arrays (a GPU run without stress does not hold
 *    them): the kick, the drift and the relative-change criterion as with
 *    zero stress;
 *  - the criteria's names. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tasks/drift/drift.h"
#include "tasks/hydro/kernel.h"
#include "tasks/kick/kick.h"
#include "tasks/kick/timestep.h"
#include "src/materials/material.h"
#include "src/part.h"

#include "tests/helpers/check.h"

static int close_to(double a, double b) {
  return fabs(a - b) <= 1e-14 * fabs(b);
}

/** One particle at rest with h 2, v_sig 1e3 and ga (0, 0, 9.81). */
static void one_particle(struct parts *p) {
  parts_alloc(p, 1);
  p->count = 1;
  p->m[0] = 1.0, p->h[0] = 2.0, p->rho[0] = 1.0, p->mat[0] = 0;
  p->v_sig[0] = 1e3;
  p->gaz[0] = 9.81;
}

int main(void) {
  struct material_table t;
  material_table_init(&t);
  struct hydro_props hp;
  memset(&hp, 0, sizeof hp);
  hp.enabled = 1;
  hp.cfl = 0.2;
  hp.log_max_volume_change = log(1.4);
  const double H = kernel_gamma * 2.0;
  double d[TIMESTEP_NR];

  struct parts p;
  one_particle(&p);
  struct timestep_props tp;
  memset(&tp, 0, sizeof tp);
  tp.hydro = 1;
  const double courant = 2.0 * 0.2 * H / 1e3;
  double dt = timestep_part_criteria(&p, 0, &hp, &t, &tp, d);
  CHECK(close_to(dt, courant) && d[TIMESTEP_COURANT] == dt, "Courant alone: %g (%g)", dt, courant);
  CHECK(d[TIMESTEP_ACCEL] == 1e300 && d[TIMESTEP_GRAVITY] == 1e300, "no acceleration, no gravity");

  /* self-gravity, absolute softening 0.1: a = ga after the kick */
  tp.gravity = 1;
  tp.grav_eps = 0.1;
  tp.grav_eta = 0.025;
  dt = kick2_part(&p, 0, 0.0, &hp, &t, &tp);
  CHECK(p.az[0] == 9.81, "the kick adds ga: az %g", p.az[0]);
  timestep_part_criteria(&p, 0, &hp, &t, &tp, d);
  const double acc = sqrt(2.0 * 0.2 * H / 9.81), grav = sqrt(2.0 * 0.025 * 0.1 / 9.81);
  CHECK(close_to(d[TIMESTEP_ACCEL], acc), "acceleration criterion %g (%g)", d[TIMESTEP_ACCEL], acc);
  CHECK(close_to(d[TIMESTEP_GRAVITY], grav), "gravity, eps: %g (%g)", d[TIMESTEP_GRAVITY], grav);
  CHECK(dt == fmin(courant, fmin(acc, grav)), "the smallest: %g", dt);

  /* softening tied to h: eps_i = 0.5 h_i = 1 */
  tp.grav_eps = 0.0;
  tp.grav_h_factor = 0.5;
  timestep_part_criteria(&p, 0, &hp, &t, &tp, d);
  const double grav_h = sqrt(2.0 * 0.025 * 1.0 / 9.81);
  CHECK(close_to(d[TIMESTEP_GRAVITY], grav_h), "gravity, h_factor: %g (%g)", d[TIMESTEP_GRAVITY],
        grav_h);
  parts_free(&p);

  /* gravity only: a is ga alone, no hydrodynamic criterion */
  one_particle(&p);
  p.az[0] = 5.0; /* a stale hydrodynamic acceleration */
  tp.hydro = 0;
  dt = kick2_part(&p, 0, 0.0, &hp, &t, &tp);
  CHECK(p.az[0] == 9.81, "gravity only: az %g (ga alone)", p.az[0]);
  CHECK(close_to(dt, grav_h), "gravity only: dt %g (%g)", dt, grav_h);
  timestep_part_criteria(&p, 0, &hp, &t, &tp, d);
  CHECK(d[TIMESTEP_COURANT] == 1e300 && d[TIMESTEP_ACCEL] == 1e300, "no hydrodynamic criterion");
  parts_free(&p);

  /* CSPM continuity: a truncated kernel's M, diag(1, 1, 0.25) rotated by
   * 45 degrees about x (its eigenvalues unchanged): sqrt(0.25) = 0.5 */
  one_particle(&p);
  tp.hydro = 1;
  tp.gravity = 0;
  p.gmxx[0] = 1.0, p.gmyy[0] = p.gmzz[0] = 0.625, p.gmyz[0] = 0.375;
  timestep_part_criteria(&p, 0, &hp, &t, &tp, d);
  CHECK(d[TIMESTEP_CSPM] == 1e300, "no CSPM criterion without continuity_correction");
  hp.continuity_cspm = 1;
  dt = timestep_part_criteria(&p, 0, &hp, &t, &tp, d);
  CHECK(close_to(d[TIMESTEP_CSPM], 0.5 * courant) && dt == d[TIMESTEP_CSPM],
        "CSPM, lambda_min 0.25: %g (%g)", d[TIMESTEP_CSPM], 0.5 * courant);
  p.gmyy[0] = p.gmzz[0] = 1.0, p.gmyz[0] = 0.0;
  dt = timestep_part_criteria(&p, 0, &hp, &t, &tp, d);
  CHECK(close_to(d[TIMESTEP_CSPM], courant) && close_to(dt, courant), "CSPM, full kernel: %g (%g)",
        d[TIMESTEP_CSPM], courant);
  p.gmyy[0] = p.gmzz[0] = p.gmyz[0] = 0.0; /* singular: the uncorrected divergence */
  timestep_part_criteria(&p, 0, &hp, &t, &tp, d);
  CHECK(close_to(d[TIMESTEP_CSPM], courant), "CSPM, singular M: no limit (%g)", d[TIMESTEP_CSPM]);
  hp.continuity_cspm = 0;
  parts_free(&p);

  /* a run without stress holds no stress arrays (parts_drop, gpu_set_absent): the
   * kick, the drift and the relative-change criterion skip them and give
   * what zero stress gives, field for field */
  {
    struct parts a, b;
    one_particle(&a);
    one_particle(&b);
    hp.max_rel_change = 0.1;
    double *keep[24];
    double **slot[24] = {&b.Sxx,  &b.Sxy,  &b.Sxz,  &b.Syy,  &b.Syz,  &b.Szz,  &b.Spxx, &b.Spxy,
                         &b.Spxz, &b.Spyy, &b.Spyz, &b.Spzz, &b.dSxx, &b.dSxy, &b.dSxz, &b.dSyy,
                         &b.dSyz, &b.dSzz, &b.Rxx,  &b.Rxy,  &b.Rxz,  &b.Ryy,  &b.Ryz,  &b.Rzz};
    for (int k = 0; k < 24; k++) keep[k] = *slot[k], *slot[k] = NULL;
    for (int q = 0; q < 2; q++) {
      struct parts *r = q ? &b : &a;
      r->ax[0] = 3.0, r->du_dt[0] = -2.0, r->u[0] = r->up[0] = 10.0, r->cs[0] = 5.0;
      r->drho_dt[0] = 0.01, r->div_v[0] = 1e-3;
    }
    const double dta = kick2_part(&a, 0, 0.5, &hp, &t, &tp),
                 dtb = kick2_part(&b, 0, 0.5, &hp, &t, &tp);
    drift_part(&a, 0, 0.5, 0.0, 1e30, 0);
    drift_part(&b, 0, 0.5, 0.0, 1e30, 0);
    CHECK(dta == dtb && a.vx[0] == b.vx[0] && a.u[0] == b.u[0] && a.x[0] == b.x[0] &&
              a.h[0] == b.h[0] && a.vpx[0] == b.vpx[0] && a.up[0] == b.up[0],
          "no stress arrays: kick, drift and time step as with zero stress (dt %g, %g)", dta, dtb);
    timestep_part_criteria(&b, 0, &hp, &t, &tp, d);
    CHECK(d[TIMESTEP_RELATIVE] < 1e300, "no stress arrays: the relative-change criterion %g",
          d[TIMESTEP_RELATIVE]);
    for (int k = 0; k < 24; k++) *slot[k] = keep[k];
    hp.max_rel_change = 0.0;
    parts_free(&a);
    parts_free(&b);
  }

  CHECK(strstr(timestep_criterion_name(TIMESTEP_COURANT), "Courant") != NULL, "Courant's name");
  CHECK(strstr(timestep_criterion_name(TIMESTEP_GRAVITY), "gravitational") != NULL, "gravity's");
  CHECK(strcmp(timestep_criterion_name(TIMESTEP_NR), "none") == 0, "no criterion: none");
  material_table_free(&t);
  printf("test_timestep: %d checks, %d failed\n", checks, failures);
  return failures ? 1 : 0;
}
