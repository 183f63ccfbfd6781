/* Self-gravity on the CPU: tree walks over the cell octrees (see
 * gravity_cpu.h; the formulas are in gravity_iact.h and theory/gravity.md). */
/* the M2L operators unrolled for each expansion order (gravity_iact.h) */
#define GRAVITY_UNROLL_LOOPS 1
#include "tasks/gravity/gravity_cpu.h"
#include "tasks/gravity/gravity_walk.h"

#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "src/cell.h"
#include "src/error.h"
#include "src/part.h"
#include "src/timeline.h"

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

/** Multipole of c from its particles (leaf) or its progeny (split cell):
 *  gravity_up_leaf and gravity_up_node, shared with the GPU's kernels.
 *  act (a step of active particles only, gravity_props.active; else
 *  NULL): whether each cell holds a particle that ends its step at
 *  active_ti (its bin's step divides it: the test the drift made, read from
 *  the bins rather than from PART_INACTIVE, which the ghost clears for the
 *  particles the density phase wakes while this pass may run), by cell
 *  index; a leaf without one keeps its particles' ga and pot, since no
 *  walk adds to them this step. */
static void up_rec(struct parts *p, const struct cell *c, struct gravity_cell *gc, int order,
                   double h_factor, unsigned char *act, integertime_t active_ti) {
  struct gravity_cell *g = gc + c->index;
  gravity_field_zero(&g->field);
  const double centre[3] = {c->loc[0] + 0.5 * c->width[0], c->loc[1] + 0.5 * c->width[1],
                            c->loc[2] + 0.5 * c->width[2]};
  if (act) act[c->index] = 0;
  if (c->count == 0) {
    gravity_up_leaf(&g->mp, &g->a_min, &g->h_support, p->x, p->y, p->z, p->m, p->h, p->gax, p->gay,
                    p->gaz, 0, 0, order, h_factor, centre);
    return;
  }
  if (c->split) {
    const struct gravity_multipole *ch[8];
    double ch_a[8], ch_h[8];
    int n = 0;
    for (int q = 0; q < 8; q++) {
      const struct cell *cp = c->progeny[q];
      if (cp == NULL || cp->count == 0) continue;
      up_rec(p, cp, gc, order, h_factor, act, active_ti);
      if (act) act[c->index] |= act[cp->index];
      ch[n] = &gc[cp->index].mp, ch_a[n] = gc[cp->index].a_min, ch_h[n] = gc[cp->index].h_support;
      n++;
    }
    gravity_up_node(&g->mp, &g->a_min, &g->h_support, ch, ch_a, ch_h, n, order, centre);
  } else {
    /* |ga| of the previous pass read, then a fresh start of the sums */
    gravity_up_leaf(&g->mp, &g->a_min, &g->h_support, p->x, p->y, p->z, p->m, p->h, p->gax, p->gay,
                    p->gaz, c->offset, c->offset + c->count, order, h_factor, centre);
    const size_t end = c->offset + c->count;
    if (act) {
      for (size_t i = c->offset; i < end && !act[c->index]; i++)
        act[c->index] =
            active_ti % timeline_step_of_bin(p->time_bin[i] > 0 ? p->time_bin[i] : 1) == 0;
      if (!act[c->index]) return;
    }
    for (size_t i = c->offset; i < end; i++) p->gax[i] = p->gay[i] = p->gaz[i] = p->pot[i] = 0.0;
  }
}

void gravity_up(struct parts *p, const struct cell *c, struct gravity_cell *gc,
                const struct gravity_props *gp) {
  if (gp->replay) {
    /* the multipoles and local expansions of the last full evaluation stay */
    for (size_t i = c->offset; i < c->offset + c->count; i++)
      p->gax[i] = p->gay[i] = p->gaz[i] = p->pot[i] = 0.0;
    return;
  }
  up_rec(p, c, gc, gp->order, gp->h_factor, gp->active, gp->active_ti);
}

/* ------------------------------------------------------------------ P2P */

/** Interaction counters of the walks (gravity_counters_get), per thread:
 *  no shared cache line between workers, no data race. */
static _Thread_local struct gravity_counters counters;

void gravity_counters_get(struct gravity_counters *out, int reset) {
  *out = counters;
  if (reset) memset(&counters, 0, sizeof counters);
}

#if defined(__SSE2__)
/** The spline loop of p2p_row two sources at a time in SSE2 (x86-64's
 *  baseline; GCC does not vectorise the plain loop because sqrt may set
 *  errno): the same arithmetic as gravity_spline_kernel (its polynomials
 *  GRAVITY_SPLINE_POT and GRAVITY_SPLINE_ACC), the branch as a mask.
 *  Adds the target's sums to out[4] and returns the first source not done
 *  (the odd one left goes through the scalar loop). */
