/* Self-gravity on the CPU: tree walks over the cell octrees (see
 * gravity_cpu.h; the formulas are in gravity_iact.h and theory/gravity.md). */
#include "gravity/gravity_cpu.h"

#include <math.h>
#include <pthread.h>
#include <string.h>

#include "cell.h"
#include "error.h"
#include "part.h"

void gravity_props_set(struct gravity_props *gp, double G, double theta, double eps, int softening,
                       int order) {
  if (order < 1 || order > GRAVITY_ORDER_MAX)
    error_exit("gravity: expansion order %d outside 1..%d", order, GRAVITY_ORDER_MAX);
  memset(gp, 0, sizeof *gp);
  gp->enabled = 1;
  gp->G = G;
  gp->theta = theta;
  gp->eps = eps;
  gp->softening = softening;
  gp->order = order;
  gp->eta = 0.025;
  if (softening == GRAVITY_SOFTENING_PLUMMER) {
    gp->h_support = 0.0;
    gp->eps2_expansion = eps * eps;
  } else {
    gp->h_support = GRAVITY_SPLINE_H_OVER_EPS * eps;
    gp->eps2_expansion = 0.0;
  }
}

void gravity_check_space(const struct gravity_props *gp, int periodic) {
  if (gp->enabled && periodic)
    error_exit(
        "Gravity:enabled: self-gravity needs an open box (InitialConditions:periodic: "
        "false); periodic gravity is not implemented");
}

struct gravity_cell *gravity_cells_reserve(struct gravity_cell *gc, int *capacity, int n) {
  if (n <= *capacity) return gc;
  gc = error_realloc(gc, (size_t)n * sizeof *gc, "gravity cells");
  *capacity = n;
  return gc;
}

/* ------------------------------------------------------------------ up */

/** Multipole of c from its particles (leaf) or its progeny (split cell). */
static void up_rec(struct parts *p, const struct cell *c, struct gravity_cell *gc, int order) {
  struct gravity_cell *g = gc + c->index;
  struct gravity_multipole *mp = &g->mp;
  gravity_field_zero(&g->field);
  gravity_multipole_zero(mp);
  mp->r_max = 0.0;
  g->a_min = 0.0;
  for (int k = 0; k < 3; k++) mp->com[k] = c->loc[k] + 0.5 * c->width[k];
  if (c->count == 0) return;

  double mass = 0.0, s[3] = {0.0, 0.0, 0.0};
  if (c->split) {
    double a_min = HUGE_VAL;
    for (int q = 0; q < 8; q++) {
      const struct cell *cp = c->progeny[q];
      if (cp == NULL || cp->count == 0) continue;
      up_rec(p, cp, gc, order);
      const struct gravity_multipole *mq = &gc[cp->index].mp;
      mass += mq->M[0];
      for (int k = 0; k < 3; k++) s[k] += mq->M[0] * mq->com[k];
      if (gc[cp->index].a_min < a_min) a_min = gc[cp->index].a_min;
    }
    g->a_min = a_min;
  } else {
    /* |ga| of the previous pass (0 for a particle never computed: then the
     * cell's a_min is 0, "unknown"), then a fresh start of the sums. */
    double a2_min = HUGE_VAL;
    for (size_t i = c->offset; i < c->offset + c->count; i++) {
      mass += p->m[i];
      s[0] += p->m[i] * p->x[i];
      s[1] += p->m[i] * p->y[i];
      s[2] += p->m[i] * p->z[i];
      const double a2 = p->gax[i] * p->gax[i] + p->gay[i] * p->gay[i] + p->gaz[i] * p->gaz[i];
      if (a2 < a2_min) a2_min = a2;
      p->gax[i] = p->gay[i] = p->gaz[i] = p->pot[i] = 0.0;
    }
    g->a_min = sqrt(a2_min);
  }
  /* A massless cell keeps its box centre as expansion centre. */
  if (mass > 0.0)
    for (int k = 0; k < 3; k++) mp->com[k] = s[k] / mass;

  if (c->split) {
    for (int q = 0; q < 8; q++) {
      const struct cell *cp = c->progeny[q];
      if (cp == NULL || cp->count == 0) continue;
      const struct gravity_multipole *mq = &gc[cp->index].mp;
      const double t[3] = {mq->com[0] - mp->com[0], mq->com[1] - mp->com[1],
                           mq->com[2] - mp->com[2]};
      gravity_m2m(mp, mq, t, order);
      const double r = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]) + mq->r_max;
      if (r > mp->r_max) mp->r_max = r;
    }
  } else {
    double r2max = 0.0;
    for (size_t i = c->offset; i < c->offset + c->count; i++) {
      const double d[3] = {p->x[i] - mp->com[0], p->y[i] - mp->com[1], p->z[i] - mp->com[2]};
      gravity_p2m(mp, d, p->m[i], order);
      const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (r2 > r2max) r2max = r2;
    }
    mp->r_max = sqrt(r2max);
  }
}

