/* The tree walks of self-gravity as inline functions on index arrays, for
 * a walk that records its interactions (what gravity_gpu_record makes the
 * CPU's recursive walks of gravity_cpu.c do): the decisions of walk_pair
 * (gravity_walk_decide), the near test of two top-level cells
 * (gravity_walk_top_near) and a walk with an explicit stack from one root
 * (gravity_walk_run).  The GPU's walk kernel (tasks/gravity/gravity_gpu.cu)
 * runs gravity_walk_run from every root; tests/unit/test_gravity_walk.c runs it
 * on the CPU and checks that it records the same interactions as the
 * recursive walks.  theory/gravity.md, "On the GPU". */
#ifndef BOLIDE_GRAVITY_WALK_H
#define BOLIDE_GRAVITY_WALK_H

#include "tasks/gravity/gravity_iact.h"

/** A leaf meeting a cell GRAVITY_LOPSIDED times smaller (radius) interacts
 *  particle by particle (gravity_walk_decide). */
#define GRAVITY_LOPSIDED 2.0

/** Opening angle, in units of Gravity:theta_cr, of an interaction whose
 *  cells lack the adaptive criterion's acceleration scale (a particle with
 *  ga = 0).  A run's first evaluation normally has the scale of
 *  gravity_estimate's pass (gravity_cpu.h); this is the fallback where that
 *  did not run (0.7: the 99th percentile of test_gravity's sets under 1e-3). */
#define GRAVITY_THETA_FIRST 0.7

/** Entries of a GPU walker's stack (3 ints each, in local memory, which
 *  the device reserves for every thread it can hold at once: 132 x 2048
 *  threads of an H200 x 3 kB = 0.8 GB).  A walker whose stack fills hands
 *  it on (gravity_walk_spill); the CPU's test gives its walkers more. */
#define GRAVITY_WALK_STACK 256

/** The cell tree as the walk reads it, by cell index. */
struct gravity_walk_tree {
  const int *progeny;                 /**< 8 per cell: child cell or -1 */
  const int *count;                   /**< particles of each cell */
  const unsigned char *split;         /**< 1: the cell has progeny */
  const struct gravity_multipole *mp; /**< multipoles (com, r_max, M[0]) */
  const double *a_min, *h_support;    /**< struct gravity_cell's (gravity_up) */
  const unsigned char *active;        /**< a step of active particles only (time bins): per cell,
                                           whether it receives (gravity_props.active); NULL:
                                           every cell */
};

/** The acceptance parameters of struct gravity_props. */
struct gravity_walk_params {
  double G, theta, epsilon_fmm, h_support, h_factor;
  int order;
};

/** What the walk records: four lists of (target, source) cell pairs, in
 *  the encoding of struct gravity_gpu_rec (source < 0: -1 - cell, an M2P
 *  or P2L source).  0: part, 1: field, 2: part_sym, 3: field_sym.  Entries
 *  past cap[k] are counted but not written (the caller grows the lists and
 *  walks again). */
struct gravity_walk_lists {
  int *target[4], *source[4];
  unsigned long long *n; /**< 4 counters */
  unsigned long long cap[4];
};

enum { GRAVITY_REC_PART, GRAVITY_REC_FIELD, GRAVITY_REC_PART_SYM, GRAVITY_REC_FIELD_SYM };

/** Entries a walker keeps of each list before it appends them (one atomic
 *  add on the GPU per so many entries, not one per entry). */
#define GRAVITY_WALK_BUF 16

/** A walker's entries not yet appended. */
struct gravity_walk_buf {
  int t[4][GRAVITY_WALK_BUF], s[4][GRAVITY_WALK_BUF];
  int n[4];
};

/** Append the kept entries of list k (atomically on the GPU). */
BOLIDE_INLINE void gravity_walk_flush(const struct gravity_walk_lists *L,
                                      struct gravity_walk_buf *B, int k) {
  const int m = B->n[k];
  if (m == 0) return;
#ifdef __CUDA_ARCH__
  const unsigned long long i0 = atomicAdd(L->n + k, (unsigned long long)m);
#else
  const unsigned long long i0 = L->n[k];
  L->n[k] += (unsigned long long)m;
#endif
  for (int q = 0; q < m; q++)
    if (i0 + (unsigned long long)q < L->cap[k]) {
      L->target[k][i0 + q] = B->t[k][q];
      L->source[k][i0 + q] = B->s[k][q];
    }
  B->n[k] = 0;
}