static size_t p2p_spline_sse2(const double *restrict x, const double *restrict y,
                              const double *restrict z, const double *restrict m,
                              double *restrict pot, double *restrict gax, double *restrict gay,
                              double *restrict gaz, size_t j0, size_t j1, const double xi[3],
                              double gmi, int sym, double inv_H, double H2, double G,
                              double out[4]) {
  const __m128d vx = _mm_set1_pd(xi[0]), vy = _mm_set1_pd(xi[1]), vz = _mm_set1_pd(xi[2]);
  const __m128d vih = _mm_set1_pd(inv_H), vih3 = _mm_set1_pd(inv_H * inv_H * inv_H);
  const __m128d vH2 = _mm_set1_pd(H2), vG = _mm_set1_pd(G), vgmi = _mm_set1_pd(gmi);
  const __m128d one = _mm_set1_pd(1.0);
  __m128d sp = _mm_setzero_pd(), sx = sp, sy = sp, sz = sp;
  size_t j = j0;
  for (; j + 2 <= j1; j += 2) {
    const __m128d dx = vx - _mm_loadu_pd(x + j), dy = vy - _mm_loadu_pd(y + j),
                  dz = vz - _mm_loadu_pd(z + j);
    const __m128d r2 = dx * dx + dy * dy + dz * dz;
    const __m128d r = _mm_sqrt_pd(r2);
    const __m128d in = _mm_cmplt_pd(r2, vH2);
    const __m128d inv_r = one / _mm_or_pd(_mm_and_pd(in, one), _mm_andnot_pd(in, r));
    const __m128d u = r * vih, u2 = u * u;
    const __m128d kp = vih * GRAVITY_SPLINE_POT(u, u2);
    const __m128d ka = vih3 * GRAVITY_SPLINE_ACC(u, u2);
    const __m128d wpot = _mm_or_pd(_mm_and_pd(in, kp), _mm_andnot_pd(in, inv_r));
    const __m128d wacc = _mm_or_pd(_mm_and_pd(in, ka), _mm_andnot_pd(in, inv_r * inv_r * inv_r));
    const __m128d gmj = vG * _mm_loadu_pd(m + j);
    sp -= gmj * wpot;
    sx -= gmj * wacc * dx;
    sy -= gmj * wacc * dy;
    sz -= gmj * wacc * dz;
    if (sym) {
      const __m128d g = vgmi * wacc;
      _mm_storeu_pd(pot + j, _mm_loadu_pd(pot + j) - vgmi * wpot);
      _mm_storeu_pd(gax + j, _mm_loadu_pd(gax + j) + g * dx);
      _mm_storeu_pd(gay + j, _mm_loadu_pd(gay + j) + g * dy);
      _mm_storeu_pd(gaz + j, _mm_loadu_pd(gaz + j) + g * dz);
    }
  }
  out[0] += sp[0] + sp[1];
  out[1] += sx[0] + sx[1];
  out[2] += sy[0] + sy[1];
  out[3] += sz[0] + sz[1];
  return j;
}
#endif

/** One target (xi, mi) against sources [j0, j1) of the particle arrays:
 *  returns the target's sums in pot_a[4] (pot, ax, ay, az, without G) and,
 *  when sym, adds the reaction to the sources (times G mi).  The spline
 *  case runs two sources at a time (p2p_spline_sse2) where SSE2 exists. */
static inline void p2p_row(const double *restrict x, const double *restrict y,
                           const double *restrict z, const double *restrict m, double *restrict pot,
                           double *restrict gax, double *restrict gay, double *restrict gaz,
                           size_t j0, size_t j1, const double xi[3], double gmi, int sym,
                           int plummer, double eps, double inv_H, double H2, double G,
                           double out[4]) {
  double sp = 0.0, sx = 0.0, sy = 0.0, sz = 0.0;
#if defined(__SSE2__)
  double vs[4] = {0.0, 0.0, 0.0, 0.0};
  if (!plummer)
    j0 = p2p_spline_sse2(x, y, z, m, pot, gax, gay, gaz, j0, j1, xi, gmi, sym, inv_H, H2, G, vs);
  sp = vs[0];
  sx = vs[1];
  sy = vs[2];
  sz = vs[3];
#endif
  if (plummer) {
    const double e2 = eps * eps;
    for (size_t j = j0; j < j1; j++) {
      const double dx = xi[0] - x[j], dy = xi[1] - y[j], dz = xi[2] - z[j];
      const double r2 = dx * dx + dy * dy + dz * dz;
      const double q = 1.0 / sqrt(r2 + e2);
      const double wpot = q, wacc = q * q * q;
      const double gmj = G * m[j];
      sp -= gmj * wpot;
      sx -= gmj * wacc * dx;
      sy -= gmj * wacc * dy;
      sz -= gmj * wacc * dz;
      if (sym) {
        pot[j] -= gmi * wpot;
        gax[j] += gmi * wacc * dx;
        gay[j] += gmi * wacc * dy;
        gaz[j] += gmi * wacc * dz;
      }
    }
  } else if (sym) {
    for (size_t j = j0; j < j1; j++) {
      const double dx = xi[0] - x[j], dy = xi[1] - y[j], dz = xi[2] - z[j];
      const double r2 = dx * dx + dy * dy + dz * dz;
      double wpot, wacc;
      gravity_spline_kernel(r2, inv_H, H2, &wpot, &wacc);
      const double gmj = G * m[j];
      sp -= gmj * wpot;
      sx -= gmj * wacc * dx;
      sy -= gmj * wacc * dy;
      sz -= gmj * wacc * dz;
      pot[j] -= gmi * wpot;
      gax[j] += gmi * wacc * dx;
      gay[j] += gmi * wacc * dy;
      gaz[j] += gmi * wacc * dz;
    }
  } else {
    for (size_t j = j0; j < j1; j++) {
      const double dx = xi[0] - x[j], dy = xi[1] - y[j], dz = xi[2] - z[j];
      const double r2 = dx * dx + dy * dy + dz * dz;
      double wpot, wacc;
      gravity_spline_kernel(r2, inv_H, H2, &wpot, &wacc);
      const double gmj = G * m[j];
      sp -= gmj * wpot;
      sx -= gmj * wacc * dx;
      sy -= gmj * wacc * dy;
      sz -= gmj * wacc * dz;
    }
  }
  out[0] = sp;
  out[1] = sx;
  out[2] = sy;
  out[3] = sz;
}

/* ------------------------------------------------------------------ lists */

