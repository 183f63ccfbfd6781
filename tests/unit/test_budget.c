/* The pieces of the conservation budget that a run cannot show alone
 * (theory/sph.md, "Conservation budget"; issue 17):
 *  - the pressure floor P_min of a material: 0 by default without strength,
 *    -inf (tension) with strength, applied by material_eos with c^2 = 0
 *    (so c = cs_min) where it acts, and settable per material;
 *  - the kick's floor on u acts only on particles whose material needs
 *    u >= 0 (ideal gas, tables: PART_U_FLOOR, set from material.u_floor),
 *    and counts the energy it adds in e_clamp; other particles keep an
 *    undershoot below 0;
 *  - the kick's radial return brings a stress outside the yield surface
 *    back onto it and counts the plastic work Y d eps_p / rho;
 *  - a particle leaving the open box at a rebuild of the kick-drift-kick
 *    step takes the energy of its state of now (the drift's predicted
 *    velocity and energy, the potential moved with it since its last
 *    evaluation) and the momentum of its step's middle (space.c). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tasks/kick/kick.h"
#include "src/materials/material.h"
#include "src/part.h"
#include "src/space.h"
#include "src/timeline.h"
#include "tasks/gravity/gravity_cpu.h"
#include "tasks/task_families.h"

#include "tests/helpers/check.h"

/** Tillotson granite of the library (SWIFT id 101), without strength. */
static void granite(struct material *m) {
  material_init(m, 101, "granite", EOS_TILLOTSON);
  const char *keys[] = {"rho0", "A", "B", "E0", "Eiv", "Ecv", "a", "b", "alpha", "beta"};
  const double vals[] = {2680, 18e9, 18e9, 16e6, 3.5e6, 18e6, 0.5, 1.3, 5, 5};
  char msg[256];
  for (int k = 0; k < 10; k++)
    CHECK(material_set(m, keys[k], vals[k], msg, sizeof msg) == 0, "set %s: %s", keys[k], msg);
}

static void test_pressure_floor(void) {
  char msg[256];
  struct material fluid, solid, asked;
  granite(&fluid);
  CHECK(material_finalize(&fluid, msg, sizeof msg) == 0, "%s", msg);
  CHECK(fluid.P_min == 0.0, "P_min of a strengthless material: %g (must be 0)", fluid.P_min);
  double P, cs;
  material_eos(&fluid, 0.8 * 2680, 0.0, &P, &cs); /* cold expanded: T1 < 0 */
  CHECK(P == 0.0 && cs == fluid.cs_min, "floor: P %g (0), cs %g (cs_min %g)", P, cs, fluid.cs_min);
  granite(&solid);
  solid.strength = STRENGTH_VON_MISES;
  CHECK(material_set(&solid, "shear_modulus", 22e9, msg, sizeof msg) == 0, "%s", msg);
  CHECK(material_set(&solid, "yield_stress", 1e9, msg, sizeof msg) == 0, "%s", msg);
  CHECK(material_finalize(&solid, msg, sizeof msg) == 0, "%s", msg);
  CHECK(isinf(solid.P_min) && solid.P_min < 0, "P_min with strength: %g (must be -inf)",
        solid.P_min);
  material_eos(&solid, 0.8 * 2680, 0.0, &P, &cs);
  const double T1 = 18e9 * (0.8 - 1) + 18e9 * 0.04; /* A mu + B mu^2 at u = 0 */
  CHECK(fabs(P - T1) <= 1e-12 * fabs(T1), "tension of a solid: P %g (T1 %g)", P, T1);
  granite(&asked);
  CHECK(material_set(&asked, "P_min", -1e8, msg, sizeof msg) == 0, "%s", msg);
  CHECK(material_finalize(&asked, msg, sizeof msg) == 0, "%s", msg);
  material_eos(&asked, 0.8 * 2680, 0.0, &P, &cs);
  CHECK(P == -1e8, "P_min -1e8 asked: P %g", P);
  CHECK(fluid.u_floor == 0, "Tillotson keeps u < 0");
  struct material gas;
  material_init(&gas, 0, "gas", EOS_IDEAL_GAS);
  CHECK(material_set(&gas, "gamma", 5.0 / 3.0, msg, sizeof msg) == 0, "%s", msg);
  CHECK(material_finalize(&gas, msg, sizeof msg) == 0, "%s", msg);
  CHECK(gas.u_floor == 1, "the ideal gas needs u >= 0");
}

