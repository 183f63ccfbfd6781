/* CPU against GPU on the same particles, every task family of the FORCE
 * phase (theory/architecture.md, rule 9): density sums (rho, neighbour number,
 * div v), the iterated smoothing lengths, pressure and sound speed from the
 * EOS, the accelerations, du/dt, the signal velocity, the kicked velocities and
 * energies and the new time steps; with solids the corrected velocity
 * gradient, dS/dt, the stress after the radial return and the kick, the
 * plastic strain and the artificial stress; with brittle materials the
 * damage, d^(1/3), the activated flaws and the growth rate.  The CPU side
 * runs the engine's task functions cell by cell (symmetric self and pair
 * loops, ghost, gradient, extra ghost, force, damage, kick2); the GPU side
 * runs the runner's FORCE phase (gather form, one thread per particle).
 * The two differ only in the order of the sums, so every quantity must
 * agree to 1e-10 relative (measured: ~1e-14); vectors and tensors relative
 * to their largest magnitude over the particles (the pressure too: the
 * isotropic part of the stress), integers exactly.
 * Three cases: a periodic box of ideal gas, an open box of Tillotson
 * granite (material library), and an open box of Tillotson basalt with
 * Collins strength, artificial stress and Weibull flaws (pre-stressed,
 * partly damaged, so that plasticity and flaw activation and growth all
 * happen: the test fails if any of them does not).  All are jittered
 * lattices with h off by up to 40% so that the h iteration runs several
 * rounds.  Self-gravity: the tree method with its far and near field on the
 * GPU against the CPU's (run_gravity_case).  Exits 77 (skip) when there is
 * no CUDA device. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/helpers/eos_tables.h"
#include "tasks/damage/damage_part.h"
#include "tasks/damage/flaws.h"
#include "tasks/density/density_cpu.h"
#include "src/engine.h"
#include "src/error.h"
#include "tasks/force/force_cpu.h"
#include "tasks/ghost/ghost_cpu.h"
#include "tasks/gradient/gradient_cpu.h"
#include "tasks/gravity/gravity_cpu.h"
#include "tests/helpers/gravity_sets.h"
#include "src/gpu/gpu_engine.h"
#include "src/gpu/gpu_lists.h"
#include "tasks/gravity/gpu_gravity.h"
#include "tasks/hydro_parts.h"
#include "tasks/hydro/kernel.h"
#include "tasks/kick/kick_cpu.h"
#include "tasks/kick/timestep.h"
#include "src/materials/material.h"
#include "src/space.h"

/** Uniform random number in [0, 1) (64-bit LCG). */
static double urand(unsigned long long *s) {
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

/** Per-top-cell neighbour lists as the engine builds them (engine_graph.c). */
static struct engine_cell_tasks *make_ngbs(const struct space *s) {
  struct engine_cell_tasks *ct = calloc(s->nr_top, sizeof *ct);
  const double zero[3] = {0, 0, 0};
  struct space_pair *pairs;
  const size_t np = space_top_pairs(s, &pairs);
  for (int c = 0; c < s->nr_top; c++) {
    ct[c].ngb = malloc((27 + 2) * sizeof(int));
    ct[c].ngb_shift = malloc((27 + 2) * sizeof(double[3]));
    ct[c].ngb[0] = c;
    memcpy(ct[c].ngb_shift[0], zero, sizeof zero);
    ct[c].nr_ngb = 1;
  }
  for (size_t k = 0; k < np; k++) {
    const int a = pairs[k].ci, b = pairs[k].cj;
    ct[a].ngb[ct[a].nr_ngb] = b;
    ct[b].ngb[ct[b].nr_ngb] = a;
    for (int d = 0; d < 3; d++) {
      ct[a].ngb_shift[ct[a].nr_ngb][d] = pairs[k].shift[d];
      ct[b].ngb_shift[ct[b].nr_ngb][d] = -pairs[k].shift[d];
    }
    ct[a].nr_ngb++;
    ct[b].nr_ngb++;
  }
  free(pairs);
  return ct;
}

/** Largest |a - b| / (|b| + floor) over the particles, b the reference
 *  (equal values count 0, also where both are 0; a NaN counts as failed). */
static double worst_rel(const double *a, const double *b, size_t n, double floor) {
  double w = 0.0;
  for (size_t i = 0; i < n; i++) {
    if (a[i] == b[i]) continue;
    const double e = fabs(a[i] - b[i]) / (fabs(b[i]) + floor);
    if (!(e <= w)) w = isnan(e) ? INFINITY : e;
  }
  return w;
}

/** Largest |x| over n values of each of the k arrays a[0..k). */
static double max_abs(double *const *a, int k, size_t n) {
  double m = 0.0;
  for (int c = 0; c < k; c++)
    for (size_t i = 0; i < n; i++) m = fmax(m, fabs(a[c][i]));
  return m;
}

/** A list entry: neighbouring leaf and shift. */
struct list_entry {
  int leaf;
  double shift[3];
};

/** Order of list entries (leaf, then shift). */
static int list_entry_cmp(const void *a, const void *b) {
  const struct list_entry *x = a, *y = b;
  if (x->leaf != y->leaf) return x->leaf < y->leaf ? -1 : 1;
  for (int k = 0; k < 3; k++)
    if (x->shift[k] != y->shift[k]) return x->shift[k] < y->shift[k] ? -1 : 1;
  return 0;
}

/** The neighbour lists built on the device (gpu_cells_build_dev) against
 *  those of the host's dual tree walk (gpu_cells_build) over the task cells
 *  tcells[0..nr) of sp: the same leaves and caps, and for every leaf the
 *  same entries as sets.  Also fails when the lists are degenerate: no
 *  entries, with must_prune every candidate pair kept (the acceptance test
 *  not exercised), or, in a periodic box, no entry with a shift.  Returns
 *  the failures. */
static int compare_lists(struct gpu *g, const struct space *sp, struct cell *const *tcells, int nr,
                         const struct engine_cell_tasks *ct, const double *tc_h_cap, double growth,
                         int leaf_size, int must_prune) {
  struct gpu_cells gh, gd;
  memset(&gh, 0, sizeof gh);
  memset(&gd, 0, sizeof gd);
  gh.nr_threads = 3;
  gd.nr_threads = 3; /* the device build's host part on 3 threads, whatever the size */
  gd.min_parallel = 1;
  gh.leaf_size = gd.leaf_size = leaf_size;
  gpu_cells_build(&gh, sp, tcells, nr, ct, tc_h_cap, growth, gh.nr_threads);
  gpu_cells_build_dev(g, &gd, sp, tcells, nr, ct, tc_h_cap, growth);
  int fail = 0;
  if (gh.n != gd.n || gh.nr_ngb != gd.nr_ngb) {
    printf("  FAIL lists: host %d leaves, %d entries; device %d leaves, %d entries\n", gh.n,
           gh.nr_ngb, gd.n, gd.nr_ngb);
    fail++;
  }
  for (int l = 0; l < gh.n && l < gd.n && !fail; l++)
    if (gh.offset[l] != gd.offset[l] || gh.count[l] != gd.count[l] || gh.top[l] != gd.top[l] ||
        gh.h_cap[l] != gd.h_cap[l] || gh.h_list_cap[l] != gd.h_list_cap[l] ||
        gh.dx_allow[l] != gd.dx_allow[l]) {
      printf("  FAIL lists: leaf %d differs between host and device builds\n", l);
      fail++;
    }
  int *start = malloc((gd.n + 1) * sizeof(int)), *leaf = malloc((gd.nr_ngb + 1) * sizeof(int));
  double *shift = malloc(3 * ((size_t)gd.nr_ngb + 1) * sizeof(double));
  gpu_lists_download(gd.dev, start, leaf, shift);
  long candidates = 0, shifted = 0, same_order = 1, bad_leaves = 0;
  int *tc_leaves = calloc(nr, sizeof(int));
  for (int l = 0; l < gd.n; l++) tc_leaves[gd.top[l]]++;
  for (int l = 0; l < gd.n && !fail; l++) {
    const int t = gd.top[l];
    for (int k = 0; k < ct[t].nr_ngb; k++) candidates += tc_leaves[ct[t].ngb[k]];
    const int nh = gh.ngb_start[l + 1] - gh.ngb_start[l], nd = start[l + 1] - start[l];
    if (start[l] != gh.ngb_start[l] || nh != nd) {
      bad_leaves++;
      continue;
    }
    struct list_entry *eh = malloc((nh + 1) * sizeof *eh), *ed = malloc((nd + 1) * sizeof *ed);
    for (int e = 0; e < nh; e++) {
      eh[e].leaf = gh.ngb_leaf[gh.ngb_start[l] + e];
      ed[e].leaf = leaf[start[l] + e];
      for (int d = 0; d < 3; d++) {
        eh[e].shift[d] = gh.ngb_shift[3 * (size_t)(gh.ngb_start[l] + e) + d];
        ed[e].shift[d] = shift[3 * (size_t)(start[l] + e) + d];
      }
      if (list_entry_cmp(&eh[e], &ed[e])) same_order = 0;
      if (ed[e].shift[0] != 0.0 || ed[e].shift[1] != 0.0 || ed[e].shift[2] != 0.0) shifted++;
    }
    qsort(eh, nh, sizeof *eh, list_entry_cmp);
    qsort(ed, nd, sizeof *ed, list_entry_cmp);
    for (int e = 0; e < nh; e++)
      if (list_entry_cmp(&eh[e], &ed[e])) {
        bad_leaves++;
        break;
      }
    free(eh);
    free(ed);
  }
  if (bad_leaves) {
    printf("  FAIL lists: %ld of %d leaves have different entries on the host and the device\n",
           bad_leaves, gd.n);
    fail++;
  }
  const int periodic = sp->periodic;
  printf(
      "  lists (growth %.2f, leaves of at most %d particles): %d leaves, %d entries of %ld "
      "candidate leaf pairs, %ld shifted; device = host as sets%s%s\n",
      growth, leaf_size, gd.n, gd.nr_ngb, candidates, shifted, same_order ? " and in order" : "",
      fail ? "  FAIL" : "");
  if (gd.nr_ngb == 0 || (must_prune && gd.nr_ngb >= candidates) || (periodic && shifted == 0)) {
    printf(
        "  FAIL lists: degenerate test (no entry, every candidate kept, or no periodic image)\n");
    fail++;
  }
  free(tc_leaves);
  free(start);
  free(leaf);
  free(shift);
  gpu_cells_free(&gh);
  gpu_cells_free(&gd);
  return fail;
}

/** The three cases. */
/** KIND_BASALT_CONT: the solid case with the density from the continuity
 *  equation (from perturbed densities) and XSPH; KIND_GRANITE_TABLE: the
 *  granite case with its Tillotson EOS as a table (eos_tables.h);
 *  KIND_GRANITE_TABLE_NODES: the same on irregular axes narrower than the
 *  states (bisection, linear in rho outside, ideal gas above the last u). */
enum test_kind {
  KIND_GAS,
  KIND_GRANITE,
  KIND_BASALT_SOLID,
  KIND_BASALT_CONT,
  KIND_GRANITE_TABLE,
  KIND_GRANITE_TABLE_NODES
};

/** The solids and damage fields of the CPU run p and the GPU run q: tensors
 *  relative to their largest component over the particles, damage relative
 *  to itself, activated flaws exactly.  Also fails when the case did not
 *  exercise plasticity, flaw activation or damage growth.  Returns the
 *  number of failures. */
static int compare_solids(const struct parts *p, const struct parts *q, size_t n) {
  double *gv_p[9] = {p->gvxx, p->gvxy, p->gvxz, p->gvyx, p->gvyy,
                     p->gvyz, p->gvzx, p->gvzy, p->gvzz};
  double *gv_q[9] = {q->gvxx, q->gvxy, q->gvxz, q->gvyx, q->gvyy,
                     q->gvyz, q->gvzx, q->gvzy, q->gvzz};
  double *dS_p[6] = {p->dSxx, p->dSxy, p->dSxz, p->dSyy, p->dSyz, p->dSzz};
  double *dS_q[6] = {q->dSxx, q->dSxy, q->dSxz, q->dSyy, q->dSyz, q->dSzz};
  double *S_p[6] = {p->Sxx, p->Sxy, p->Sxz, p->Syy, p->Syz, p->Szz};
  double *S_q[6] = {q->Sxx, q->Sxy, q->Sxz, q->Syy, q->Syz, q->Szz};
  double *R_p[6] = {p->Rxx, p->Rxy, p->Rxz, p->Ryy, p->Ryz, p->Rzz};
  double *R_q[6] = {q->Rxx, q->Rxy, q->Rxz, q->Ryy, q->Ryz, q->Rzz};
  static const char *const tn[6] = {"xx", "xy", "xz", "yy", "yz", "zz"};
  static const char *const gn[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};
  const double gv_max = max_abs(gv_p, 9, n), dS_max = max_abs(dS_p, 6, n);
  const double S_max = max_abs(S_p, 6, n), R_max = max_abs(R_p, 6, n);
  double *eps_p = p->eps_p;
  const double ep_max = max_abs(&eps_p, 1, n);
  int fail = 0;
  char name[32];
  /* each component: its name, CPU and GPU arrays, the floor */
  for (int c = 0; c < 9 + 6 + 6 + 6; c++) {
    const double *a, *b;
    double floor;
    if (c < 9) {
      snprintf(name, sizeof name, "gv%s", gn[c]);
      a = gv_q[c], b = gv_p[c], floor = gv_max;
    } else if (c < 15) {
      snprintf(name, sizeof name, "dS%s", tn[c - 9]);
      a = dS_q[c - 9], b = dS_p[c - 9], floor = dS_max;
    } else if (c < 21) {
      snprintf(name, sizeof name, "S%s", tn[c - 15]);
      a = S_q[c - 15], b = S_p[c - 15], floor = S_max;
    } else {
      snprintf(name, sizeof name, "R%s", tn[c - 21]);
      a = R_q[c - 21], b = R_p[c - 21], floor = R_max;
    }
    const double w = worst_rel(a, b, n, floor);
    const int bad = !(w < 1e-10);
    printf("  %-7s worst relative difference %.3e%s\n", name, w, bad ? "  FAIL (> 1e-10)" : "");
    fail += bad;
  }
  struct {
    const char *name;
    const double *cpu, *gpu;
    double floor;
  } cmp[] = {
      {"eps_p", p->eps_p, q->eps_p, ep_max},
      {"dmg", p->dmg, q->dmg, 0.0},
      {"dcbrt", p->dcbrt, q->dcbrt, 0.0},
      {"dmg_rate", p->dmg_rate, q->dmg_rate, 0.0},
  };
  for (size_t k = 0; k < sizeof cmp / sizeof cmp[0]; k++) {
    const double w = worst_rel(cmp[k].gpu, cmp[k].cpu, n, cmp[k].floor);
    const int bad = !(w < 1e-10);
    printf("  %-7s worst relative difference %.3e%s\n", cmp[k].name, w,
           bad ? "  FAIL (> 1e-10)" : "");
    fail += bad;
  }
  size_t nact_diff = 0, plastic = 0, activated = 0, growing = 0;
  for (size_t i = 0; i < n; i++) {
    nact_diff += p->n_act[i] != q->n_act[i];
    plastic += p->eps_p[i] > 0.0;
    activated += p->n_act[i] > 0;
    growing += p->dmg_rate[i] > 0.0;
  }
  printf("  n_act   %zu particles differ%s\n", nact_diff, nact_diff ? "  FAIL" : "");
  fail += nact_diff != 0;
  printf("  exercised: %zu plastic, %zu with activated flaws, %zu with growing damage (of %zu)\n",
         plastic, activated, growing, n);
  if (plastic == 0 || activated == 0 || growing == 0) {
    printf("  FAIL: the case must exercise plasticity, flaw activation and damage growth\n");
    fail++;
  }
  return fail;
}

/** The jittered lattice of a case (side^3 particles, h off by up to 40%),
 *  the solids pre-stressed and partly damaged. */
static void case_lattice(struct parts *p, int periodic, int side, enum test_kind kind, double eta,
                         unsigned long long seed) {
  unsigned long long s = seed;
  const int granite = kind != KIND_GAS;
  const int cont = kind == KIND_BASALT_CONT, solid = kind == KIND_BASALT_SOLID || cont;
  const double dx = (periodic ? 1.0 : 0.6) / side, rho0 = granite ? 2680.0 : 1.0;
  /* the solid case: velocities and a time step of the scale of the material */
  const double vscale = solid ? 10.0 : 1.0;
  size_t i = 0;
  for (int a = 0; a < side; a++)
    for (int b = 0; b < side; b++)
      for (int c = 0; c < side; c++, i++) {
        const double o = periodic ? 0.0 : 0.2;
        p->x[i] = o + (a + 0.5 + 0.3 * (urand(&s) - 0.5)) * dx;
        p->y[i] = o + (b + 0.5 + 0.3 * (urand(&s) - 0.5)) * dx;
        p->z[i] = o + (c + 0.5 + 0.3 * (urand(&s) - 0.5)) * dx;
        p->vx[i] = p->vpx[i] = vscale * (0.3 * sin(6.283 * p->y[i]) + 0.1 * (urand(&s) - 0.5));
        p->vy[i] = p->vpy[i] = vscale * (0.3 * cos(6.283 * p->z[i]) + 0.1 * (urand(&s) - 0.5));
        p->vz[i] = p->vpz[i] = vscale * 0.1 * (urand(&s) - 0.5);
        p->m[i] = rho0 * dx * dx * dx * (0.8 + 0.4 * urand(&s));
        p->h[i] = eta * dx * (0.7 + 0.7 * urand(&s));
        p->u[i] = p->up[i] = (solid ? 1e4 : granite ? 1e6 : 1.0) * (0.5 + urand(&s));
        p->mat[i] = granite ? 1 : 0;
        p->id[i] = (int64_t)i;
        if (solid) {
          /* deviatoric stress of +-2e8 Pa (tension for many particles:
           * flaws activate; above the yield stress: radial return), a third
           * of the particles already damaged */
          const double Sd[5] = {2e8 * (urand(&s) - 0.5), 2e8 * (urand(&s) - 0.5),
                                2e8 * (urand(&s) - 0.5), 2e8 * (urand(&s) - 0.5),
                                2e8 * (urand(&s) - 0.5)};
          p->Sxx[i] = p->Spxx[i] = Sd[0];
          p->Syy[i] = p->Spyy[i] = Sd[1];
          p->Szz[i] = p->Spzz[i] = -Sd[0] - Sd[1];
          p->Sxy[i] = p->Spxy[i] = Sd[2];
          p->Sxz[i] = p->Spxz[i] = Sd[3];
          p->Syz[i] = p->Spyz[i] = Sd[4];
          p->dcbrt[i] = urand(&s) < 0.33 ? 0.5 * urand(&s) : 0.0;
          p->dmg[i] = p->dcbrt[i] * p->dcbrt[i] * p->dcbrt[i];
        }
        if (cont) p->rho_full[i] = p->rho_fp[i] = rho0 * (0.95 + 0.1 * urand(&s));
      }
}

/** The material of a case into mats, and what it switches on in hp. */
static void case_material(struct material_table *mats, struct hydro_props *hp,
                          enum test_kind kind) {
  const int granite = kind != KIND_GAS;
  const int cont = kind == KIND_BASALT_CONT, solid = kind == KIND_BASALT_SOLID || cont;
  struct material m;
  char msg[256];
  if (solid) {
    /* basalt with Collins et al. (2004) strength and Weibull flaws
     * (Nakamura & Fujiwara 1991 k, m) */
    material_from_library(&m, material_default_library(), "basalt", 1);
    m.strength = STRENGTH_COLLINS;
    const char *keys[] = {"yield_stress",     "yield_stress_max", "friction_intact",
                          "cohesion_damaged", "friction_damaged", "weibull_k",
                          "weibull_m"};
    const double vals[] = {1e7, 3.5e9, 1.2, 1e5, 0.6, 5e34, 8.0};
    for (int k = 0; k < 7; k++)
      if (material_set(&m, keys[k], vals[k], msg, sizeof msg)) error_exit("%s", msg);
    hp->solids = 1;
    hp->gradient_correction = 1;
    hp->momentum_form = HYDRO_MOMENTUM_STANDARD;
    hp->as_eps = 0.3;
    hp->as_n = 4.0;
    hp->as_wdp_inv = 1.0 / kernel_W(1.0 / hp->eta, 1.0);
    hp->max_rel_change = 0.25;
    if (cont) {
      hp->continuity = 1;
      hp->xsph = 0.5;
    }
  } else if (granite) {
    material_from_library(&m, material_default_library(), "granite", 1);
    if (kind == KIND_GRANITE_TABLE) {
      /* 96 x 96 nodes over the states of the case (rho 0.4 to 2.5 rho0,
       * u 1e4 to 1e8 J/kg): the GPU must read the same nodes */
      const struct eos_tillotson till = m.eos.tillotson;
      m.eos_type = EOS_TABLE;
      memset(&m.eos, 0, sizeof m.eos);
      table_from_tillotson(&m.eos.table, &till, 96, 96, 0.4 * till.rho0, 2.5 * till.rho0, 1e4, 1e8);
    } else if (kind == KIND_GRANITE_TABLE_NODES) {
      /* 40 x 40 irregular nodes over rho 0.8 to 1.6 rho0 and u 3e4 to 1e6
       * J/kg: many states of the case lie outside */
      const struct eos_tillotson till = m.eos.tillotson;
      double rho[40], u[40];
      for (int k = 0; k < 40; k++) {
        const double w = (k + (k % 3 == 1 ? 0.3 : k % 3 == 2 ? -0.2 : 0.0)) / 39.0;
        rho[k] = till.rho0 * (0.8 + 0.8 * w);
        u[k] = 3e4 * pow(1e6 / 3e4, w);
      }
      m.eos_type = EOS_TABLE;
      memset(&m.eos, 0, sizeof m.eos);
      table_from_tillotson_nodes(&m.eos.table, &till, rho, 40, u, 40, 1.4);
    }
  } else {
    material_init(&m, 0, "gas", EOS_IDEAL_GAS);
    material_set(&m, "gamma", 5.0 / 3.0, msg, sizeof msg);
  }
  if (material_finalize(&m, msg, sizeof msg)) error_exit("%s", msg);
  material_table_add(mats, &m);
}

/** The CPU side of a case: the engine's tasks, cell by cell (density, ghost,
 *  with solids gradient and extra ghost, force, damage, kick2), dt_cpu the
 *  time step of each top-level cell.  Returns whether a cell capped h. */
static int case_cpu(struct parts *p, struct space *sp, const struct engine_cell_tasks *ct,
                    const struct space_pair *pairs, size_t np, const double *top_h_cap,
                    const struct hydro_props *hp, const struct material_table *mats,
                    const struct flaws *fl, int solid, double dt_kick, double dt_damage,
                    double damage_max_change, double *dt_cpu) {
  const size_t n = p->count;
  for (size_t k = 0; k < n; k++) hydro_density_reset(p, k);
  for (int c = 0; c < sp->nr_top; c++) density_self_cpu(p, &sp->cells[c], NULL);
  for (size_t k = 0; k < np; k++)
    density_pair_cpu(p, &sp->cells[pairs[k].ci], &sp->cells[pairs[k].cj], pairs[k].shift, NULL);
  int capped_cpu = 0;
  for (int c = 0; c < sp->nr_top; c++) {
    struct cell *cells[32];
    for (int k = 0; k < ct[c].nr_ngb; k++) cells[k] = &sp->cells[ct[c].ngb[k]];
    struct ghost_ngbs ng = {ct[c].nr_ngb, cells, (const double(*)[3])ct[c].ngb_shift};
    long long resummed;
    capped_cpu |= ghost_cell_cpu(p, &sp->cells[c], &ng, hp, mats, top_h_cap[c] * kernel_gamma, NULL,
                                 &resummed);
  }
  if (solid) {
    /* ghost -> gradient -> extra ghost -> force */
    for (int c = 0; c < sp->nr_top; c++) gradient_self_cpu(p, &sp->cells[c]);
    for (size_t k = 0; k < np; k++)
      gradient_pair_cpu(p, &sp->cells[pairs[k].ci], &sp->cells[pairs[k].cj], pairs[k].shift);
    for (int c = 0; c < sp->nr_top; c++) extra_ghost_cell_cpu(p, &sp->cells[c], hp, mats);
  }
  for (int c = 0; c < sp->nr_top; c++) force_self_cpu(p, &sp->cells[c], hp);
  for (size_t k = 0; k < np; k++)
    force_pair_cpu(p, &sp->cells[pairs[k].ci], &sp->cells[pairs[k].cj], pairs[k].shift, hp);
  /* force -> damage -> kick2 (tasks/task_families.h) */
  for (size_t k = 0; k < n && solid; k++) damage_part(p, k, mats, fl->eps, dt_damage);
  /* the GPU kick's: hydrodynamics, porous rates (no-ops here), damage */
  struct timestep_props tp;
  memset(&tp, 0, sizeof tp);
  tp.hydro = tp.porous = 1;
  tp.damage_max_change = solid ? damage_max_change : 0.0;
  for (int c = 0; c < sp->nr_top; c++)
    dt_cpu[c] = sp->cells[c].count
                    ? kick2_cell_cpu(p, &sp->cells[c], dt_kick, hp, mats, &tp, NULL, NULL)
                    : 1e300;
  return capped_cpu;
}

/** The fields of the FORCE phase on the CPU (p) and the GPU (q), each to
 *  1e-10 relative: returns the number of failed comparisons. */
static int compare_force(const struct parts *p, const struct parts *q, size_t n, double rho0) {
  double amax = 0.0, hmean = 0.0;
  for (size_t k = 0; k < n; k++) {
    amax = fmax(amax, sqrt(p->ax[k] * p->ax[k] + p->ay[k] * p->ay[k] + p->az[k] * p->az[k]));
    hmean += p->h[k] / n;
  }
  double vmax = 0.0, Pmax = 0.0, dumax = 0.0;
  for (size_t k = 0; k < n; k++) {
    vmax = fmax(vmax, fabs(p->vx[k]));
    Pmax = fmax(Pmax, fabs(p->P[k]));
    dumax = fmax(dumax, fabs(p->du_dt[k]));
  }
  struct {
    const char *name;
    const double *cpu, *gpu;
    double floor;
  } cmp[] = {
      {"rho", p->rho, q->rho, 0.0},
      {"wcount", p->wcount, q->wcount, 0.0},
      {"h", p->h, q->h, 0.0},
      {"div_v", p->div_v, q->div_v, 1e-3 * vmax / hmean},
      /* the isotropic part of the stress: signed in a solid, and near P = 0
       * (rho near rho_0) A (rho / rho_0 - 1) magnifies the sums' round-off in
       * rho; relative to the largest |P|, as the stress components */
      {"P", p->P, q->P, Pmax},
      {"cs", p->cs, q->cs, 0.0},
      {"ax", p->ax, q->ax, amax},
      {"ay", p->ay, q->ay, amax},
      {"az", p->az, q->az, amax},
      {"du_dt", p->du_dt, q->du_dt, dumax},
      {"v_sig", p->v_sig, q->v_sig, 0.0},
      {"vx", p->vx, q->vx, vmax},
      {"u", p->u, q->u, 0.0},
      /* continuity + XSPH case (zero elsewhere: rho_full and the XSPH sums
       * then compare as equal) */
      {"drho_dt", p->drho_dt, q->drho_dt, 1e-3 * rho0 * vmax / hmean},
      {"rho_full", p->rho_full, q->rho_full, 0.0},
      {"xsphx", p->xsphx, q->xsphx, vmax},
      {"xsphy", p->xsphy, q->xsphy, vmax},
      {"xsphz", p->xsphz, q->xsphz, vmax},
  };
  int fail = 0;
  for (size_t k = 0; k < sizeof cmp / sizeof cmp[0]; k++) {
    const double w = worst_rel(cmp[k].gpu, cmp[k].cpu, n, cmp[k].floor);
    const int bad = !(w < 1e-10);
    printf("  %-7s worst relative difference %.3e%s\n", cmp[k].name, w,
           bad ? "  FAIL (> 1e-10)" : "");
    fail += bad;
  }
  return fail;
}

/** One case: returns the number of failed comparisons. */
static int run_case(struct gpu *g, int periodic, int side, enum test_kind kind,
                    unsigned long long seed) {
  const int granite = kind != KIND_GAS;
  const int cont = kind == KIND_BASALT_CONT, solid = kind == KIND_BASALT_SOLID || cont;
  const size_t n = (size_t)side * side * side;
  const double box[3] = {1.0, 1.0, 1.0};
  const double rho0 = granite ? 2680.0 : 1.0;
  struct parts p;
  parts_alloc(&p, n);
  struct hydro_props hp = {.enabled = 1,
                           .eta = 1.2348,
                           .h_tolerance = 1e-4,
                           .h_taylor = 4.0824829046386306e-3, /* SPH:h_taylor's sqrt(1e-4 / 6) */
                           .h_max = 1.0,
                           .max_iterations = 60,
                           .cfl = 0.2,
                           .log_max_volume_change = log(1.4),
                           .alpha = 1.5,
                           .beta = 3.0,
                           .balsara = 1,
                           .alpha_u = 0.5};
  case_lattice(&p, periodic, side, kind, hp.eta, seed);
  struct material_table mats;
  material_table_init(&mats);
  case_material(&mats, &hp, kind);
  /* Weibull flaws (damage_init_flaws' procedure, index order) */
  struct flaws fl;
  memset(&fl, 0, sizeof fl);
  const int64_t nr_flaws =
      solid ? flaws_generate_materials(n, p.mat, p.m, p.rho, &mats, 2024, &fl) : 0;
  for (size_t k = 0; k < n && solid; k++) {
    p.flaw_first[k] = fl.offset[k];
    p.n_flaws[k] = (int32_t)(fl.offset[k + 1] - fl.offset[k]);
  }
  const double dt_damage = solid ? 2e-6 : 0.0, damage_max_change = 0.1;

  struct space sp;
  space_init(&sp, &p, box, periodic, 64, 4);
  space_rebuild(&sp);
  struct engine_cell_tasks *ct = make_ngbs(&sp);
  /* the top-level cells serve as task cells */
  struct cell **tcells = malloc(sp.nr_top * sizeof(struct cell *));
  for (int c = 0; c < sp.nr_top; c++) tcells[c] = &sp.cells[c];
  struct space_pair *pairs;
  const size_t np = space_top_pairs(&sp, &pairs);
  double H_limit = sp.width[0];
  for (int k = 0; k < 3; k++) {
    if (sp.width[k] < H_limit) H_limit = sp.width[k];
    if (periodic && 0.5 * sp.dim[k] < H_limit) H_limit = 0.5 * sp.dim[k];
  }
  double *top_h_cap = malloc(sp.nr_top * sizeof(double));
  for (int c = 0; c < sp.nr_top; c++)
    top_h_cap[c] = (H_limit - 2.0 * sp.cells[c].dx_max) / kernel_gamma;

  /* the GPU copy, taken before the CPU touches anything */
  struct parts q;
  parts_alloc(&q, n);
  for (int f = 0; f < part_nr_fields; f++)
    memcpy(part_field_array(&q, &part_fields[f]), part_field_array(&p, &part_fields[f]),
           n * part_fields[f].size);
  const double dt_kick = solid ? 1e-6 : 1e-3;

  /* CPU: the engine's tasks, cell by cell */
  double *dt_cpu = malloc(sp.nr_top * sizeof(double)), *dt_gpu = malloc(sp.nr_top * sizeof(double));
  double t0 = error_walltime();
  const int capped_cpu = case_cpu(&p, &sp, ct, pairs, np, top_h_cap, &hp, &mats, &fl, solid,
                                  dt_kick, dt_damage, damage_max_change, dt_cpu);
  const double t_cpu = error_walltime() - t0;

  /* GPU: the runner's FORCE phase on the copy, cells reset to its h */
  sp.parts = &q;
  for (int c = 0; c < sp.nr_top; c++) cell_update_bounds(&q, &sp.cells[c]);
  struct gpu_cells gc;
  memset(&gc, 0, sizeof gc);
  gc.nr_threads = 3; /* the threaded list build */
  const struct gpu_damage dmg = {solid, dt_damage, damage_max_change};
  t0 = error_walltime();
  if (solid) gpu_set_flaws(g, fl.eps, (size_t)nr_flaws);
  const int capped_gpu = gpu_cells_force(g, &gc, &q, &sp, tcells, sp.nr_top, ct, top_h_cap, &hp,
                                         &mats, &dmg, NULL, dt_kick, 0, dt_gpu, NULL);
  const double t_gpu = error_walltime() - t0;

  int fail = 0;
  printf(
      "%s box, %zu particles, %s: CPU %.3f s (1 thread), GPU %.3f s (lists %d leaves, %d "
      "entries)\n",
      periodic ? "periodic" : "open", n,
      kind == KIND_GRANITE_TABLE         ? "granite as a 96 x 96 (rho, u) EOS table"
      : kind == KIND_GRANITE_TABLE_NODES ? "granite as a 40 x 40 table on irregular, narrow axes"
      : cont    ? "Tillotson basalt, Collins strength, damage, continuity density, XSPH"
      : solid   ? "Tillotson basalt, Collins strength, artificial stress, Weibull flaws"
      : granite ? "Tillotson granite"
                : "ideal gas",
      t_cpu, t_gpu, gc.n, gc.nr_ngb);
  /* the lists built on the device equal the host's (at the h the phase
   * left): at the leaves of the tree, and on coarser cells with wider lists
   * (in the periodic box these are the top-level cells: every candidate kept) */
  fail += compare_lists(g, &sp, tcells, sp.nr_top, ct, top_h_cap, 1.25, 0, 1);
  fail += compare_lists(g, &sp, tcells, sp.nr_top, ct, top_h_cap, 1.9, 250, !periodic);
  fail += compare_force(&p, &q, n, rho0);
  if (solid) fail += compare_solids(&p, &q, n);
  const double wdt = worst_rel(dt_gpu, dt_cpu, (size_t)sp.nr_top, 0.0);
  printf("  %-7s worst relative difference %.3e%s\n", "dt", wdt,
         wdt < 1e-10 ? "" : "  FAIL (> 1e-10)");
  fail += !(wdt < 1e-10);
  if (capped_cpu != capped_gpu) {
    printf("  FAIL: capped by the cells: CPU %d, GPU %d\n", capped_cpu, capped_gpu);
    fail++;
  }
  gpu_cells_free(&gc);
  for (int c = 0; c < sp.nr_top; c++) {
    free(ct[c].ngb);
    free(ct[c].ngb_shift);
  }
  free(ct);
  free(pairs);
  free(top_h_cap);
  free(tcells);
  free(dt_cpu);
  free(dt_gpu);
  space_free(&sp);
  parts_free(&p);
  parts_free(&q);
  material_table_free(&mats);
  flaws_free(&fl);
  return fail;
}

/** Worst relative difference of the accelerations of q from those of p
 *  (relative to |a_i| + 1e-3 max |a|: near the centre of a body a_i
 *  vanishes) and of the potentials; in wa and wp. */
static void gravity_diff(const struct parts *p, const struct parts *q, double *wa, double *wp) {
  const size_t n = p->count;
  double amax = 0.0;
  for (size_t i = 0; i < n; i++)
    amax = fmax(amax, sqrt(p->gax[i] * p->gax[i] + p->gay[i] * p->gay[i] + p->gaz[i] * p->gaz[i]));
  *wa = 0.0;
  for (size_t i = 0; i < n; i++) {
    const double ai = sqrt(p->gax[i] * p->gax[i] + p->gay[i] * p->gay[i] + p->gaz[i] * p->gaz[i]);
    const double d[3] = {q->gax[i] - p->gax[i], q->gay[i] - p->gay[i], q->gaz[i] - p->gaz[i]};
    const double e = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / (ai + 1e-3 * amax);
    if (!(e <= *wa)) *wa = isnan(e) ? INFINITY : e;
  }
  *wp = worst_rel(q->pot, p->pot, n, 0.0);
}

/** Print and count the failures of one comparison of gravity_diff. */
static int gravity_report(const char *what, const struct parts *p, const struct parts *q) {
  double wa, wp;
  gravity_diff(p, q, &wa, &wp);
  printf("  %-28s ga %.3e%s  pot %.3e%s\n", what, wa, wa < 1e-10 ? "" : " FAIL (> 1e-10)", wp,
         wp < 1e-10 ? "" : " FAIL (> 1e-10)");
  return !(wa < 1e-10) + !(wp < 1e-10);
}

/** Worst difference of the upward pass on the device (gd) from the CPU's
 *  (gc) over the cells of sp: moments of order n relative to M0 r_max^n of
 *  the CPU's cell, centres relative to the cell's width, r_max, a_min and
 *  h_support relative to their own size; printed.  The device compiles the
 *  upward pass without fused multiply-adds (gravity_tree_gpu.cu) and both
 *  sides read the same |ga|: all must equal the CPU's exactly. */
static int gravity_up_report(const struct space *sp, const struct gravity_cell *gc,
                             const struct gravity_cell *gd, int order) {
  double wm = 0.0, wc = 0.0, wr = 0.0, wa = 0.0, wh = 0.0;
  for (int k = 0; k < sp->nr_cells; k++) {
    const struct gravity_multipole *a = &gc[k].mp, *b = &gd[k].mp;
    const double w = sp->cells[k].width[0];
    int i = 0;
    for (int n = 0; n <= order; n++) {
      const double scale = fabs(a->M[0]) * pow(a->r_max > 0.0 ? a->r_max : w, n) + 1e-300;
      for (int j = 0; j < (n + 1) * (n + 2) / 2; j++, i++)
        wm = fmax(wm, fabs(b->M[i] - a->M[i]) / scale);
    }
    for (int d = 0; d < 3; d++) wc = fmax(wc, fabs(b->com[d] - a->com[d]) / w);
    wr = fmax(wr, fabs(b->r_max - a->r_max) / w);
    wa = fmax(wa, fabs(gd[k].a_min - gc[k].a_min) / (fabs(gc[k].a_min) + 1e-300));
    wh = fmax(wh, fabs(gd[k].h_support - gc[k].h_support) / (fabs(gc[k].h_support) + 1e-300));
    if (isnan(b->M[0]) || isnan(b->r_max) || isnan(gd[k].a_min)) wm = INFINITY;
  }
  const int bad = !(wm == 0.0) + !(wc == 0.0) + !(wr == 0.0) + !(wa == 0.0) + !(wh == 0.0);
  printf(
      "  multipoles on the GPU vs the CPU, %d cells: moments %.2e, centres %.2e, r_max %.2e, "
      "a_min %.2e, h_support %.2e%s\n",
      sp->nr_cells, wm, wc, wr, wa, wh, bad ? " FAIL (must be equal)" : "");
  return bad;
}

/** Self-gravity: the tree method on the CPU (gravity_tree_all) against the
 *  same method with the far field on the GPU (gpu_grav_tree_all: the CPU
 *  computes the multipoles and walks the trees, recording every
 *  interaction; the GPU runs M2L, P2L, L2L, L2P, M2P and P2P with the same
 *  inline operators).  The two make the same decisions on the same
 *  multipoles and sum the same terms in another order, so potentials and
 *  accelerations must agree to 1e-10 (accelerations relative to |a_i| +
 *  1e-3 max |a|).  Three evaluations: the first (no acceleration scale
 *  yet), a second with the adaptive criterion (Gravity:epsilon_fmm at its
 *  default) reading |ga| of the first (the CPU's, on both sides, so that no
 *  decision can flip on a round-off of a_min), and a replay of the second's
 *  interactions at moved positions (Gravity:reuse_steps: gravity_replay on
 *  the CPU, gpu_grav_run with replay on the GPU).  n particles of equal
 *  masses, G = 1, uniform in a unit sphere or (clustered) two Plummer
 *  spheres of tests/helpers/gravity_sets.h, whose large sparse leaves meet small
 *  dense cells: the walks' lopsided M2P and P2L, which the case then
 *  requires.  Returns the number of failures. */
static int run_gravity_case(struct gpu *g, size_t n, int softening, unsigned long long seed,
                            int clustered) {
  unsigned long long s = seed;
  struct parts p, q;
  parts_alloc(&p, n);
  srand48((long)seed);
  const double centre[3] = {2.0, 2.0, 2.0};
  for (size_t i = 0; i < n;) {
    double x = 2.0 * urand(&s) - 1.0, y = 2.0 * urand(&s) - 1.0, z = 2.0 * urand(&s) - 1.0;
    if (clustered) {
      double r[3];
      gset_two_bodies(i, n, centre, r);
      x = r[0] - 2.0, y = r[1] - 2.0, z = r[2] - 2.0;
    } else if (x * x + y * y + z * z >= 1.0)
      continue;
    p.x[i] = 2.0 + x, p.y[i] = 2.0 + y, p.z[i] = 2.0 + z;
    p.m[i] = 1.0 / (double)n;
    p.h[i] = 0.05;
    p.id[i] = (int64_t)i;
    i++;
  }
  const double box[3] = {4.0, 4.0, 4.0};
  struct space sp;
  space_init(&sp, &p, box, 0, 32, 4);
  space_rebuild(&sp);
  parts_alloc(&q, n);
  for (int f = 0; f < part_nr_fields; f++)
    memcpy(part_field_array(&q, &part_fields[f]), part_field_array(&p, &part_fields[f]),
           n * part_fields[f].size);
  struct gravity_props gp;
  gravity_props_set(&gp, 1.0, 0.5, 2e-3, softening, GRAVITY_ORDER_DEFAULT);
  gp.epsilon_fmm = GRAVITY_EPSILON_FMM_DEFAULT;
  int capp = 0, capq = 0;
  struct gravity_cell *gcp = gravity_cells_reserve(NULL, &capp, sp.cells_capacity);
  struct gravity_cell *gcq = gravity_cells_reserve(NULL, &capq, sp.cells_capacity);
  memset(gcp, 0, (size_t)capp * sizeof *gcp);
  memset(gcq, 0, (size_t)capq * sizeof *gcq);
  struct gpu_grav *gg = gpu_grav_new(g);
  struct gpu_grav_host h;
  memset(&h, 0, sizeof h);
  h.built_rebuild = -1;
  struct gravity_gpu_rec rec;
  memset(&rec, 0, sizeof rec);
  int fail = 0;
  printf("gravity, %zu particles %s, %s softening, far field on the GPU:\n", n,
         clustered ? "in two Plummer spheres" : "in a sphere",
         softening == GRAVITY_SOFTENING_PLUMMER ? "Plummer" : "spline");

  /* 1: first evaluation */
  double t0 = error_walltime();
  gravity_tree_all(&p, sp.cells, sp.nr_top, gcp, &gp);
  const double t_cpu = error_walltime() - t0;
  t0 = error_walltime();
  gpu_grav_tree_all(gg, &h, &rec, &q, &sp, gcq, &gp, 0, 0, 0);
  const double t_gpu = error_walltime() - t0;
  /* the interactions, a mutual one counted in each direction */
  size_t n_m2p = 0, n_p2l = 0;
  for (size_t k = 0; k < rec.part.n; k++) n_m2p += rec.part.source[k] < 0;
  for (size_t k = 0; k < rec.field.n; k++) n_p2l += rec.field.source[k] < 0;
  const size_t n_part = rec.part.n + 2 * rec.part_sym.n,
               n_field = rec.field.n + 2 * rec.field_sym.n;
  printf(
      "  CPU tree %.3f s; CPU up + recorded walks + GPU %.3f s; %zu P2P/M2P and %zu M2L/P2L "
      "interactions, %d leaves, %d L2L levels\n",
      t_cpu, t_gpu, n_part, n_field, h.tree.nr_leaves, h.tree.nr_levels);
  fail += gravity_report("first evaluation", &p, &q);
  printf("  exercised: %zu M2P, %zu P2L, %zu M2L, %zu P2P\n", n_m2p, n_p2l, n_field - n_p2l,
         n_part - n_m2p);
  if (n_part - n_m2p == 0 || n_field - n_p2l == 0 || h.tree.nr_levels == 0) {
    printf("  FAIL: the walk recorded no P2P or no M2L, or the tree has no levels\n");
    fail++;
  }
  if (clustered && (n_m2p == 0 || n_p2l == 0)) {
    printf("  FAIL: the clustered set exercised no M2P or no P2L\n");
    fail++;
  }

  /* 2: adaptive criterion on |ga| of the first (the CPU's on both sides) */
  double *ga1 = malloc(3 * n * sizeof(double));
  for (size_t i = 0; i < n; i++) {
    q.gax[i] = ga1[3 * i] = p.gax[i];
    q.gay[i] = ga1[3 * i + 1] = p.gay[i];
    q.gaz[i] = ga1[3 * i + 2] = p.gaz[i];
  }
  struct gravity_ilist il;
  memset(&il, 0, sizeof il);
  gravity_record_begin(&il);
  gravity_tree_all(&p, sp.cells, sp.nr_top, gcp, &gp);
  gravity_record_end();
  gpu_grav_tree_all(gg, &h, &rec, &q, &sp, gcq, &gp, 0, 0, 0);
  fail += gravity_report("second (adaptive) evaluation", &p, &q);

  /* 2b: the same evaluation with the upward pass on the device
   * (Scheduler:gpu_multipoles: device): the same multipoles bit for bit,
   * the same walks, the same accelerations */
  int capd = 0;
  struct gravity_cell *gcd = gravity_cells_reserve(NULL, &capd, sp.cells_capacity);
  memset(gcd, 0, (size_t)capd * sizeof *gcd);
  for (size_t i = 0; i < n; i++)
    q.gax[i] = ga1[3 * i], q.gay[i] = ga1[3 * i + 1], q.gaz[i] = ga1[3 * i + 2];
  gpu_grav_tree_all(gg, &h, &rec, &q, &sp, gcd, &gp, 0, 1, 0);
  fail += gravity_up_report(&sp, gcq, gcd, gp.order);
  fail += gravity_report("second, multipoles on the GPU", &p, &q);
  /* 2c: and the walks on the device too (Scheduler:gpu_walks: device):
   * the same decisions on the same multipoles */
  for (size_t i = 0; i < n; i++)
    q.gax[i] = ga1[3 * i], q.gay[i] = ga1[3 * i + 1], q.gaz[i] = ga1[3 * i + 2];
  gpu_grav_tree_all(gg, &h, &rec, &q, &sp, gcd, &gp, 0, 1, 1);
  fail += gravity_report("second, multipoles and walks on the GPU", &p, &q);
  free(gcd);
  free(ga1);

  /* 3: replay at positions moved by up to 1e-3 (of a unit radius) */
  for (size_t i = 0; i < n; i++) {
    const double d[3] = {1e-3 * (urand(&s) - 0.5), 1e-3 * (urand(&s) - 0.5),
                         1e-3 * (urand(&s) - 0.5)};
    p.x[i] += d[0], p.y[i] += d[1], p.z[i] += d[2];
    q.x[i] += d[0], q.y[i] += d[1], q.z[i] += d[2];
  }
  gp.replay = 1;
  for (int i = 0; i < sp.nr_top; i++) gravity_up(&p, sp.cells + i, gcp, &gp);
  gravity_replay(&p, &il, gcp, &gp);
  for (int i = 0; i < sp.nr_top; i++) gravity_down(&p, sp.cells + i, gcp, &gp);
  gpu_grav_run(gg, &q, NULL, 0, gp.G, gp.eps, gp.softening, gp.eps2_expansion, gp.order, 0, 1);
  fail += gravity_report("replay at moved positions", &p, &q);

  gravity_ilist_free(&il);
  gravity_gpu_rec_free(&rec);
  gpu_grav_print(gg, stdout);
  gpu_grav_free(gg);
  gpu_grav_host_free(&h);
  free(gcp);
  free(gcq);
  space_free(&sp);
  parts_free(&p);
  parts_free(&q);
  return fail;
}

int main(int argc, char **argv) {
  (void)argc;
  error_init(argv[0]);
  char why[256];
  struct gpu *g = gpu_init(0, why, sizeof why);
  if (!g) {
    printf("SKIP: no GPU (%s)\n", why);
    return 77;
  }
  printf("device: %s\n", gpu_name(g));
  int fail = 0;
  fail += run_case(g, 1, 24, KIND_GAS, 12345);
  fail += run_case(g, 0, 20, KIND_GRANITE, 777);
  fail += run_case(g, 0, 20, KIND_BASALT_SOLID, 4242);
  fail += run_case(g, 0, 20, KIND_BASALT_CONT, 4343);
  fail += run_case(g, 0, 20, KIND_GRANITE_TABLE, 778);
  fail += run_case(g, 0, 20, KIND_GRANITE_TABLE_NODES, 779);
  fail += run_gravity_case(g, 40000, GRAVITY_SOFTENING_SPLINE, 99, 0);
  fail += run_gravity_case(g, 20000, GRAVITY_SOFTENING_PLUMMER, 98, 0);
  fail += run_gravity_case(g, 40000, GRAVITY_SOFTENING_SPLINE, 97, 1);
  gpu_print_timers(g, stdout);
  gpu_free(g);
  printf("%s\n", fail ? "FAIL" : "PASS");
  return fail ? 1 : 0;
}