/** The list the walks of this thread record into (NULL: none). */
static _Thread_local struct gravity_ilist *recording;

void gravity_record_begin(struct gravity_ilist *il) {
  recording = il;
  if (il) {
    il->count = 0;
    il->d_min = HUGE_VAL;
  }
}

void gravity_record_end(void) {
  recording = NULL;
}

void gravity_ilist_free(struct gravity_ilist *il) {
  free(il->item);
  memset(il, 0, sizeof *il);
}

static void record(const struct cell *a, const struct cell *b, int kind, int symmetric) {
  struct gravity_ilist *il = recording;
  if (il->count == il->capacity) {
    il->capacity = il->capacity ? 2 * il->capacity : 64;
    il->item = error_realloc(il->item, (size_t)il->capacity * sizeof *il->item,
                             "gravity interaction list");
  }
  il->item[il->count++] = (struct gravity_iitem){a, b, kind, symmetric};
}

static void record_distance(double r2) {
  if (recording && r2 < recording->d_min * recording->d_min) recording->d_min = sqrt(r2);
}

/** p2p_block with the softening tied to h (Gravity:softening_h_factor):
 *  each pair's softening is gravity_pair_softening(h_i, h_j), spline
 *  kernel; a plain scalar loop (the SSE2 path assumes one support). */
static void p2p_block_h(struct parts *p, size_t i0, size_t i1, size_t j0, size_t j1, int self,
                        int sym, const struct gravity_props *gp) {
  const double G = gp->G;
  for (size_t i = i0; i < i1; i++) {
    const double xi = p->x[i], yi = p->y[i], zi = p->z[i], hi = p->h[i];
    const double gmi = G * p->m[i];
    double sp = 0.0, sa[3] = {0.0, 0.0, 0.0};
    for (size_t j = self ? i + 1 : j0; j < j1; j++) {
      const double dx[3] = {xi - p->x[j], yi - p->y[j], zi - p->z[j]};
      const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
      const double eps = gravity_pair_softening(gp->eps, gp->h_factor, hi, p->h[j]);
      double wpot, wacc;
      gravity_softened_kernel(r2, eps, GRAVITY_SOFTENING_SPLINE, &wpot, &wacc);
      const double gmj = G * p->m[j];
      sp -= gmj * wpot;
      sa[0] -= gmj * wacc * dx[0];
      sa[1] -= gmj * wacc * dx[1];
      sa[2] -= gmj * wacc * dx[2];
      if (sym) {
        p->pot[j] -= gmi * wpot;
        p->gax[j] += gmi * wacc * dx[0];
        p->gay[j] += gmi * wacc * dx[1];
        p->gaz[j] += gmi * wacc * dx[2];
      }
    }
    p->pot[i] += sp;
    p->gax[i] += sa[0];
    p->gay[i] += sa[1];
    p->gaz[i] += sa[2];
  }
  const size_t ni = i1 - i0, nj = j1 - j0;
  counters.p2p += self ? ni * (ni - 1) / 2 : ni * nj;
}

/** Particles [i0, i1) against [j0, j1) (disjoint, or j0 = i + 1 for the
 *  self interaction when self is set); sym: the sources receive too. */
static void p2p_block(struct parts *p, size_t i0, size_t i1, size_t j0, size_t j1, int self,
                      int sym, const struct gravity_props *gp) {
  if (gp->h_factor > 0.0) {
    p2p_block_h(p, i0, i1, j0, j1, self, sym, gp);
    return;
  }
  const int plummer = gp->softening == GRAVITY_SOFTENING_PLUMMER;
  const double H = GRAVITY_SPLINE_H_OVER_EPS * gp->eps;
  const double inv_H = H > 0.0 ? 1.0 / H : 0.0, H2 = H * H;
  for (size_t i = i0; i < i1; i++) {
    const double xi[3] = {p->x[i], p->y[i], p->z[i]};
    double out[4];
    p2p_row(p->x, p->y, p->z, p->m, p->pot, p->gax, p->gay, p->gaz, self ? i + 1 : j0, j1, xi,
            gp->G * p->m[i], sym, plummer, gp->eps, inv_H, H2, gp->G, out);
    p->pot[i] += out[0];
    p->gax[i] += out[1];
    p->gay[i] += out[2];
    p->gaz[i] += out[3];
  }
  const size_t ni = i1 - i0, nj = j1 - j0;
  counters.p2p += self ? ni * (ni - 1) / 2 : ni * nj;
}

/** Where the calling thread's walks record their interactions instead of
 *  computing them (NULL: compute; gravity_gpu_record). */
static _Thread_local struct gravity_gpu_rec *gpu_sink;

void gravity_gpu_record(struct gravity_gpu_rec *r) {
  gpu_sink = r;
}

/** Append (target, source) to l. */
static void rec_add(struct gravity_rec_list *l, int target, int source) {
  if (l->n == l->cap) {
    l->cap = l->cap ? 2 * l->cap : 1024;
    l->target = error_realloc(l->target, l->cap * sizeof(int), "GPU gravity list");
    l->source = error_realloc(l->source, l->cap * sizeof(int), "GPU gravity list");
  }
  l->target[l->n] = target;
  l->source[l->n] = source;
  l->n++;
}

static void rec_list_free(struct gravity_rec_list *l) {
  free(l->target);
  free(l->source);
  memset(l, 0, sizeof *l);
}

void gravity_gpu_rec_free(struct gravity_gpu_rec *r) {
  rec_list_free(&r->part);
  rec_list_free(&r->field);
  rec_list_free(&r->part_sym);
  rec_list_free(&r->field_sym);
}

