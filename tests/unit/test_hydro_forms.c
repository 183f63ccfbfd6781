/* The symmetric CPU loops (cell self and pair tasks) against the gather form
 * of the same pair interactions evaluated by brute force over all pairs:
 * density sums and forces must agree to round-off, and the symmetric forces
 * must conserve linear momentum to round-off (theory/architecture.md, rule 3).
 * Also with one top-level cell (cells paired with their own periodic
 * images) and with leaves of up to 3000 particles (Scheduler:cpu_leaf_size).
 * Random particles with h varying by a factor 4, periodic and open boxes;
 * one case mixes fluid and solid particles (some in tension) under
 * SPH:fluid_solid_interface.
 *
 * Then the fluid-solid interface on a lattice (theory/fluids.md, F6 and the
 * density jump): a uniform pressure P = 1 across the interface of a liquid
 * (rho 1) and a solid (rho 2.7), equal volumes: with the interface treatment
 * a particle on either side of it feels no force (to 1e-12 of the
 * scale P/rho sum_j V_j |grad W|); without it (standard form) it feels
 * -P (rho_b - rho_a)^2 / (rho_a^2 rho_b) sum_{j other phase} V_j grad_i W_ij
 * to 1e-12 relative. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tasks/density/density_cpu.h"
#include "src/error.h"
#include "tasks/force/force_cpu.h"
#include "tasks/hydro_parts.h"
#include "tasks/hydro/kernel.h"
#include "src/space.h"

static double urand(unsigned long long *s) {
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

/** Minimum-image separation x_i - x_j. */
static void sep(const struct parts *p, size_t i, size_t j, const double box[3], int periodic,
                double dx[3]) {
  const double a[3] = {p->x[i] - p->x[j], p->y[i] - p->y[j], p->z[i] - p->z[j]};
  for (int k = 0; k < 3; k++) {
    dx[k] = a[k];
    if (periodic) dx[k] -= box[k] * round(a[k] / box[k]);
  }
}

/** One configuration of the force loop. */
struct forms_case {
  const char *name; /**< printed */
  int solids;       /**< deviatoric stress terms on, with random S */
  int form;         /**< HYDRO_MOMENTUM_* */
  double as_eps;    /**< artificial stress (random R) */
  double xsph;      /**< XSPH sums */
  int fsi;          /**< SPH:fluid_solid_interface, random phases, a third in tension */
};

/** check() with the top-level grid at most max_top cells a side and the
 *  loops' leaves up to leaf_max particles (Scheduler:cpu_leaf_size). */