void gravity_up(struct parts *p, const struct cell *c, struct gravity_cell *gc,
                const struct gravity_props *gp) {
  up_rec(p, c, gc, gp->order);
}

/* ------------------------------------------------------------------ P2P */

/** All pairs within leaf c, each once (symmetric). */
static void p2p_self(struct parts *p, const struct cell *c, const struct gravity_props *gp) {
  const size_t i0 = c->offset, i1 = c->offset + c->count;
  for (size_t i = i0; i < i1; i++) {
    double pot = 0.0, a[3] = {0.0, 0.0, 0.0};
    for (size_t j = i + 1; j < i1; j++) {
      const double dx[3] = {p->x[i] - p->x[j], p->y[i] - p->y[j], p->z[i] - p->z[j]};
      const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
      double wpot, wacc;
      gravity_softened_kernel(r2, gp->eps, gp->softening, &wpot, &wacc);
      const double gi = gp->G * p->m[i], gj = gp->G * p->m[j];
      pot -= gj * wpot;
      a[0] -= gj * wacc * dx[0];
      a[1] -= gj * wacc * dx[1];
      a[2] -= gj * wacc * dx[2];
      p->pot[j] -= gi * wpot;
      p->gax[j] += gi * wacc * dx[0];
      p->gay[j] += gi * wacc * dx[1];
      p->gaz[j] += gi * wacc * dx[2];
    }
    p->pot[i] += pot;
    p->gax[i] += a[0];
    p->gay[i] += a[1];
    p->gaz[i] += a[2];
  }
}

/** Every particle of leaf a with every particle of leaf b; both updated
 *  when symmetric, only a's otherwise. */
static void p2p_pair(struct parts *p, const struct cell *a, const struct cell *b, int symmetric,
                     const struct gravity_props *gp) {
  const size_t j0 = b->offset, j1 = b->offset + b->count;
  for (size_t i = a->offset; i < a->offset + a->count; i++) {
    double pot = 0.0, acc[3] = {0.0, 0.0, 0.0};
    const double gi = gp->G * p->m[i];
    for (size_t j = j0; j < j1; j++) {
      const double dx[3] = {p->x[i] - p->x[j], p->y[i] - p->y[j], p->z[i] - p->z[j]};
      const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
      double wpot, wacc;
      gravity_softened_kernel(r2, gp->eps, gp->softening, &wpot, &wacc);
      const double gj = gp->G * p->m[j];
      pot -= gj * wpot;
      acc[0] -= gj * wacc * dx[0];
      acc[1] -= gj * wacc * dx[1];
      acc[2] -= gj * wacc * dx[2];
      if (symmetric) {
        p->pot[j] -= gi * wpot;
        p->gax[j] += gi * wacc * dx[0];
        p->gay[j] += gi * wacc * dx[1];
        p->gaz[j] += gi * wacc * dx[2];
      }
    }
    p->pot[i] += pot;
    p->gax[i] += acc[0];
    p->gay[i] += acc[1];
    p->gaz[i] += acc[2];
  }
}

/* ------------------------------------------------------------------ walks */

/** Acceptance of the interaction between cells a and b, the same in both
 *  directions (mutual interactions conserve momentum): the geometric
 *  criterion and, where the previous pass gave a scale, the adaptive one
 *  for a and for b. */
static int accept(const struct gravity_cell *a, const struct gravity_cell *b, double r2,
                  const struct gravity_props *gp) {
  if (!gravity_mac(a->mp.r_max, b->mp.r_max, r2, gp->theta, gp->h_support)) return 0;
  const double rs = a->mp.r_max + b->mp.r_max;
  return gravity_mac_adaptive(gp->G, b->mp.M[0], rs, r2, gp->order, gp->epsilon_fmm, a->a_min) &&
         gravity_mac_adaptive(gp->G, a->mp.M[0], rs, r2, gp->order, gp->epsilon_fmm, b->a_min);
}

/** Particle i (in a cell of scale a_min_i) with every particle of leaf b;
 *  upd_i / upd_b: which side receives. */