/** All pairs within leaf c, each once (symmetric). */
static void p2p_self(struct parts *p, const struct cell *c, const struct gravity_props *gp) {
  if (recording) record(c, NULL, 0, 1);
  if (gpu_sink) {
    rec_add(&gpu_sink->part, c->index, c->index);
    return;
  }
  p2p_block(p, c->offset, c->offset + c->count, c->offset, c->offset + c->count, 1, 1, gp);
}

/** Every particle of leaf a with every particle of leaf b; both updated
 *  when symmetric, only a's otherwise. */
static void p2p_pair(struct parts *p, const struct cell *a, const struct cell *b, int symmetric,
                     const struct gravity_props *gp) {
  if (recording) record(a, b, 0, symmetric);
  if (gpu_sink) {
    if (symmetric)
      rec_add(&gpu_sink->part_sym, a->index, b->index);
    else
      rec_add(&gpu_sink->part, a->index, b->index);
    return;
  }
  p2p_block(p, a->offset, a->offset + a->count, b->offset, b->offset + b->count, 0, symmetric, gp);
}

/* ------------------------------------------------------------------ walks */

/** The M2L of walk_pair with the expansion order a compile-time constant:
 *  gravity_derivatives and gravity_m2l(_sym) of gravity_iact.h, inlined
 *  once per order so that the compiler unrolls their loops and folds the
 *  multi-index arithmetic (several times faster than the run-time order).
 *  sym: both fields receive, R = z_b - z_a; else only fa, from mb. */
#define M2L_ORDER(P)                                                                          \
  static void m2l_order_##P(                                                                  \
      struct gravity_field *fa, struct gravity_field *fb, const struct gravity_multipole *ma, \
      const struct gravity_multipole *mb, const double R[3], double eps2, int sym) {          \
    double D[GRAVITY_NCOMP(P)];                                                               \
    if (sym) {                                                                                \
      gravity_derivatives(R, eps2, P, D);                                                     \
      gravity_m2l_sym(fa, fb, ma, mb, D, P);                                                  \
    } else {                                                                                  \
      const double Rab[3] = {-R[0], -R[1], -R[2]};                                            \
      gravity_derivatives(Rab, eps2, P, D);                                                   \
      gravity_m2l(fa, mb, D, P);                                                              \
    }                                                                                         \
  }
M2L_ORDER(1)
M2L_ORDER(2)
M2L_ORDER(3)
M2L_ORDER(4)
M2L_ORDER(5)

/** Mutual point-cell interactions of every particle of leaf `leaf` with the
 *  multipole of cell gs (gravity_m2p_p2l, order P a constant as in
 *  M2L_ORDER): the particles receive when upd_point, gs's field when
 *  upd_cell. */
#define M2P_ORDER(P)                                                                     \
  static void m2p_leaf_order_##P(struct parts *p, const struct cell *leaf,               \
                                 struct gravity_cell *gs, int upd_point, int upd_cell,   \
                                 double eps2, double G) {                                \
    for (size_t i = leaf->offset; i < leaf->offset + leaf->count; i++) {                 \
      const double R[3] = {gs->mp.com[0] - p->x[i], gs->mp.com[1] - p->y[i],             \
                           gs->mp.com[2] - p->z[i]};                                     \
      double D[GRAVITY_NCOMP(P)], pot = 0.0, a[3] = {0.0, 0.0, 0.0};                     \
      gravity_derivatives(R, eps2, P, D);                                                \
      gravity_m2p_p2l(p->m[i], &gs->mp, upd_cell ? &gs->field : NULL, D, P, G, &pot, a); \
      if (upd_point) {                                                                   \
        p->pot[i] += pot;                                                                \
        p->gax[i] += a[0];                                                               \
        p->gay[i] += a[1];                                                               \
        p->gaz[i] += a[2];                                                               \
      }                                                                                  \
    }                                                                                    \
  }
M2P_ORDER(1)
M2P_ORDER(2)
M2P_ORDER(3)
M2P_ORDER(4)
M2P_ORDER(5)

/** M2P/P2L of leaf against cell gs at run-time order p (see M2P_ORDER). */
static void m2p_leaf(struct parts *p, const struct cell *leaf, struct gravity_cell *gs,
                     int upd_point, int upd_cell, double eps2, double G, int pord) {
  switch (pord) {
    case 1:
      m2p_leaf_order_1(p, leaf, gs, upd_point, upd_cell, eps2, G);
      break;
    case 2:
      m2p_leaf_order_2(p, leaf, gs, upd_point, upd_cell, eps2, G);
      break;
    case 3:
      m2p_leaf_order_3(p, leaf, gs, upd_point, upd_cell, eps2, G);
      break;
    case 4:
      m2p_leaf_order_4(p, leaf, gs, upd_point, upd_cell, eps2, G);
      break;
    default:
      m2p_leaf_order_5(p, leaf, gs, upd_point, upd_cell, eps2, G);
      break;
  }
}

/** M2L between a and b at run-time order p (see M2L_ORDER). */
static void m2l_cells(struct gravity_cell *ga, struct gravity_cell *gb, const double R[3],
                      double eps2, int p, int sym) {
  switch (p) {
    case 1:
      m2l_order_1(&ga->field, &gb->field, &ga->mp, &gb->mp, R, eps2, sym);
      break;
    case 2:
      m2l_order_2(&ga->field, &gb->field, &ga->mp, &gb->mp, R, eps2, sym);
      break;
    case 3:
      m2l_order_3(&ga->field, &gb->field, &ga->mp, &gb->mp, R, eps2, sym);
      break;
    case 4:
      m2l_order_4(&ga->field, &gb->field, &ga->mp, &gb->mp, R, eps2, sym);
      break;
    default:
      m2l_order_5(&ga->field, &gb->field, &ga->mp, &gb->mp, R, eps2, sym);
      break;
  }
}