static int check_at(int periodic, size_t n, unsigned long long seed, const struct forms_case *fc,
                    int max_top, int leaf_max) {
  unsigned long long s = seed;
  struct parts p;
  parts_alloc(&p, n);
  const double box[3] = {1.0, 1.0, 1.0};
  for (size_t i = 0; i < n; i++) {
    p.x[i] = 0.05 + 0.9 * urand(&s);
    p.y[i] = 0.05 + 0.9 * urand(&s);
    p.z[i] = 0.05 + 0.9 * urand(&s);
    if (periodic) p.x[i] = urand(&s), p.y[i] = urand(&s), p.z[i] = urand(&s);
    p.vpx[i] = urand(&s) - 0.5;
    p.vpy[i] = urand(&s) - 0.5;
    p.vpz[i] = urand(&s) - 0.5;
    p.m[i] = 0.5 + urand(&s);
    p.h[i] = 0.03 + 0.09 * urand(&s);
    p.id[i] = (int64_t)i;
    p.flags[i] = (fc->fsi && urand(&s) < 0.5) ? PART_SOLID : 0;
  }
  struct space sp;
  cell_loop_leaf_max = leaf_max;
  space_init(&sp, &p, box, periodic, 50, max_top);
  space_rebuild(&sp);
  struct space_pair *pairs;
  const size_t np = space_top_pairs(&sp, &pairs);

  /* symmetric cell loops */
  for (size_t i = 0; i < n; i++) hydro_density_reset(&p, i);
  for (int c = 0; c < sp.nr_top; c++) density_self_cpu(&p, &sp.cells[c], NULL);
  for (size_t k = 0; k < np; k++)
    density_pair_cpu(&p, &sp.cells[pairs[k].ci], &sp.cells[pairs[k].cj], pairs[k].shift, NULL);

  /* gather form by brute force */
  int fail = 0;
  double worst = 0.0;
  for (size_t i = 0; i < n; i++) {
    struct density_acc a = {0, 0, 0, 0, 0, {0, 0, 0}};
    const double Hi = kernel_gamma * p.h[i];
    for (size_t j = 0; j < n; j++) {
      if (j == i) continue;
      double dx[3];
      sep(&p, i, j, box, periodic, dx);
      const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
      if (r2 >= Hi * Hi) continue;
      const double dv[3] = {p.vpx[i] - p.vpx[j], p.vpy[i] - p.vpy[j], p.vpz[i] - p.vpz[j]};
      density_iact(r2, dx, 1.0 / p.h[i], p.m[j], dv, &a);
    }
    const double got[3] = {p.rho[i], p.wcount[i], p.div_v[i]};
    const double want[3] = {a.rho, a.wcount, a.div_v};
    const double scale[3] = {fabs(a.rho) + 1e-300, fabs(a.wcount) + 1e-300, fabs(a.rho) / p.h[i]};
    for (int k = 0; k < 3; k++) {
      const double e = fabs(got[k] - want[k]) / scale[k];
      if (e > worst) worst = e;
    }
  }
  printf(
      "%s box, N = %zu, %d top-level cells a side at most, leaves up to %d: density, "
      "symmetric vs gather: worst relative difference %.3e\n",
      periodic ? "periodic" : "open", n, max_top, leaf_max > 50 ? leaf_max : 50, worst);
  if (worst > 1e-12) fail = 1;

  /* a pressure field and the force loops */
  struct hydro_props hp = {.alpha = 1.5, .beta = 3.0, .alpha_u = 1.0, .balsara = 1};
  hp.solids = fc->solids;
  hp.momentum_form = fc->form;
  hp.as_eps = fc->as_eps;
  hp.as_n = 4.0;
  hp.as_wdp_inv = 1.0 / kernel_W(1.0 / 1.2348, 1.0);
  hp.xsph = fc->xsph;
  hp.fluid_solid_interface = fc->fsi;
  for (size_t i = 0; i < n; i++) {
    p.rho[i] += p.m[i] * kernel_W(0.0, p.h[i]);
    p.up[i] = 1.0 + urand(&s);
    p.P[i] = (2.0 / 3.0) * p.rho[i] * p.up[i];
    p.cs[i] = sqrt((5.0 / 3.0) * p.P[i] / p.rho[i]);
    if (fc->fsi && urand(&s) < 0.33) p.P[i] = -p.P[i]; /* tension (cut across the interface) */
    p.f_gradh[i] = 0.8 + 0.4 * urand(&s);
    p.balsara[i] = urand(&s);
    if (fc->solids) {
      p.Spxx[i] = urand(&s) - 0.5, p.Spxy[i] = urand(&s) - 0.5, p.Spxz[i] = urand(&s) - 0.5;
      p.Spyy[i] = urand(&s) - 0.5, p.Spyz[i] = urand(&s) - 0.5, p.Spzz[i] = -p.Spxx[i] - p.Spyy[i];
    }
    if (fc->as_eps > 0.0) {
      p.Rxx[i] = -urand(&s), p.Rxy[i] = 0.1 * urand(&s), p.Rxz[i] = 0.1 * urand(&s);
      p.Ryy[i] = -urand(&s), p.Ryz[i] = 0.1 * urand(&s), p.Rzz[i] = -urand(&s);
    }
    hydro_force_reset(&p, i);
  }
  for (int c = 0; c < sp.nr_top; c++) force_self_cpu(&p, &sp.cells[c], &hp);
  for (size_t k = 0; k < np; k++)
    force_pair_cpu(&p, &sp.cells[pairs[k].ci], &sp.cells[pairs[k].cj], pairs[k].shift, &hp);
  worst = 0.0;
  double mom[3] = {0, 0, 0}, mom_abs = 0.0, edot = 0.0, edot_abs = 0.0;
  for (size_t i = 0; i < n; i++) {
    struct force_acc a;
    force_acc_zero(&a);
    struct force_in in_i, in_j;
    hydro_force_load(&p, i, &in_i, hp.solids);
    for (size_t j = 0; j < n; j++) {
      if (j == i) continue;
      double dx[3];
      sep(&p, i, j, box, periodic, dx);
      const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
      const double H = kernel_gamma * fmax(p.h[i], p.h[j]);
      if (r2 >= H * H) continue;
      hydro_force_load(&p, j, &in_j, hp.solids);
      const double dv[3] = {p.vpx[i] - p.vpx[j], p.vpy[i] - p.vpy[j], p.vpz[i] - p.vpz[j]};
      force_iact(r2, dx, dv, &in_i, &in_j, &hp, &a);
    }
    const double amag = sqrt(a.a[0] * a.a[0] + a.a[1] * a.a[1] + a.a[2] * a.a[2]) + 1e-300;
    const double got[3] = {p.ax[i], p.ay[i], p.az[i]};
    for (int k = 0; k < 3; k++) {
      const double e = fabs(got[k] - a.a[k]) / amag;
      if (e > worst) worst = e;
    }
    const double e = fabs(p.du_dt[i] - a.du_dt) / (fabs(a.du_dt) + amag * p.h[i]);
    if (e > worst) worst = e;
    const double xs[3] = {p.xsphx[i], p.xsphy[i], p.xsphz[i]};
    const double xsn = fabs(a.xsph[0]) + fabs(a.xsph[1]) + fabs(a.xsph[2]) + 1e-300;
    for (int k = 0; k < 3; k++)
      if (fabs(xs[k] - a.xsph[k]) / xsn > worst) worst = fabs(xs[k] - a.xsph[k]) / xsn;
    mom[0] += p.m[i] * p.ax[i];
    mom[1] += p.m[i] * p.ay[i];
    mom[2] += p.m[i] * p.az[i];
    mom_abs += p.m[i] * amag;
    /* energy: sum m (v.a + du/dt) is zero for the conservative terms */
    edot += p.m[i] * (p.vpx[i] * p.ax[i] + p.vpy[i] * p.ay[i] + p.vpz[i] * p.az[i] + p.du_dt[i]);
    edot_abs += p.m[i] * (fabs(p.du_dt[i]) + amag);
  }
  const double mom_rel = sqrt(mom[0] * mom[0] + mom[1] * mom[1] + mom[2] * mom[2]) / mom_abs;
  printf("  force [%s], symmetric vs gather: worst relative difference %.3e\n", fc->name, worst);
  printf("  |sum m a| / sum m |a| = %.3e, |dE/dt| / sum m (|a| + |du/dt|) = %.3e\n", mom_rel,
         fabs(edot) / edot_abs);
  if (worst > 1e-12) fail = 1;
  if (mom_rel > 1e-13) fail = 1;
  if (fabs(edot) / edot_abs > 1e-12) fail = 1;
  free(pairs);
  space_free(&sp);
  parts_free(&p);
  return fail;
}