/** Add (t, s) to list k. */
BOLIDE_INLINE void gravity_walk_emit(const struct gravity_walk_lists *L, struct gravity_walk_buf *B,
                                     int k, int t, int s) {
  if (B->n[k] == GRAVITY_WALK_BUF) gravity_walk_flush(L, B, k);
  B->t[k][B->n[k]] = t;
  B->s[k][B->n[k]] = s;
  B->n[k]++;
}

/** Outcomes of gravity_walk_decide. */
enum {
  GRAVITY_WALK_NONE,   /**< an empty cell: nothing */
  GRAVITY_WALK_M2L,    /**< multipole to local expansion */
  GRAVITY_WALK_P2P,    /**< two leaves, particle by particle */
  GRAVITY_WALK_M2P,    /**< a leaf much larger than a split cell: M2P to it, P2L back */
  GRAVITY_WALK_OPEN_A, /**< open a (its children meet b) */
  GRAVITY_WALK_OPEN_B  /**< open b */
};

/** Acceptance of the interaction between cells a and b (multipoles ma,
 *  mb, previous-pass scales a_min, largest supports hs), the same in both
 *  directions (mutual interactions conserve momentum): the geometric
 *  criterion and, where the previous pass gave a scale, the adaptive one
 *  (gravity_mac_power, the multipoles' power) for a and for b.  Without a
 *  scale (a particle with ga = 0 where gravity_estimate did not run) while
 *  the adaptive criterion is on, a tighter geometric angle stands in for it.
 *  The support beyond which every pair of a and b is Newtonian is the
 *  constant one or, with the softening tied to h, the larger of the two
 *  cells' largest supports. */
BOLIDE_INLINE int gravity_walk_accept(const struct gravity_multipole *ma,
                                      const struct gravity_multipole *mb, double a_min_a,
                                      double a_min_b, double hs_a, double hs_b, double r2,
                                      const struct gravity_walk_params *wp) {
  const double theta = (wp->epsilon_fmm > 0.0 && (a_min_a <= 0.0 || a_min_b <= 0.0))
                           ? GRAVITY_THETA_FIRST * wp->theta
                           : wp->theta;
  const double hs = wp->h_factor > 0.0 ? fmax(hs_a, hs_b) : wp->h_support;
  if (!gravity_mac(ma->r_max, mb->r_max, r2, theta, hs)) return 0;
  return gravity_mac_power(wp->G, mb->power, ma->r_max, mb->r_max, r2, wp->order, wp->epsilon_fmm,
                           a_min_a) &&
         gravity_mac_power(wp->G, ma->power, mb->r_max, ma->r_max, r2, wp->order, wp->epsilon_fmm,
                           a_min_b);
}

/** The dual-tree walk's step between disjoint cells a and b (Dehnen 2002),
 *  from what it reads of them (particle counts, split flags, multipoles,
 *  a_min, h_support): M2L where the criterion accepts, unless one side is
 *  a leaf GRAVITY_LOPSIDED times larger than the other (then P2P if the
 *  other is a leaf too, else M2P to the big leaf's particles and P2L back:
 *  a local expansion as large as the leaf would add up the truncation
 *  errors of the many small cells it meets); P2P between two leaves; else
 *  open the larger cell that can be opened (ties: a).  *a_big: for M2P,
 *  whether a is the big leaf; *r2: the squared distance of the centres. */
BOLIDE_INLINE int gravity_walk_choose(int count_a, int count_b, int split_a, int split_b,
                                      const struct gravity_multipole *ma,
                                      const struct gravity_multipole *mb, double a_min_a,
                                      double a_min_b, double hs_a, double hs_b,
                                      const struct gravity_walk_params *wp, int *a_big,
                                      double *r2) {
  if (count_a == 0 || count_b == 0) return GRAVITY_WALK_NONE;
  const double R[3] = {mb->com[0] - ma->com[0], mb->com[1] - ma->com[1], mb->com[2] - ma->com[2]};
  *r2 = R[0] * R[0] + R[1] * R[1] + R[2] * R[2];
  if (gravity_walk_accept(ma, mb, a_min_a, a_min_b, hs_a, hs_b, *r2, wp)) {
    *a_big = ma->r_max >= mb->r_max;
    const int split_big = *a_big ? split_a : split_b, split_small = *a_big ? split_b : split_a;
    const double r_big = *a_big ? ma->r_max : mb->r_max, r_small = *a_big ? mb->r_max : ma->r_max;
    if (!split_big && r_big > GRAVITY_LOPSIDED * r_small)
      return split_small ? GRAVITY_WALK_M2P : GRAVITY_WALK_P2P;
    return GRAVITY_WALK_M2L;
  }
  if (!split_a && !split_b) return GRAVITY_WALK_P2P;
  return split_a && (!split_b || ma->r_max >= mb->r_max) ? GRAVITY_WALK_OPEN_A
                                                         : GRAVITY_WALK_OPEN_B;
}