static void p2p_point_leaf(struct parts *p, size_t i, const struct cell *b, int upd_i, int upd_b,
                           const struct gravity_props *gp) {
  double pot = 0.0, acc[3] = {0.0, 0.0, 0.0};
  const double gi = gp->G * p->m[i];
  for (size_t j = b->offset; j < b->offset + b->count; j++) {
    const double dx[3] = {p->x[i] - p->x[j], p->y[i] - p->y[j], p->z[i] - p->z[j]};
    const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
    double wpot, wacc;
    gravity_softened_kernel(r2, gp->eps, gp->softening, &wpot, &wacc);
    const double gj = gp->G * p->m[j];
    pot -= gj * wpot;
    acc[0] -= gj * wacc * dx[0];
    acc[1] -= gj * wacc * dx[1];
    acc[2] -= gj * wacc * dx[2];
    if (upd_b) {
      p->pot[j] -= gi * wpot;
      p->gax[j] += gi * wacc * dx[0];
      p->gay[j] += gi * wacc * dx[1];
      p->gaz[j] += gi * wacc * dx[2];
    }
  }
  if (upd_i) {
    p->pot[i] += pot;
    p->gax[i] += acc[0];
    p->gay[i] += acc[1];
    p->gaz[i] += acc[2];
  }
}

/** Particle i (its leaf's a_min is a_min_i) against the tree of b: the
 *  mutual point-cell interaction (gravity_m2p_p2l) where the criterion
 *  accepts (point radius 0), else open b, P2P at b's leaves.  Used when a
 *  leaf too large to be opened meets smaller cells: its particles then see
 *  those cells one by one, instead of through one local expansion as large
 *  as the leaf, whose truncation errors would add up coherently over many
 *  small sources. */
static void walk_point(struct parts *p, size_t i, double a_min_i, const struct cell *b, int upd_i,
                       int upd_b, struct gravity_cell *gc, const struct gravity_props *gp) {
  if (b->count == 0) return;
  struct gravity_cell *gb = gc + b->index;
  const double R[3] = {gb->mp.com[0] - p->x[i], gb->mp.com[1] - p->y[i], gb->mp.com[2] - p->z[i]};
  const double r2 = R[0] * R[0] + R[1] * R[1] + R[2] * R[2];
  const double rb = gb->mp.r_max;
  if (gravity_mac(0.0, rb, r2, gp->theta, gp->h_support) &&
      gravity_mac_adaptive(gp->G, gb->mp.M[0], rb, r2, gp->order, gp->epsilon_fmm, a_min_i) &&
      gravity_mac_adaptive(gp->G, p->m[i], rb, r2, gp->order, gp->epsilon_fmm, gb->a_min)) {
    double D[GRAVITY_ND], pot = 0.0, a[3] = {0.0, 0.0, 0.0};
    gravity_derivatives(R, gp->eps2_expansion, gp->order, D);
    gravity_m2p_p2l(p->m[i], &gb->mp, upd_b ? &gb->field : NULL, D, gp->order, gp->G, &pot, a);
    if (upd_i) {
      p->pot[i] += pot;
      p->gax[i] += a[0];
      p->gay[i] += a[1];
      p->gaz[i] += a[2];
    }
    return;
  }
  if (!b->split) {
    p2p_point_leaf(p, i, b, upd_i, upd_b, gp);
    return;
  }
  for (int q = 0; q < 8; q++)
    if (b->progeny[q]) walk_point(p, i, a_min_i, b->progeny[q], upd_i, upd_b, gc, gp);
}

/** Dual-tree walk between disjoint cells a and b (Dehnen 2002):
 *  M2L where the criterion accepts, P2P between leaves, else open the
 *  larger cell; when the larger is a leaf, its particles walk the other
 *  cell one by one (walk_point).  symmetric: both cells receive (pair
 *  task), else only a (long-range task).  The decisions are symmetric in a
 *  and b, so the walk from b's side pairs the same interactions (momentum). */