/** The default layout: at most 8 top-level cells a side, the tree's leaves. */
static int check(int periodic, size_t n, unsigned long long seed, const struct forms_case *fc) {
  return check_at(periodic, n, seed, fc, 8, 0);
}

/** The acceleration of particle i (gather form) on a lattice of spacing 1,
 *  solid below z = 0 (rho 2.7), liquid above (rho 1), every volume 1, P = 1,
 *  at rest; and sum_{j other phase} V_j grad_i W_ij in g_other. */
static void lattice_accel(int zi, int fsi, double a[3], double g_other[3], double *scale) {
  const int L = 6;
  const double rho_s = 2.7, rho_f = 1.0, h = 1.2348;
  struct hydro_props hp = {.alpha = 1.5, .beta = 3.0, .balsara = 1};
  hp.solids = 1;
  hp.fluid_solid_interface = fsi;
  struct force_in in_i, in_j;
  struct force_in *ins[2] = {&in_i, &in_j};
  for (int k = 0; k < 2; k++) {
    struct force_in *in = ins[k];
    in->h_inv = 1.0 / h, in->h = h, in->P = 1.0, in->cs = in->cl = 1.0, in->u = 1.0;
    in->f = 1.0, in->balsara = 1.0;
    for (int c = 0; c < 6; c++) in->S[c] = in->R[c] = 0.0;
  }
  const double zc = zi + 0.5; /* layers at z = +-0.5, +-1.5, ... */
  in_i.solid = zc < 0.0;
  in_i.rho = in_i.solid ? rho_s : rho_f;
  in_i.m = in_i.rho;
  struct force_acc acc;
  force_acc_zero(&acc);
  const double dv[3] = {0, 0, 0};
  const double H = kernel_gamma * h;
  g_other[0] = g_other[1] = g_other[2] = 0.0;
  *scale = 0.0;
  for (int x = -L; x <= L; x++)
    for (int y = -L; y <= L; y++)
      for (int z = -L; z < L; z++) {
        const double dx[3] = {-x, -y, zc - (z + 0.5)};
        const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
        if (r2 <= 0.0 || r2 >= H * H) continue;
        in_j.solid = z + 0.5 < 0.0;
        in_j.rho = in_j.solid ? rho_s : rho_f;
        in_j.m = in_j.rho;
        force_iact(r2, dx, dv, &in_i, &in_j, &hp, &acc);
        double w, w_dr, w_dh;
        kernel_eval_r(sqrt(r2), 1.0 / h, &w, &w_dr, &w_dh);
        for (int k = 0; k < 3; k++) {
          const double g = w_dr * dx[k] / sqrt(r2);
          if (in_j.solid != in_i.solid) g_other[k] += g;
          *scale += fabs(g) / in_i.rho;
        }
      }
  for (int k = 0; k < 3; k++) a[k] = acc.a[k];
}