/** gravity_walk_choose for cells a and b of the tree T. */
BOLIDE_INLINE int gravity_walk_decide(const struct gravity_walk_tree *T,
                                      const struct gravity_walk_params *wp, int a, int b,
                                      int *a_big) {
  double r2;
  return gravity_walk_choose(T->count[a], T->count[b], T->split[a], T->split[b], T->mp + a,
                             T->mp + b, T->a_min[a], T->a_min[b], T->h_support[a], T->h_support[b],
                             wp, a_big, &r2);
}

/** Whether two top-level cells, with bounding boxes lo/hi (3 each), are
 *  near: their walk is a pair task's (symmetric) rather than a long-range
 *  one (gravity_top_pair_is_near). */
BOLIDE_INLINE int gravity_walk_top_near(const double *lo_i, const double *hi_i, const double *lo_j,
                                        const double *hi_j, double theta, double h_support) {
  double ri2 = 0.0, rj2 = 0.0, d2 = 0.0;
  for (int k = 0; k < 3; k++) {
    const double wi = hi_i[k] - lo_i[k];
    const double wj = hi_j[k] - lo_j[k];
    const double d = 0.5 * (lo_j[k] + hi_j[k] - lo_i[k] - hi_i[k]);
    ri2 += 0.25 * wi * wi;
    rj2 += 0.25 * wj * wj;
    d2 += d * d;
  }
  return !gravity_mac(sqrt(ri2), sqrt(rj2), d2, theta, h_support);
}

/** Root r of the nt x nt pairs (i, j) = (r / nt, r % nt) of top-level
 *  cells top[i] and top[j] (top NULL: i and j; the non-empty ones only, so
 *  that a grid of mostly empty cells makes no nt^2 roots), with particle
 *  counts count[] by cell and boxes lo_hi by i (lo then hi, 6 doubles), as
 *  the CPU's tasks divide the walks: i == j the self walk, a near pair
 *  (gravity_walk_top_near) with j > i the symmetric walk, a far pair the
 *  long-range walk of i.  skip (several MPI ranks; NULL: none), by i: 1
 *  for a cell of copies only, which receives nothing (no self or
 *  long-range walk; a near pair with a cell of this rank walked one way,
 *  for that cell, as gravity_task.c does), 2 for a cell of which only some
 *  particles are here, which no walk reads (the host reads it by its
 *  record).  Returns 1 with the walk's stack entry (a, b, sym) of cell
 *  indices in item, 0 where the root has no walk (an empty or skipped
 *  cell, a near pair with j < i). */
BOLIDE_INLINE int gravity_walk_root(const int *count, const double *lo_hi, int nt, double theta,
                                    double h_support_top, const unsigned char *skip, const int *top,
                                    long long r, int item[3]) {
  const int i = (int)(r / nt), j = (int)(r % nt);
  const int ci = top ? top[i] : i, cj = top ? top[j] : j;
  if (count[ci] == 0 || count[cj] == 0) return 0;
  const int si = skip ? skip[i] : 0, sj = skip ? skip[j] : 0;
  if (si == 2 || sj == 2) return 0;
  item[0] = ci, item[1] = cj, item[2] = 1;
  if (i == j) return si == 0;
  const int near = gravity_walk_top_near(lo_hi + 6 * i, lo_hi + 6 * i + 3, lo_hi + 6 * j,
                                         lo_hi + 6 * j + 3, theta, h_support_top);
  if (near) {
    if (j < i || (si && sj)) return 0;
    if (si || sj) {
      /* one way, the cell of this rank's particles receiving */
      item[0] = si ? cj : ci, item[1] = si ? ci : cj, item[2] = 0;
    }
    return 1;
  }
  item[2] = 0;
  return si == 0;
}

/** The walk from the n entries (a, b, sym) on stack, recorded in L:
 *  a == b: every interaction within the cell (the self walk: each child's
 *  own and each pair of children, symmetric); else the pair walk of a with
 *  b, both receiving (sym) or only a (a long-range walk).  Entries go to
 *  B (B->n zeroed by the caller once, gravity_walk_flush of each list when
 *  the walker is done).  stack: room for cap entries of 3 ints.  At most
 *  budget entries are taken from the stack, and none whose successors
 *  would not fit on it; returns the number left on it (0: the walk is
 *  complete; on the GPU the rest goes to other threads,
 *  gravity_walk_spill).  The entries are independent: any division of
 *  them among walkers records the same interactions. */