static void test_u_floor(void) {
  struct parts p;
  parts_alloc(&p, 2);
  p.count = 2;
  for (int i = 0; i < 2; i++) p.u[i] = 1.0, p.du_dt[i] = -10.0;
  p.flags[0] = PART_U_FLOOR; /* an ideal gas */
  p.flags[1] = 0;            /* Tillotson */
  kick_part(&p, 0, 1.0);
  kick_part(&p, 1, 1.0);
  CHECK(p.u[0] == 0.5 && p.e_clamp[0] == 9.5,
        "floored: u %g (0.5), e_clamp %g (9.5 = 0.5 - (1 - 10))", p.u[0], p.e_clamp[0]);
  CHECK(p.u[1] == -9.0 && p.e_clamp[1] == 0.0, "not floored: u %g (-9), e_clamp %g (0)", p.u[1],
        p.e_clamp[1]);
  parts_free(&p);
}

static void test_kick_return(void) {
  char msg[256];
  struct material_table t;
  material_table_init(&t);
  struct material m;
  granite(&m);
  m.id = 0;
  m.strength = STRENGTH_VON_MISES;
  CHECK(material_set(&m, "shear_modulus", 22e9, msg, sizeof msg) == 0, "%s", msg);
  CHECK(material_set(&m, "yield_stress", 1e8, msg, sizeof msg) == 0, "%s", msg);
  CHECK(material_finalize(&m, msg, sizeof msg) == 0, "%s", msg);
  material_table_add(&t, &m);
  struct hydro_props hp;
  memset(&hp, 0, sizeof hp);
  hp.solids = 1;
  hp.cfl = 0.2;
  hp.log_max_volume_change = log(1.4);
  struct parts p;
  parts_alloc(&p, 1);
  p.count = 1;
  p.m[0] = 1.0, p.h[0] = 1.0, p.rho[0] = 2680.0, p.u[0] = p.up[0] = 0.0, p.mat[0] = 0;
  p.P[0] = 0.0, p.v_sig[0] = 1e3;
  /* a trial stress 10% above yield after the kick: pure shear xy,
   * sqrt(3 J2) = sqrt(3) |S_xy| */
  const double Sxy = 1.1e8 / sqrt(3.0);
  p.Sxy[0] = 0.0, p.dSxy[0] = Sxy; /* kicked by dt 1 */
  struct timestep_props tp;
  memset(&tp, 0, sizeof tp);
  tp.hydro = 1;
  kick2_part(&p, 0, 1.0, &hp, &t, &tp);
  const double seq = sqrt(3.0) * fabs(p.Sxy[0]);
  CHECK(fabs(seq - 1e8) <= 1e-6, "after the kick sqrt(3 J2) = %.9g (Y = 1e8)", seq);
  CHECK(p.Spxy[0] == p.Sxy[0], "the predicted stress is the returned one");
  const double deps = (1.1e8 - 1e8) / (3.0 * 22e9);
  CHECK(fabs(p.eps_p[0] - deps) <= 1e-12 * deps, "plastic strain %g (%g)", p.eps_p[0], deps);
  CHECK(fabs(p.w_plastic[0] - 1e8 * deps / 2680.0) <= 1e-12 * p.w_plastic[0],
        "plastic work %g (Y d eps_p / rho = %g)", p.w_plastic[0], 1e8 * deps / 2680.0);
  parts_free(&p);
}

/** One particle inside a unit box, one outside it (m 2, v (100, 0, 0)
 *  at its step's middle, vp (110, 0, 0) and up 6 predicted, u 5, pot -50,
 *  g (-1, 0.5, 0)): what the rebuild removes, with the clock c. */
static struct budget_removed removed_with(const struct space_clock *c, int bin) {
  const double L[3] = {1.0, 1.0, 1.0};
  struct parts p;
  parts_alloc(&p, 2);
  for (size_t i = 0; i < 2; i++) {
    p.x[i] = i ? 1.5 : 0.5;
    p.y[i] = p.z[i] = 0.5;
    p.h[i] = 0.1;
    p.m[i] = 2.0;
    p.id[i] = (int64_t)i + 1;
    p.vx[i] = 100.0;
    p.vpx[i] = 110.0;
    p.u[i] = 5.0;
    p.up[i] = 6.0;
    p.pot[i] = -50.0;
    p.gax[i] = -1.0;
    p.gay[i] = 0.5;
    p.time_bin[i] = bin;
  }
  struct space s;
  space_init(&s, &p, L, 0, 8, 4);
  s.clock = *c;
  CHECK(space_rebuild(&s) == 1, "one particle outside the box removed");
  const struct budget_removed r = s.removed;
  space_free(&s);
  parts_free(&p);
  return r;
}