static void walk_pair(struct parts *p, const struct cell *a, const struct cell *b, int symmetric,
                      struct gravity_cell *gc, const struct gravity_props *gp) {
  if (a->count == 0 || b->count == 0) return;
  struct gravity_cell *ga = gc + a->index, *gb = gc + b->index;
  const double R[3] = {gb->mp.com[0] - ga->mp.com[0], gb->mp.com[1] - ga->mp.com[1],
                       gb->mp.com[2] - ga->mp.com[2]};
  const double r2 = R[0] * R[0] + R[1] * R[1] + R[2] * R[2];
  if (accept(ga, gb, r2, gp)) {
    double D[GRAVITY_ND];
    if (symmetric) {
      gravity_derivatives(R, gp->eps2_expansion, gp->order, D);
      gravity_m2l_sym(&ga->field, &gb->field, &ga->mp, &gb->mp, D, gp->order);
    } else {
      /* target a, source b: the tensor at z_a - z_b */
      const double Rab[3] = {-R[0], -R[1], -R[2]};
      gravity_derivatives(Rab, gp->eps2_expansion, gp->order, D);
      gravity_m2l(&ga->field, &gb->mp, D, gp->order);
    }
    return;
  }
  if (!a->split && !b->split) {
    p2p_pair(p, a, b, symmetric, gp);
    return;
  }
  /* the larger cell (ties: a), as in Dehnen 2002 */
  const int a_larger = ga->mp.r_max >= gb->mp.r_max;
  const struct cell *big = a_larger ? a : b, *small = a_larger ? b : a;
  if (big->split) {
    for (int q = 0; q < 8; q++) {
      const struct cell *c = big->progeny[q];
      if (c == NULL) continue;
      if (a_larger)
        walk_pair(p, c, b, symmetric, gc, gp);
      else
        walk_pair(p, a, c, symmetric, gc, gp);
    }
    return;
  }
  /* big is a leaf, small is split: big's particles one by one.  Receivers:
   * both (symmetric), else a only (a is big: the points; b is big: the
   * cells of a). */
  const int upd_point = symmetric || a_larger, upd_cells = symmetric || !a_larger;
  const double a_min_big = gc[big->index].a_min;
  for (size_t i = big->offset; i < big->offset + big->count; i++)
    walk_point(p, i, a_min_big, small, upd_point, upd_cells, gc, gp);
}

/** All interactions within c: self of every progeny and every pair of them. */
static void walk_self(struct parts *p, const struct cell *c, struct gravity_cell *gc,
                      const struct gravity_props *gp) {
  if (c->count < 2) return;
  if (!c->split) {
    p2p_self(p, c, gp);
    return;
  }
  for (int q = 0; q < 8; q++) {
    if (c->progeny[q] == NULL) continue;
    walk_self(p, c->progeny[q], gc, gp);
    for (int r = q + 1; r < 8; r++)
      if (c->progeny[r]) walk_pair(p, c->progeny[q], c->progeny[r], 1, gc, gp);
  }
}

void gravity_interact_cells(struct parts *p, const struct cell *ci, const struct cell *cj,
                            struct gravity_cell *gc, const struct gravity_props *gp) {
  if (ci == cj)
    walk_self(p, ci, gc, gp);
  else
    walk_pair(p, ci, cj, 1, gc, gp);
}

int gravity_top_pair_is_near(const struct cell *ci, const struct cell *cj,
                             const struct gravity_props *gp) {
  double ri2 = 0.0, rj2 = 0.0, d2 = 0.0;
  for (int k = 0; k < 3; k++) {
    const double wi = ci->bmax[k] - ci->bmin[k] + 2.0 * ci->dx_max;
    const double wj = cj->bmax[k] - cj->bmin[k] + 2.0 * cj->dx_max;
    const double d = 0.5 * (cj->bmin[k] + cj->bmax[k] - ci->bmin[k] - ci->bmax[k]);
    ri2 += 0.25 * wi * wi;
    rj2 += 0.25 * wj * wj;
    d2 += d * d;
  }
  return !gravity_mac(sqrt(ri2), sqrt(rj2), d2, gp->theta, gp->h_support);
}

void gravity_long_range(struct parts *p, const struct cell *ci, const struct cell *tops, int nr_top,
                        struct gravity_cell *gc, const struct gravity_props *gp) {
  if (ci->count == 0) return;
  for (int j = 0; j < nr_top; j++) {
    const struct cell *cj = tops + j;
    if (cj == ci || cj->count == 0 || gravity_top_pair_is_near(ci, cj, gp)) continue;
    walk_pair(p, ci, cj, 0, gc, gp);
  }
}

/* ------------------------------------------------------------------ down */

/** Push c's local expansion to its progeny (L2L) or its particles (L2P). */
static void down_rec(struct parts *p, const struct cell *c, struct gravity_cell *gc,
                     const struct gravity_props *gp) {
  if (c->count == 0) return;
  const struct gravity_cell *g = gc + c->index;
  if (c->split) {
    for (int q = 0; q < 8; q++) {
      const struct cell *cp = c->progeny[q];
      if (cp == NULL || cp->count == 0) continue;
      struct gravity_cell *gq = gc + cp->index;
      const double t[3] = {gq->mp.com[0] - g->mp.com[0], gq->mp.com[1] - g->mp.com[1],
                           gq->mp.com[2] - g->mp.com[2]};
      gravity_l2l(&gq->field, &g->field, t, gp->order);
      down_rec(p, cp, gc, gp);
    }
    return;
  }
  for (size_t i = c->offset; i < c->offset + c->count; i++) {
    const double s[3] = {p->x[i] - g->mp.com[0], p->y[i] - g->mp.com[1], p->z[i] - g->mp.com[2]};
    double pot = 0.0, a[3] = {0.0, 0.0, 0.0};
    gravity_l2p(&g->field, s, gp->order, gp->G, &pot, a);
    p->pot[i] += pot;
    p->gax[i] += a[0];
    p->gay[i] += a[1];
    p->gaz[i] += a[2];
  }
}