BOLIDE_INLINE int gravity_walk_run(const struct gravity_walk_tree *T,
                                   const struct gravity_walk_params *wp,
                                   const struct gravity_walk_lists *L, struct gravity_walk_buf *B,
                                   int *stack, int cap, int n, long long budget) {
  for (long long step = 0; n > 0 && step < budget; step++) {
    n--;
    int a = stack[3 * n], b = stack[3 * n + 1], s = stack[3 * n + 2];
    if (T->active) {
      /* a step of active particles only: a cell that is not marked receives
       * nothing; the decisions are symmetric in a and b, so b may take a's
       * place (the CPU's walk_pair, tasks/gravity/gravity_cpu.c) */
      if (a == b) {
        if (!T->active[a]) continue;
      } else {
        const int ra = T->active[a], rb = s && T->active[b];
        if (!ra && !rb) continue;
        if (!ra) {
          const int t = a;
          a = b, b = t;
        }
        if (!ra || !rb) s = 0;
      }
    }
    if (a == b) { /* self */
      if (T->count[a] < 2) continue;
      if (!T->split[a]) {
        gravity_walk_emit(L, B, GRAVITY_REC_PART, a, a);
        continue;
      }
      if (n + 36 > cap) return n + 1; /* the entry stays */
      for (int q = 0; q < 8; q++) {
        const int cq = T->progeny[8 * a + q];
        if (cq < 0) continue;
        stack[3 * n] = cq, stack[3 * n + 1] = cq, stack[3 * n + 2] = 1, n++;
        for (int r = q + 1; r < 8; r++) {
          const int cr = T->progeny[8 * a + r];
          if (cr < 0) continue;
          stack[3 * n] = cq, stack[3 * n + 1] = cr, stack[3 * n + 2] = 1, n++;
        }
      }
      continue;
    }
    int a_big = 0;
    const int d = gravity_walk_decide(T, wp, a, b, &a_big);
    if (d == GRAVITY_WALK_P2P) {
      gravity_walk_emit(L, B, s ? GRAVITY_REC_PART_SYM : GRAVITY_REC_PART, a, b);
    } else if (d == GRAVITY_WALK_M2P) {
      const int big = a_big ? a : b, small = a_big ? b : a;
      if (s || a_big) gravity_walk_emit(L, B, GRAVITY_REC_PART, big, -1 - small);
      if (s || !a_big) gravity_walk_emit(L, B, GRAVITY_REC_FIELD, small, -1 - big);
    } else if (d == GRAVITY_WALK_M2L) {
      gravity_walk_emit(L, B, s ? GRAVITY_REC_FIELD_SYM : GRAVITY_REC_FIELD, a, b);
    } else if (d != GRAVITY_WALK_NONE) { /* open a or b: its children meet the other */
      const int open_a = d == GRAVITY_WALK_OPEN_A, big = open_a ? a : b;
      if (n + 8 > cap) return n + 1;
      for (int q = 0; q < 8; q++) {
        const int c = T->progeny[8 * big + q];
        if (c < 0) continue;
        stack[3 * n] = open_a ? c : a, stack[3 * n + 1] = open_a ? b : c, stack[3 * n + 2] = s;
        n++;
      }
    }
  }
  return n;
}

/** A queue of walk entries (a, b, sym) that walkers hand on: item holds
 *  cap entries of 3 ints; *n counts those offered (it may pass cap: the
 *  entries that did not fit stayed with their walker). */
struct gravity_walk_queue {
  int *item;
  unsigned long long *n;
  unsigned long long cap;
};

/** Move the top entries of the n on stack to Q (atomically on the GPU) as
 *  far as Q has room; those that do not fit stay at the bottom of stack.
 *  Returns the number that stayed. */
BOLIDE_INLINE int gravity_walk_spill(const struct gravity_walk_queue *Q, int *stack, int n) {
  if (n <= 0) return n;
#ifdef __CUDA_ARCH__
  const unsigned long long i0 = atomicAdd(Q->n, (unsigned long long)n);
#else
  const unsigned long long i0 = *Q->n;
  *Q->n += (unsigned long long)n;
#endif
  const unsigned long long room = i0 >= Q->cap ? 0 : Q->cap - i0;
  const int fit = room < (unsigned long long)n ? (int)room : n;
  for (int q = 0; q < fit; q++)
    for (int k = 0; k < 3; k++) Q->item[3 * (i0 + q) + k] = stack[3 * (n - 1 - q) + k];
  return n - fit;
}

#endif