/** The acceptance parameters of gp (gravity_walk.h). */
static struct gravity_walk_params walk_params(const struct gravity_props *gp) {
  const struct gravity_walk_params wp = {gp->G,         gp->theta,    gp->epsilon_fmm,
                                         gp->h_support, gp->h_factor, gp->order};
  return wp;
}

/** Dual-tree walk between disjoint cells a and b (Dehnen 2002): each step
 *  is gravity_walk_choose's (gravity_walk.h, shared with the GPU's walk).
 *  symmetric: both cells receive (pair task), else only a (long-range
 *  task).  The decisions are symmetric in a and b, so the walk from b's
 *  side pairs the same interactions (momentum). */
static void walk_pair(struct parts *p, const struct cell *a, const struct cell *b, int symmetric,
                      struct gravity_cell *gc, const struct gravity_props *gp) {
  if (a->count == 0 || b->count == 0) return;
  if (gp->active) {
    /* a step of active particles only: a cell without one receives nothing
     * (the decisions are symmetric in a and b, so b may take a's place) */
    const int ra = gp->active[a->index], rb = symmetric && gp->active[b->index];
    if (!ra && !rb) return;
    if (!ra) {
      walk_pair(p, b, a, 0, gc, gp);
      return;
    }
    if (!rb) symmetric = 0;
  }
  struct gravity_cell *ga = gc + a->index, *gb = gc + b->index;
  const struct gravity_walk_params wp = walk_params(gp);
  int a_big = 0;
  double r2 = 0.0;
  counters.mac++;
  const int d =
      gravity_walk_choose((int)a->count, (int)b->count, a->split, b->split, &ga->mp, &gb->mp,
                          ga->a_min, gb->a_min, ga->h_support, gb->h_support, &wp, &a_big, &r2);
  if (d == GRAVITY_WALK_P2P) {
    p2p_pair(p, a, b, symmetric, gp);
  } else if (d == GRAVITY_WALK_M2P) {
    const struct cell *big = a_big ? a : b, *small = a_big ? b : a;
    counters.m2p += big->count;
    record_distance(r2);
    if (recording && (symmetric || a_big)) record(big, small, 1, 0);
    if (gpu_sink) {
      /* M2P to big's particles, P2L to small's local expansion */
      if (symmetric || a_big) rec_add(&gpu_sink->part, big->index, -1 - small->index);
      if (symmetric || !a_big) rec_add(&gpu_sink->field, small->index, -1 - big->index);
      return;
    }
    m2p_leaf(p, big, gc + small->index, symmetric || a_big, symmetric || !a_big, gp->eps2_expansion,
             gp->G, gp->order);
  } else if (d == GRAVITY_WALK_M2L) {
    counters.m2l++;
    record_distance(r2);
    if (gpu_sink) {
      /* one M2L per receiving cell */
      if (symmetric)
        rec_add(&gpu_sink->field_sym, a->index, b->index);
      else
        rec_add(&gpu_sink->field, a->index, b->index);
      return;
    }
    /* one-way: target a, source b, the tensor at z_a - z_b */
    const double R[3] = {gb->mp.com[0] - ga->mp.com[0], gb->mp.com[1] - ga->mp.com[1],
                         gb->mp.com[2] - ga->mp.com[2]};
    m2l_cells(ga, gb, R, gp->eps2_expansion, gp->order, symmetric);
  } else if (d != GRAVITY_WALK_NONE) {
    /* the larger cell that is split: its progeny meet the other */
    const int open_a = d == GRAVITY_WALK_OPEN_A;
    const struct cell *big = open_a ? a : b;
    for (int q = 0; q < 8; q++) {
      const struct cell *c = big->progeny[q];
      if (c == NULL) continue;
      if (open_a)
        walk_pair(p, c, b, symmetric, gc, gp);
      else
        walk_pair(p, a, c, symmetric, gc, gp);
    }
  }
}