static void test_removed_now(void) {
  /* not in a step (the first rebuild, rk2, pc): the fields as they are */
  const struct space_clock none = {0, 0.0, NULL, 0};
  struct budget_removed r = removed_with(&none, 0);
  double E = 2.0 * (0.5 * 100.0 * 100.0 + 5.0 - 50.0);
  CHECK(fabs(r.E - E) <= 1e-12 * fabs(E), "E removed outside a step %.17g (%.17g)", r.E, E);
  /* the global step, dt 4 ago: 1/2 vp^2 + up + pot - dt g . v */
  const struct space_clock glob = {1, 4.0, NULL, 0};
  r = removed_with(&glob, 0);
  E = 2.0 * (0.5 * 110.0 * 110.0 + 6.0 - 50.0 + 4.0 * 100.0);
  CHECK(fabs(r.E - E) <= 1e-12 * fabs(E), "E removed in the global step %.17g (%.17g)", r.E, E);
  CHECK(r.p[0] == 200.0 && r.p[1] == 0.0 && r.p[2] == 0.0,
        "momentum removed (%g, %g, %g): that of the step's middle (200, 0, 0)", r.p[0], r.p[1],
        r.p[2]);
  /* time bins: bin 3 (8 ticks), now tick 13: its step began at tick 8 */
  const struct timeline tl = timeline_make(0.0, 1.0, 1.0);
  const struct space_clock bins = {1, 99.0, &tl, 13};
  r = removed_with(&bins, 3);
  const double since = timeline_time(&tl, 13) - timeline_time(&tl, 8);
  E = 2.0 * (0.5 * 110.0 * 110.0 + 6.0 - 50.0 + since * 100.0);
  CHECK(since > 0.0 && fabs(r.E - E) <= 1e-12 * fabs(E),
        "E removed in bins %.17g (%.17g, %g since its step began)", r.E, E, since);
  /* at the end of its step (tick 16): the whole step, 8 ticks */
  const struct space_clock end = {1, 99.0, &tl, 16};
  r = removed_with(&end, 3);
  const double step = timeline_time(&tl, 16) - timeline_time(&tl, 8);
  E = 2.0 * (0.5 * 110.0 * 110.0 + 6.0 - 50.0 + step * 100.0);
  CHECK(fabs(r.E - E) <= 1e-12 * fabs(E), "E removed at the end of its step %.17g (%.17g)", r.E, E);
}

/** Particles removed together: the space keeps them (x, y, z, m, h) for
 *  the potential energy of their pairs, which their m pot counts twice
 *  (engine.c subtracts it once): two outside a unit box, 3 apart, m 2 and
 *  5, one inside. */
static void test_removed_pairs(void) {
  const double L[3] = {1.0, 1.0, 1.0};
  struct parts p;
  parts_alloc(&p, 3);
  const double x[3] = {0.5, 2.0, 5.0}, m[3] = {1.0, 2.0, 5.0};
  for (size_t i = 0; i < 3; i++) {
    p.x[i] = x[i];
    p.y[i] = p.z[i] = 0.5;
    p.h[i] = 0.1;
    p.m[i] = m[i];
    p.id[i] = (int64_t)i + 1;
  }
  struct space s;
  space_init(&s, &p, L, 0, 8, 4);
  CHECK(space_rebuild(&s) == 2, "two particles removed");
  CHECK(s.nr_gone == 2, "the space kept %zu removed particles (2)", s.nr_gone);
  double xs = 0.0, ms = 0.0;
  for (size_t k = 0; k < s.nr_gone; k++) {
    xs += s.gone[5 * k];
    ms += s.gone[5 * k + 3];
  }
  CHECK(xs == 7.0 && ms == 7.0, "kept x %g (7), m %g (7)", xs, ms);
  struct gravity_props gp;
  gravity_props_set(&gp, 1.0, 0.5, 0.1, GRAVITY_SOFTENING_SPLINE, 3);
  const double U = gravity_pairs_energy(s.gone, s.nr_gone, &gp);
  CHECK(fabs(U + 2.0 * 5.0 / 3.0) <= 1e-14, "their pair's energy %.17g (-G m1 m2 / r = %.17g)", U,
        -10.0 / 3.0);
  space_free(&s);
  parts_free(&p);
}

int main(void) {
  test_pressure_floor();
  test_removed_pairs();
  test_removed_now();
  test_u_floor();
  test_kick_return();
  printf("test_budget: %d checks, %d failed\n", checks, failures);
  return failures ? 1 : 0;
}