void gravity_down(struct parts *p, const struct cell *c, struct gravity_cell *gc,
                  const struct gravity_props *gp) {
  down_rec(p, c, gc, gp);
}

void gravity_tree_all(struct parts *p, const struct cell *tops, int nr_top, struct gravity_cell *gc,
                      const struct gravity_props *gp) {
  for (int i = 0; i < nr_top; i++) gravity_up(p, tops + i, gc, gp);
  for (int i = 0; i < nr_top; i++) {
    gravity_interact_cells(p, tops + i, tops + i, gc, gp);
    for (int j = i + 1; j < nr_top; j++)
      if (gravity_top_pair_is_near(tops + i, tops + j, gp))
        gravity_interact_cells(p, tops + i, tops + j, gc, gp);
  }
  for (int i = 0; i < nr_top; i++) gravity_long_range(p, tops + i, tops, nr_top, gc, gp);
  for (int i = 0; i < nr_top; i++) gravity_down(p, tops + i, gc, gp);
}

/* ------------------------------------------------------------------ direct */

/** Work of one thread of gravity_direct: particles [i0, i1) from all. */
struct direct_job {
  struct parts *p; /**< the particles */
  size_t i0, i1;   /**< targets of this thread */
  double G, eps;   /**< constant and softening */
  int softening;   /**< enum gravity_softening */
};

/** Gather form: each target sums over every other particle. */
static void *direct_gather(void *arg) {
  const struct direct_job *job = arg;
  struct parts *p = job->p;
  for (size_t i = job->i0; i < job->i1; i++) {
    double pot = 0.0, a[3] = {0.0, 0.0, 0.0};
    for (size_t j = 0; j < p->count; j++) {
      if (j == i) continue;
      const double dx[3] = {p->x[i] - p->x[j], p->y[i] - p->y[j], p->z[i] - p->z[j]};
      const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
      gravity_p2p(dx, r2, p->m[j], job->G, job->eps, job->softening, &pot, a);
    }
    p->pot[i] += pot;
    p->gax[i] += a[0];
    p->gay[i] += a[1];
    p->gaz[i] += a[2];
  }
  return NULL;
}

static void direct_threads(struct parts *p, double G, double eps, int softening, int nthreads);

void gravity_direct(struct parts *p, double G, double eps, int softening, int nthreads) {
  const size_t n = p->count;
  memset(p->gax, 0, n * sizeof(double));
  memset(p->gay, 0, n * sizeof(double));
  memset(p->gaz, 0, n * sizeof(double));
  memset(p->pot, 0, n * sizeof(double));
  if (nthreads <= 1) {
    /* Symmetric: each pair once. */
    struct gravity_props gp;
    gravity_props_set(&gp, G, 0.0, eps, softening, 1);
    struct cell all;
    memset(&all, 0, sizeof all);
    all.offset = 0;
    all.count = p->count;
    p2p_self(p, &all, &gp);
  } else {
    direct_threads(p, G, eps, softening, nthreads);
  }
  for (size_t i = 0; i < n; i++) {
  }
}

/** Gather-form direct summation over nthreads POSIX threads. */
static void direct_threads(struct parts *p, double G, double eps, int softening, int nthreads) {
  pthread_t tid[64];
  struct direct_job job[64];
  if (nthreads > 64) nthreads = 64;
  for (int t = 0; t < nthreads; t++) {
    job[t].p = p;
    job[t].i0 = p->count * t / nthreads;
    job[t].i1 = p->count * (t + 1) / nthreads;
    job[t].G = G;
    job[t].eps = eps;
    job[t].softening = softening;
    if (pthread_create(&tid[t], NULL, direct_gather, &job[t]) != 0)
      error_exit("gravity_direct: cannot start thread %d", t);
  }
  for (int t = 0; t < nthreads; t++) pthread_join(tid[t], NULL);
}

double gravity_potential_energy(const struct parts *p) {
  double e = 0.0;
  for (size_t i = 0; i < p->count; i++) e += p->m[i] * p->pot[i];
  return 0.5 * e;
}