/** All interactions within c: self of every progeny and every pair of them. */
static void walk_self(struct parts *p, const struct cell *c, struct gravity_cell *gc,
                      const struct gravity_props *gp) {
  if (c->count < 2 || (gp->active && !gp->active[c->index])) return;
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

void gravity_interact_pair_one_way(struct parts *p, const struct cell *ci, const struct cell *cj,
                                   struct gravity_cell *gc, const struct gravity_props *gp) {
  walk_pair(p, ci, cj, 0, gc, gp);
}

int gravity_top_pair_is_near(const struct cell *ci, const struct cell *cj,
                             const struct gravity_props *gp) {
  return gravity_walk_top_near(ci->bmin, ci->bmax, cj->bmin, cj->bmax, gp->theta, gp->h_support);
}

void gravity_walk_tree_arrays(const struct cell *cells, int nr_cells, int *progeny, int *count,
                              unsigned char *split) {
  for (int k = 0; k < nr_cells; k++) {
    const struct cell *c = cells + k;
    if (c->index != k) error_bug("cell %d has index %d", k, c->index);
    count[k] = (int)c->count;
    split[k] = (unsigned char)(c->split != 0);
    for (int q = 0; q < 8; q++)
      progeny[8 * k + q] = c->split && c->progeny[q] ? c->progeny[q]->index : -1;
  }
}

/** Misses of the walks with other ranks' cells (gravity_remote_misses). */
static _Atomic long remote_misses;

long gravity_remote_misses(int reset) {
  return reset ? atomic_exchange(&remote_misses, 0) : atomic_load(&remote_misses);
}

/** The one-way walk of a (receiving) with the top-level cell b of another
 *  rank known by its record: walk_pair's decisions, with b never opened.
 *  apply 0: only whether the walk would have to open b (or read its
 *  particles: P2P, or M2P/P2L with b the big leaf); returns 1 if so.
 *  apply 1: the interactions, and where b would have to be opened, the M2L
 *  of b's multipole all the same; returns the number of such places. */
static long walk_remote(struct parts *p, const struct cell *a, const struct gravity_remote *b,
                        struct gravity_cell *gc, const struct gravity_props *gp, int apply) {
  if (a->count == 0) return 0;
  struct gravity_cell *ga = gc + a->index;
  const struct gravity_walk_params wp = walk_params(gp);
  int a_big = 0;
  double r2 = 0.0;
  const int nb = b->count > INT_MAX ? INT_MAX : (int)b->count;
  if (apply) counters.mac++;
  const int d =
      gravity_walk_choose((int)a->count, nb, a->split, b->split, &ga->mp, &b->mp, ga->a_min,
                          b->a_min, ga->h_support, b->h_support, &wp, &a_big, &r2);
  if (d == GRAVITY_WALK_NONE) return 0;
  if (d == GRAVITY_WALK_OPEN_A) {
    long miss = 0;
    for (int q = 0; q < 8; q++)
      if (a->progeny[q]) {
        miss += walk_remote(p, a->progeny[q], b, gc, gp, apply);
        if (miss && !apply) return 1;
      }
    return miss;
  }
  const int ok = d == GRAVITY_WALK_M2L || (d == GRAVITY_WALK_M2P && a_big);
  if (!apply) return !ok;
  struct gravity_cell gb;
  memset(&gb.field, 0, sizeof gb.field);
  gb.mp = b->mp;
  gb.a_min = b->a_min;
  gb.h_support = b->h_support;
  if (d == GRAVITY_WALK_M2P && a_big) {
    counters.m2p += a->count;
    record_distance(r2);
    m2p_leaf(p, a, &gb, 1, 0, gp->eps2_expansion, gp->G, gp->order);
    return 0;
  }
  counters.m2l++;
  record_distance(r2);
  const double R[3] = {gb.mp.com[0] - ga->mp.com[0], gb.mp.com[1] - ga->mp.com[1],
                       gb.mp.com[2] - ga->mp.com[2]};
  m2l_cells(ga, &gb, R, gp->eps2_expansion, gp->order, 0);
  return !ok;
}

void gravity_long_range(struct parts *p, const struct cell *ci, const struct cell *tops, int nr_top,
                        struct gravity_cell *gc, const struct gravity_props *gp) {
  if (ci->count == 0 || (gp->active && !gp->active[ci->index])) return;
  /* with remote_only, only the other ranks' cells whose particles are not
   * all here; else those with particles here or a record (a grid of 64^3
   * cells is mostly empty); in the same order: the sums are those of the
   * full loop */
  const int *list = gp->remote_only ? gp->remote_partial
                    : gp->tops_used && tops == gp->tops_base && nr_top == gp->nr_tops
                        ? gp->tops_used
                        : NULL;
  const int nj = gp->remote_only ? gp->nr_remote_partial : list ? gp->nr_tops_used : nr_top;
  for (int k = 0; k < nj; k++) {
    const int j = list ? list[k] : k;
    const struct cell *cj = tops + j;
    if (cj == ci) continue;
    if (gp->remote_idx && gp->remote_idx[j] >= 0) {
      /* several MPI ranks: a cell of another rank, by its record unless the
       * walk must open it */
      const struct gravity_remote *rj = gp->remote + gp->remote_idx[j];
      if (gravity_walk_top_near(ci->bmin, ci->bmax, rj->bmin, rj->bmax, gp->theta, gp->h_support)) {
        if (!rj->complete)
          error_bug("top-level cell %d of another rank is near cell %d without its particles", j,
                    ci->index);
        continue; /* (a pair task) */
      }
      if (!walk_remote(p, ci, rj, gc, gp, 0))
        walk_remote(p, ci, rj, gc, gp, 1);
      else if (rj->complete)
        walk_pair(p, ci, cj, 0, gc, gp);
      else
        atomic_fetch_add(&remote_misses, walk_remote(p, ci, rj, gc, gp, 1));
      continue;
    }
    if (cj->count == 0 || gravity_top_pair_is_near(ci, cj, gp)) continue;
    walk_pair(p, ci, cj, 0, gc, gp);
  }
}

void gravity_back_fill(const struct gravity_back *b, const struct cell *c,
                       struct gravity_cell *gc) {
  gravity_back_fill_cell(b, c->index, gc);
  if (c->split)
    for (int q = 0; q < 8; q++)
      if (c->progeny[q]) gravity_back_fill(b, c->progeny[q], gc);
}

int gravity_remote_reads(const struct cell *ci, const struct gravity_props *gp) {
  if (ci->count == 0 || (gp->active && !gp->active[ci->index])) return 0;
  for (int k = 0; k < gp->nr_remote_partial; k++) {
    const int j = gp->remote_partial[k];
    const struct gravity_remote *rj = gp->remote + gp->remote_idx[j];
    if (j != ci->index &&
        !gravity_walk_top_near(ci->bmin, ci->bmax, rj->bmin, rj->bmax, gp->theta, gp->h_support))
      return 1;
  }
  return 0;
}

/* ------------------------------------------------------------------ down */

/** Push c's local expansion to its progeny (L2L) or its particles (L2P). */
static void down_rec(struct parts *p, const struct cell *c, struct gravity_cell *gc,
                     const struct gravity_props *gp) {
  if (c->count == 0 || (gp->active && !gp->active[c->index])) return;
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

/** L2P at every leaf of c's octree from the leaf's complete local
 *  expansion (a reuse step: the L2L of the last full evaluation stay). */
static void down_leaves(struct parts *p, const struct cell *c, struct gravity_cell *gc,
                        const struct gravity_props *gp) {
  if (c->count == 0) return;
  if (c->split) {
    for (int q = 0; q < 8; q++)
      if (c->progeny[q]) down_leaves(p, c->progeny[q], gc, gp);
    return;
  }
  const struct gravity_cell *g = gc + c->index;
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
  if (gp->replay)
    down_leaves(p, c, gc, gp);
  else
    down_rec(p, c, gc, gp);
}

void gravity_replay(struct parts *p, const struct gravity_ilist *il, struct gravity_cell *gc,
                    const struct gravity_props *gp) {
  for (int k = 0; k < il->count; k++) {
    const struct gravity_iitem *it = il->item + k;
    if (it->kind == 1)
      m2p_leaf(p, it->a, gc + it->b->index, 1, 0, gp->eps2_expansion, gp->G, gp->order);
    else if (it->b == NULL)
      p2p_block(p, it->a->offset, it->a->offset + it->a->count, it->a->offset,
                it->a->offset + it->a->count, 1, 1, gp);
    else
      p2p_block(p, it->a->offset, it->a->offset + it->a->count, it->b->offset,
                it->b->offset + it->b->count, 0, it->symmetric, gp);
  }
}

/** 1 if the box of cell t lies inside the box of cell c (octree boxes
 *  nest exactly: the centre of t decides). */
static int estimate_inside(const struct cell *t, const struct cell *c) {
  for (int d = 0; d < 3; d++) {
    const double m = t->loc[d] + 0.5 * t->width[d];
    if (!(m >= c->loc[d] && m < c->loc[d] + c->width[d])) return 0;
  }
  return 1;
}

/** Every interaction that the target t receives from the particles of src
 *  (a cell disjoint from t, t itself, or one holding it), one way: writes
 *  t's cells only. */
static void estimate_walk(struct parts *p, const struct cell *t, const struct cell *src,
                          struct gravity_cell *gc, const struct gravity_props *gp) {
  if (src->count == 0) return;
  if (src == t) {
    walk_self(p, t, gc, gp);
  } else if (estimate_inside(t, src)) {
    for (int q = 0; q < 8; q++)
      if (src->progeny[q]) estimate_walk(p, t, src->progeny[q], gc, gp);
  } else {
    walk_pair(p, t, src, 0, gc, gp);
  }
}

/** The targets of the estimate's walks below c (appended to *u): c, or
 *  where c holds more than GRAVITY_ESTIMATE_UNIT particles its octants,
 *  and theirs, so that one dense top-level cell (an impact puts its bodies
 *  in a few) is shared among the threads.  They depend on the particles
 *  only, not on the threads: the sums are the same with any number. */
static void estimate_units(const struct cell *c, const struct cell ***u, int *n, int *cap) {
  if (c->count == 0) return;
  if (c->split && c->count > GRAVITY_ESTIMATE_UNIT) {
    for (int q = 0; q < 8; q++)
      if (c->progeny[q]) estimate_units(c->progeny[q], u, n, cap);
    return;
  }
  if (*n == *cap) {
    *cap = *cap ? 2 * *cap : 256;
    *u = error_realloc(*u, (size_t)*cap * sizeof **u, "gravity estimate targets");
  }
  (*u)[(*n)++] = c;
}

/** Work of the threads of gravity_estimate: one phase, each item taken by
 *  one thread (next: the first not yet taken); phases 0 and 2 over the
 *  top-level cells, phase 1 over the targets (estimate_units). */
struct estimate_job {
  struct parts *p;
  const struct cell *tops;
  int nr_top, phase; /**< phase 0: up, 1: walks (gather form), 2: down */
  const struct cell **unit;
  int nr_units;
  int next;
  struct gravity_cell *gc;
  const struct gravity_props *gp;
};

static void *estimate_worker(void *arg) {
  struct estimate_job *job = arg;
  const int n = job->phase == 1 ? job->nr_units : job->nr_top;
  for (;;) {
    const int i = __atomic_fetch_add(&job->next, 1, __ATOMIC_RELAXED);
    if (i >= n) break;
    if (job->phase == 0) {
      gravity_up(job->p, job->tops + i, job->gc, job->gp);
    } else if (job->phase == 1) {
      /* every interaction the target receives, one way: writes its cells only */
      const struct cell *t = job->unit[i];
      for (int j = 0; j < job->nr_top; j++)
        estimate_walk(job->p, t, job->tops + j, job->gc, job->gp);
    } else {
      gravity_down(job->p, job->tops + i, job->gc, job->gp);
    }
  }
  return NULL;
}

/** Order of the targets: the most particles first (the threads' loads even
 *  out at the end); ties by position in the particle order. */
static int estimate_cmp_units(const void *a, const void *b) {
  const struct cell *ca = *(const struct cell *const *)a, *cb = *(const struct cell *const *)b;
  if (ca->count != cb->count) return ca->count < cb->count ? 1 : -1;
  return (ca->offset > cb->offset) - (ca->offset < cb->offset);
}

int gravity_estimate_needed(const struct parts *p, const struct gravity_props *gp) {
  if (!gp->enabled || gp->direct || gp->replay || !(gp->epsilon_fmm > 0.0)) return 0;
  for (size_t i = 0; i < p->count; i++)
    if (p->gax[i] == 0.0 && p->gay[i] == 0.0 && p->gaz[i] == 0.0) return 1;
  return 0;
}

int gravity_estimate(struct parts *p, const struct cell *tops, int nr_top, struct gravity_cell *gc,
                     const struct gravity_props *gp, int nthreads) {
  if (!gravity_estimate_needed(p, gp)) return 0;
  struct gravity_props ge = *gp;
  ge.epsilon_fmm = 0.0; /* the geometric criterion alone */
  ge.theta = GRAVITY_ESTIMATE_THETA;
  ge.active = NULL; /* (every particle: the walks write their targets only) */
  if (ge.order > GRAVITY_ESTIMATE_ORDER) ge.order = GRAVITY_ESTIMATE_ORDER;
  if (nthreads < 1) nthreads = 1;
  if (nthreads > 64) nthreads = 64;
  /* the calling thread computes (neither records for the GPU nor for a reuse) */
  struct gravity_gpu_rec *sink = gpu_sink;
  struct gravity_ilist *rec = recording;
  gpu_sink = NULL;
  recording = NULL;
  const struct cell **unit = NULL;
  int nr_units = 0, cap = 0;
  for (int i = 0; i < nr_top; i++) estimate_units(tops + i, &unit, &nr_units, &cap);
  if (nr_units > 1) qsort(unit, (size_t)nr_units, sizeof *unit, estimate_cmp_units);
  struct estimate_job job = {p, tops, nr_top, 0, unit, nr_units, 0, gc, &ge};
  for (job.phase = 0; job.phase < 3; job.phase++) {
    job.next = 0;
    if (nthreads == 1) {
      estimate_worker(&job);
      continue;
    }
    pthread_t tid[64];
    for (int t = 0; t < nthreads; t++)
      if (pthread_create(&tid[t], NULL, estimate_worker, &job) != 0)
        error_exit("gravity_estimate: cannot start thread %d", t);
    for (int t = 0; t < nthreads; t++) pthread_join(tid[t], NULL);
  }
  free(unit);
  gpu_sink = sink;
  recording = rec;
  return 1;
}

void gravity_tree_all(struct parts *p, const struct cell *tops, int nr_top, struct gravity_cell *gc,
                      const struct gravity_props *gp) {
  gravity_estimate(p, tops, nr_top, gc, gp, 1);
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
  double h_factor; /**< Gravity:softening_h_factor (0: the constant eps) */
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
      const double eps = gravity_pair_softening(job->eps, job->h_factor, p->h[i], p->h[j]);
      gravity_p2p(dx, r2, p->m[j], job->G, eps, job->softening, &pot, a);
    }
    p->pot[i] += pot;
    p->gax[i] += a[0];
    p->gay[i] += a[1];
    p->gaz[i] += a[2];
  }
  return NULL;
}