/** Theory/fluids.md F6: no force from a uniform pressure across the
 *  interface with the treatment, the standard form's spurious force without. */
static int check_interface_lattice(void) {
  int fail = 0;
  for (int zi = -2; zi <= 1; zi++) {
    double a_on[3], a_off[3], g[3], scale;
    lattice_accel(zi, 1, a_on, g, &scale);
    lattice_accel(zi, 0, a_off, g, &scale);
    const double rho_a = zi < 0 ? 2.7 : 1.0, rho_b = zi < 0 ? 1.0 : 2.7;
    const double c = -(rho_b - rho_a) * (rho_b - rho_a) / (rho_a * rho_a * rho_b);
    double e_on = 0.0, e_off = 0.0, want_n = 0.0;
    for (int k = 0; k < 3; k++) {
      e_on = fmax(e_on, fabs(a_on[k]) / scale);
      e_off = fmax(e_off, fabs(a_off[k] - c * g[k]));
      want_n = fmax(want_n, fabs(c * g[k]));
    }
    const int adjacent = zi == -1 || zi == 0;
    printf(
        "interface lattice, layer z = %+.1f: with the treatment |a|/scale = %.2e; standard "
        "form a_z = %+.6f, formula %+.6f (rel. diff %.1e)\n",
        zi + 0.5, e_on, a_off[2], c * g[2], want_n > 0.0 ? e_off / want_n : e_off);
    if (e_on > 1e-12) fail = 1;
    if (want_n > 0.0 ? e_off / want_n > 1e-12 : e_off > 1e-12 * scale) fail = 1;
    if (adjacent && !(fabs(a_off[2]) > 1e-3 * scale)) fail = 1; /* the spurious force exists */
  }
  return fail;
}

int main(int argc, char **argv) {
  (void)argc;
  error_init(argv[0]);
  int fail = 0;
  const struct forms_case cases[] = {
      {"hydro", 0, HYDRO_MOMENTUM_STANDARD, 0.0, 0.0, 0},
      {"solid, standard form, artificial stress, XSPH", 1, HYDRO_MOMENTUM_STANDARD, 0.2, 0.5, 0},
      {"solid, symmetric form, artificial stress", 1, HYDRO_MOMENTUM_SYMMETRIC, 0.2, 0.0, 0},
      {"fluid and solid, fluid_solid_interface, tension", 1, HYDRO_MOMENTUM_STANDARD, 0.0, 0.0, 1},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    fail |= check(1, 3000, 1 + 2 * k, &cases[k]);
    fail |= check(0, 3000, 2 + 2 * k, &cases[k]);
  }
  /* the leaf loops' other paths (theory/neighbours.md, "The neighbours'
   * sums in a cache"): a periodic box of one top-level cell, whose cells
   * pair with their own images (the arrays updated directly), and leaves
   * of up to 3000 particles (a self leaf beyond the cache, pair leaves in
   * several blocks) */
  fail |= check_at(1, 3000, 21, &cases[0], 1, 3000); /* one leaf, paired with its images */
  fail |= check_at(1, 3000, 22, &cases[1], 1, 3000);
  fail |= check_at(0, 6000, 23, &cases[0], 2, 6000); /* leaves of ~750: two blocks */
  fail |= check_at(0, 3000, 24, &cases[1], 2, 3000); /* leaves of ~375, cached */
  fail |= check_interface_lattice();
  printf("%s\n", fail ? "FAIL" : "PASS");
  return fail;
}