static void direct_threads(struct parts *p, double G, double eps, int softening, double h_factor,
                           int nthreads);

void gravity_direct(struct parts *p, double G, double eps, int softening, int nthreads) {
  gravity_direct_h(p, G, eps, softening, 0.0, nthreads);
}

void gravity_direct_h(struct parts *p, double G, double eps, int softening, double h_factor,
                      int nthreads) {
  if (h_factor > 0.0 && softening != GRAVITY_SOFTENING_SPLINE)
    error_exit("gravity: the softening tied to h needs the spline softening kernel");
  const size_t n = p->count;
  memset(p->gax, 0, n * sizeof(double));
  memset(p->gay, 0, n * sizeof(double));
  memset(p->gaz, 0, n * sizeof(double));
  memset(p->pot, 0, n * sizeof(double));
  if (nthreads <= 1) {
    /* Symmetric: each pair once. */
    struct gravity_props gp;
    gravity_props_set(&gp, G, 0.0, eps, softening, 1);
    gp.h_factor = h_factor;
    struct cell all;
    memset(&all, 0, sizeof all);
    all.offset = 0;
    all.count = p->count;
    p2p_self(p, &all, &gp);
  } else {
    direct_threads(p, G, eps, softening, h_factor, nthreads);
  }
}

/** Gather-form direct summation over nthreads POSIX threads. */
static void direct_threads(struct parts *p, double G, double eps, int softening, double h_factor,
                           int nthreads) {
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
    job[t].h_factor = h_factor;
    if (pthread_create(&tid[t], NULL, direct_gather, &job[t]) != 0)
      error_exit("gravity_direct: cannot start thread %d", t);
  }
  for (int t = 0; t < nthreads; t++) pthread_join(tid[t], NULL);
}

double gravity_pairs_energy(const double *xmh, size_t n, const struct gravity_props *gp) {
  double e = 0.0;
  for (size_t i = 0; i < n; i++) {
    const double *a = xmh + 5 * i;
    double s = 0.0;
    for (size_t k = i + 1; k < n; k++) {
      const double *b = xmh + 5 * k;
      const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
      double wpot, wacc;
      gravity_softened_kernel(dx * dx + dy * dy + dz * dz,
                              gravity_pair_softening(gp->eps, gp->h_factor, a[4], b[4]),
                              gp->softening, &wpot, &wacc);
      s += b[3] * wpot;
    }
    e -= gp->G * a[3] * s;
  }
  return e;
}

double gravity_potential_energy(const struct parts *p) {
  double e = 0.0;
  for (size_t i = 0; i < p->count; i++)
    if (!(p->flags[i] & PART_FOREIGN)) e += p->m[i] * p->pot[i]; /* (MPI: copies) */
  return 0.5 * e;
}
