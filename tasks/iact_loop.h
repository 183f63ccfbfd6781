/* The interaction-loop skeleton, written once for every task family
 * (theory/architecture.md, rule 2, "three layers": pair function, loop
 * skeleton, task).
 *
 * A task family includes this header after naming its interaction:
 *
 *   #define IACT_LOOP_NAME density
 *   #define IACT_LOOP_SYM(p, i, j, r2, dx, hi, hj)    density_iact(p, i, j, r2, dx, hi, hj)
 *   #define IACT_LOOP_NONSYM(p, i, j, r2, dx, hi, hj) density_iact_gather(p, i, j, r2, dx, hi, hj)
 *   #define IACT_LOOP_ACTIVE(p, i) ((p)->flags[i] & PART_ACTIVE)      (optional)
 *   #include "tasks/iact_loop.h"
 *
 * which defines, for the macros given:
 *   IACT_LOOP_SYM (symmetric form: updates i and j; called once per pair with
 *   r < max(H_i, H_j), H = kernel_gamma * h):
 *     static void loop_density_self(struct parts *p, const struct cell *c);
 *     static void loop_density_pair(struct parts *p, const struct cell *ci,
 *                                   const struct cell *cj, const double shift[3]);
 *   IACT_LOOP_NONSYM (gather form: updates i only; called for every ordered
 *   (i, j), i != j, with r < H_i; the form the GPU and the ghost's smoothing
 *   length iteration use):
 *     static void loop_density_self_gather(struct parts *p, const struct cell *c);
 *     static void loop_density_pair_gather(struct parts *p, const struct cell *ci,
 *                                          const struct cell *cj, const double shift[3]);
 *   The gather pair updates the particles of ci from those of cj only: a pair
 *   task calls it twice, (ci, cj, shift) and (cj, ci, -shift).  (ci == cj is
 *   allowed only with a non-zero shift, as in a box of one periodic cell.)  Particles i
 *   for which IACT_LOOP_ACTIVE(p, i) is false are skipped (default: none).
 *
 * Optional: IACT_LOOP_ACC_BEGIN(p, i) and IACT_LOOP_ACC_END(p, i) open and
 * close the inner loop over j of every leaf loop, so that the interaction
 * macros can sum particle i's terms in local variables (registers) and
 * store them once, instead of updating the arrays for every pair (the arrays
 * may alias, so the compiler cannot keep them in registers by itself).
 *
 * Arguments of the interaction macros: p the particles, i and j indices into
 * them, r2 = |dx|^2, dx (const double[3]) = (x_i - x_j) - shift: the
 * separation from the image of j at x_j + shift, hi and hj the smoothing
 * lengths.  In a pair, i always belongs to ci and j to cj.
 *
 * The pair loops recurse into the octrees, pruning every pair of sub-cells
 * whose bounding boxes (grown by the cells' dx_max) are farther apart than
 * the largest kernel support involved (kernel_gamma * h_max); at leaves they
 * loop over both ranges.  A cell may be paired with its own periodic image
 * (ci == cj, shift != 0: a box of one or two top-level cells); then every
 * ordered (i, j) is visited, which counts each interaction once.  The
 * macros are undefined at the end, so the header can be included again. */
#include <math.h>
#include <stdint.h>

#include "src/cell.h"
#include "tasks/hydro/kernel.h"
#include "src/part.h"

#ifndef IACT_LOOP_NAME
#error "define IACT_LOOP_NAME before including iact_loop.h"
#endif
#if !defined(IACT_LOOP_SYM) && !defined(IACT_LOOP_NONSYM)
#error "define IACT_LOOP_SYM and/or IACT_LOOP_NONSYM before including iact_loop.h"
#endif
#ifndef IACT_LOOP_ACTIVE
#define IACT_LOOP_ACTIVE(p, i) 1
#endif
#ifndef IACT_LOOP_ACC_BEGIN
#define IACT_LOOP_ACC_BEGIN(p, i)
#endif
#ifndef IACT_LOOP_ACC_END
#define IACT_LOOP_ACC_END(p, i)
#endif

#define IACT_LOOP_PASTE2(a, b, c) a##b##c
#define IACT_LOOP_PASTE(a, b, c) IACT_LOOP_PASTE2(a, b, c)
/** loop_<NAME><suffix> */
#define IACT_LOOP_FN(suffix) IACT_LOOP_PASTE(loop_, IACT_LOOP_NAME, suffix)

#ifndef BOLIDE_IACT_LOOP_COMMON
#define BOLIDE_IACT_LOOP_COMMON
/** Particles of cj taken at a time by a leaf pair (a stack list of indices). */
#define IACT_LOOP_BLOCK 512

/** The zero shift of pairs inside one cell. */
static const double iact_loop_no_shift[3] = {0.0, 0.0, 0.0};

/** The cells' part of the widening, computed once per pair of cells: the
 *  leaf loops test every particle against iact_loop_prune_r2_pad(R, pad). */
__attribute__((unused)) static double iact_loop_prune_pad(const struct cell *ci,
                                                          const struct cell *cj,
                                                          const double shift[3]) {
  double scale = 0.0;
  for (int k = 0; k < 3; k++)
    scale += fabs(ci->loc[k]) + ci->width[k] + fabs(cj->loc[k]) + cj->width[k] + fabs(shift[k]);
  return 1e-13 * scale;
}
BOLIDE_ALWAYS_INLINE double iact_loop_prune_r2_pad(double R, double pad) {
  const double Rs = R * (1.0 + 1e-10) + pad;
  return Rs * Rs;
}
/** Square of the pruning radius R for cells ci and cj (shift applied to cj),
 *  widened by a relative 1e-10 and by 1e-13 of the coordinates' magnitude:
 *  the bounding-box distance and the particles' distances are rounded
 *  differently, and pruning must never drop a pair that the leaf test keeps. */
__attribute__((unused)) static double iact_loop_prune_r2(double R, const struct cell *ci,
                                                         const struct cell *cj,
                                                         const double shift[3]) {
  return iact_loop_prune_r2_pad(R, iact_loop_prune_pad(ci, cj, shift));
}

/** Whether the loops take cell c as a leaf: not split, or small enough
 *  (Scheduler:cpu_leaf_size) that looping over all its pairs costs less
 *  than recursing into its octants (its particles are one range). */
BOLIDE_ALWAYS_INLINE int iact_loop_leaf(const struct cell *c) {
  return !c->split || c->count <= (size_t)cell_loop_leaf_max;
}

/** The first pass of a leaf loop, without branches: of the candidates j
 *  (list[0..n) when list is given, else j0 .. j0 + n - 1), the positions k
 *  in 0 .. n - 1 of those that i at xi reaches into hit[], their number
 *  returned (the candidate is list[k], or j0 + k).  dx = (x_i
 *  - x_j) - shift, the interaction's own expression; a candidate is kept
 *  when r2 < Hi2, or with sym also when r2 < (kernel_gamma h_j)^2, and
 *  never when j == skip. */
BOLIDE_ALWAYS_INLINE size_t iact_loop_hits(const double *BOLIDE_RESTRICT x,
                                           const double *BOLIDE_RESTRICT y,
                                           const double *BOLIDE_RESTRICT z,
                                           const double *BOLIDE_RESTRICT h, const size_t *list,
                                           size_t j0, size_t n, const double xi[3],
                                           const double shift[3], double Hi2, int sym, size_t skip,
                                           size_t *BOLIDE_RESTRICT hit) {
  size_t nh = 0;
  for (size_t k = 0; k < n; k++) {
    const size_t j = list ? list[k] : j0 + k;
    const double dx[3] = {(xi[0] - x[j]) - shift[0], (xi[1] - y[j]) - shift[1],
                          (xi[2] - z[j]) - shift[2]};
    const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
    const double Hj = kernel_gamma * h[j];
    hit[nh] = k;
    nh += ((r2 < Hi2) | (sym && r2 < Hj * Hj)) & (j != skip);
  }
  return nh;
}
#endif

/* ------------------------------------------------------------ symmetric form */
#ifdef IACT_LOOP_SYM

/* The sums of the particles j of a leaf loop (the symmetric form's second
 * side) are kept in a short contiguous array while the loop runs, loaded
 * from the particle arrays before and stored after: a few cache lines per
 * neighbour instead of one per summed field.  Every sum takes the same
 * additions in the same order as it would in the arrays, so the results
 * are the same bit for bit.  A family that names no cache updates the
 * arrays directly (the macros below do nothing). */
#ifndef IACT_LOOP_JACC_T
#define IACT_LOOP_JACC_T char
#define IACT_LOOP_JACC_LOAD(p, j, a) ((void)(a))
#define IACT_LOOP_JACC_STORE(p, j, a) ((void)(a))
#define IACT_LOOP_SYM_J(p, i, j, r2, dx, hi, hj, aj) IACT_LOOP_SYM(p, i, j, r2, dx, hi, hj)
#define IACT_LOOP_ACC_END_J(p, i, ai) IACT_LOOP_ACC_END(p, i)
#endif

/** Leaf pair, symmetric: every i of ci with every j of cj (at x_j + shift).
 *  cj is taken in blocks; each block is first reduced to the particles that
 *  can reach ci's bounding box (grown by ci's drift), whose sums are cached,
 *  then every i that can reach cj's box loops over that short list.  A cell
 *  paired with its own image (ci == cj) updates the arrays directly. */
__attribute__((unused)) static void IACT_LOOP_FN(_pair_leaf)(struct parts *p, const struct cell *ci,
                                                             const struct cell *cj,
                                                             const double shift[3]) {
  const double *BOLIDE_RESTRICT x = p->x, *BOLIDE_RESTRICT y = p->y, *BOLIDE_RESTRICT z = p->z;
  const double *BOLIDE_RESTRICT h = p->h;
  const double Hi_max = kernel_gamma * ci->h_max, Hj_max = kernel_gamma * cj->h_max;
  const double back[3] = {-shift[0], -shift[1], -shift[2]};
  const size_t iend = ci->offset + ci->count, jend = cj->offset + cj->count;
  const double pad = iact_loop_prune_pad(ci, cj, shift);
  const int direct = ci == cj;
  size_t list[IACT_LOOP_BLOCK], hit[IACT_LOOP_BLOCK];
  IACT_LOOP_JACC_T cache[IACT_LOOP_BLOCK];
  for (size_t j0 = cj->offset; j0 < jend; j0 += IACT_LOOP_BLOCK) {
    const size_t j1 = jend - j0 > IACT_LOOP_BLOCK ? j0 + IACT_LOOP_BLOCK : jend;
    size_t nj = 0;
    for (size_t j = j0; j < j1; j++) {
      const double xj[3] = {x[j], y[j], z[j]}, Hj = kernel_gamma * h[j];
      const double R = (Hj > Hi_max ? Hj : Hi_max) + ci->dx_max;
      if (cell_point_dist2(ci, xj, back) <= iact_loop_prune_r2_pad(R, pad)) list[nj++] = j;
    }
    if (nj == 0) continue;
    if (!direct)
      for (size_t k = 0; k < nj; k++) IACT_LOOP_JACC_LOAD(p, list[k], &cache[k]);
    for (size_t i = ci->offset; i < iend; i++) {
      const double xi[3] = {x[i], y[i], z[i]}, hi = h[i], Hi = kernel_gamma * hi;
      const double Hi2 = Hi * Hi;
      const double R = (Hi > Hj_max ? Hi : Hj_max) + cj->dx_max;
      if (cell_point_dist2(cj, xi, shift) > iact_loop_prune_r2_pad(R, pad)) continue;
      /* the neighbours first (a loop without branches), then the interactions */
      const size_t nh = iact_loop_hits(x, y, z, h, list, 0, nj, xi, shift, Hi2, 1, SIZE_MAX, hit);
      if (nh == 0) continue;
      IACT_LOOP_ACC_BEGIN(p, i);
      for (size_t k = 0; k < nh; k++) {
        const size_t j = list[hit[k]];
        IACT_LOOP_JACC_T *aj = &cache[hit[k]];
        if (direct) IACT_LOOP_JACC_LOAD(p, j, aj);
        const double dx[3] = {(xi[0] - x[j]) - shift[0], (xi[1] - y[j]) - shift[1],
                              (xi[2] - z[j]) - shift[2]};
        const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
        IACT_LOOP_SYM_J(p, i, j, r2, dx, hi, h[j], aj);
        if (direct) IACT_LOOP_JACC_STORE(p, j, aj);
      }
      IACT_LOOP_ACC_END(p, i);
    }
    if (!direct)
      for (size_t k = 0; k < nj; k++) IACT_LOOP_JACC_STORE(p, list[k], &cache[k]);
  }
}

/** Leaf self, symmetric: every pair i < j of c once; the sums of a leaf of
 *  at most IACT_LOOP_BLOCK particles are cached (a larger one updates the
 *  arrays directly). */
__attribute__((unused)) static void IACT_LOOP_FN(_self_leaf)(struct parts *p,
                                                             const struct cell *c) {
  const double *BOLIDE_RESTRICT x = p->x, *BOLIDE_RESTRICT y = p->y, *BOLIDE_RESTRICT z = p->z;
  const double *BOLIDE_RESTRICT h = p->h;
  const size_t beg = c->offset, end = c->offset + c->count;
  const int direct = c->count > IACT_LOOP_BLOCK;
  size_t hit[IACT_LOOP_BLOCK];
  IACT_LOOP_JACC_T cache[IACT_LOOP_BLOCK], one;
  if (!direct)
    for (size_t k = beg; k < end; k++) IACT_LOOP_JACC_LOAD(p, k, &cache[k - beg]);
  for (size_t i = beg; i < end; i++) {
    const double xi[3] = {x[i], y[i], z[i]}, hi = h[i], Hi = kernel_gamma * hi;
    const double Hi2 = Hi * Hi;
    IACT_LOOP_ACC_BEGIN(p, i);
    for (size_t j0 = i + 1; j0 < end; j0 += IACT_LOOP_BLOCK) {
      const size_t j1 = end - j0 > IACT_LOOP_BLOCK ? j0 + IACT_LOOP_BLOCK : end;
      /* the neighbours first (a loop without branches), then the interactions */
      const size_t nh = iact_loop_hits(x, y, z, h, NULL, j0, j1 - j0, xi, iact_loop_no_shift, Hi2,
                                       1, SIZE_MAX, hit);
      for (size_t k = 0; k < nh; k++) {
        const size_t j = j0 + hit[k];
        IACT_LOOP_JACC_T *aj = direct ? &one : &cache[j - beg];
        if (direct) IACT_LOOP_JACC_LOAD(p, j, aj);
        const double dx[3] = {xi[0] - x[j], xi[1] - y[j], xi[2] - z[j]};
        const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
        IACT_LOOP_SYM_J(p, i, j, r2, dx, hi, h[j], aj);
        if (direct) IACT_LOOP_JACC_STORE(p, j, aj);
      }
    }
    IACT_LOOP_JACC_T *ai = direct ? &one : &cache[i - beg];
    if (direct) IACT_LOOP_JACC_LOAD(p, i, ai);
    IACT_LOOP_ACC_END_J(p, i, ai);
    if (direct) IACT_LOOP_JACC_STORE(p, i, ai);
  }
  if (!direct)
    for (size_t k = beg; k < end; k++) IACT_LOOP_JACC_STORE(p, k, &cache[k - beg]);
}
/** Pair of cells, symmetric: recurse into the octrees, prune by bounding box
 *  against max(H_max of ci, H_max of cj) + the drifts, loop at the leaves. */
__attribute__((unused)) static void IACT_LOOP_FN(_pair)(struct parts *p, const struct cell *ci,
                                                        const struct cell *cj,
                                                        const double shift[3]) {
  if (ci->count == 0 || cj->count == 0) return;
  const double h_max = ci->h_max > cj->h_max ? ci->h_max : cj->h_max;
  const double R = kernel_gamma * h_max + ci->dx_max + cj->dx_max;
  if (cell_bbox_dist2(ci, cj, shift) > iact_loop_prune_r2(R, ci, cj, shift)) return;
  if (!iact_loop_leaf(ci) && !iact_loop_leaf(cj)) {
    for (int a = 0; a < 8; a++)
      if (ci->progeny[a])
        for (int b = 0; b < 8; b++)
          if (cj->progeny[b]) IACT_LOOP_FN(_pair)(p, ci->progeny[a], cj->progeny[b], shift);
  } else if (!iact_loop_leaf(ci)) {
    for (int a = 0; a < 8; a++)
      if (ci->progeny[a]) IACT_LOOP_FN(_pair)(p, ci->progeny[a], cj, shift);
  } else if (!iact_loop_leaf(cj)) {
    for (int b = 0; b < 8; b++)
      if (cj->progeny[b]) IACT_LOOP_FN(_pair)(p, ci, cj->progeny[b], shift);
  } else {
    IACT_LOOP_FN(_pair_leaf)(p, ci, cj, shift);
  }
}

/** One cell with itself, symmetric: each pair of its particles once. */
__attribute__((unused)) static void IACT_LOOP_FN(_self)(struct parts *p, const struct cell *c) {
  if (c->count < 2) return;
  if (iact_loop_leaf(c)) {
    IACT_LOOP_FN(_self_leaf)(p, c);
    return;
  }
  for (int a = 0; a < 8; a++) {
    if (!c->progeny[a]) continue;
    IACT_LOOP_FN(_self)(p, c->progeny[a]);
    for (int b = a + 1; b < 8; b++)
      if (c->progeny[b]) IACT_LOOP_FN(_pair)(p, c->progeny[a], c->progeny[b], iact_loop_no_shift);
  }
}

#endif /* IACT_LOOP_SYM */

/* ------------------------------------------------------------ gather form */
#ifdef IACT_LOOP_NONSYM

/** Leaf pair, gather: every active i of ci from every j of cj with r < H_i
 *  (cj in blocks reduced to the particles that can reach ci, as above). */
__attribute__((unused)) static void IACT_LOOP_FN(_pair_gather_leaf)(struct parts *p,
                                                                    const struct cell *ci,
                                                                    const struct cell *cj,
                                                                    const double shift[3]) {
  const double *BOLIDE_RESTRICT x = p->x, *BOLIDE_RESTRICT y = p->y, *BOLIDE_RESTRICT z = p->z;
  const double *BOLIDE_RESTRICT h = p->h;
  const double back[3] = {-shift[0], -shift[1], -shift[2]};
  const double pad = iact_loop_prune_pad(ci, cj, shift);
  const double reach2 = iact_loop_prune_r2_pad(kernel_gamma * ci->h_max + ci->dx_max, pad);
  const size_t iend = ci->offset + ci->count, jend = cj->offset + cj->count;
  size_t list[IACT_LOOP_BLOCK], hit[IACT_LOOP_BLOCK];
  for (size_t j0 = cj->offset; j0 < jend; j0 += IACT_LOOP_BLOCK) {
    const size_t j1 = jend - j0 > IACT_LOOP_BLOCK ? j0 + IACT_LOOP_BLOCK : jend;
    size_t nj = 0;
    for (size_t j = j0; j < j1; j++) {
      const double xj[3] = {x[j], y[j], z[j]};
      if (cell_point_dist2(ci, xj, back) <= reach2) list[nj++] = j;
    }
    if (nj == 0) continue;
    for (size_t i = ci->offset; i < iend; i++) {
      if (!(IACT_LOOP_ACTIVE(p, i))) continue;
      const double xi[3] = {x[i], y[i], z[i]}, hi = h[i], Hi = kernel_gamma * hi;
      const double Hi2 = Hi * Hi;
      if (cell_point_dist2(cj, xi, shift) > iact_loop_prune_r2_pad(Hi + cj->dx_max, pad)) continue;
      const size_t nh = iact_loop_hits(x, y, z, h, list, 0, nj, xi, shift, Hi2, 0, SIZE_MAX, hit);
      IACT_LOOP_ACC_BEGIN(p, i);
      for (size_t k = 0; k < nh; k++) {
        const size_t j = list[hit[k]];
        const double dx[3] = {(xi[0] - x[j]) - shift[0], (xi[1] - y[j]) - shift[1],
                              (xi[2] - z[j]) - shift[2]};
        const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
        IACT_LOOP_NONSYM(p, i, j, r2, dx, hi, h[j]);
      }
      IACT_LOOP_ACC_END(p, i);
    }
  }
}

/** Leaf self, gather: every active i of c from every other j of c. */
__attribute__((unused)) static void IACT_LOOP_FN(_self_gather_leaf)(struct parts *p,
                                                                    const struct cell *c) {
  const double *BOLIDE_RESTRICT x = p->x, *BOLIDE_RESTRICT y = p->y, *BOLIDE_RESTRICT z = p->z;
  const double *BOLIDE_RESTRICT h = p->h;
  const size_t beg = c->offset, end = c->offset + c->count;
  size_t hit[IACT_LOOP_BLOCK];
  for (size_t i = beg; i < end; i++) {
    if (!(IACT_LOOP_ACTIVE(p, i))) continue;
    const double xi[3] = {x[i], y[i], z[i]}, hi = h[i], Hi = kernel_gamma * hi;
    const double Hi2 = Hi * Hi;
    IACT_LOOP_ACC_BEGIN(p, i);
    for (size_t j0 = beg; j0 < end; j0 += IACT_LOOP_BLOCK) {
      const size_t j1 = end - j0 > IACT_LOOP_BLOCK ? j0 + IACT_LOOP_BLOCK : end;
      const size_t nh =
          iact_loop_hits(x, y, z, h, NULL, j0, j1 - j0, xi, iact_loop_no_shift, Hi2, 0, i, hit);
      for (size_t k = 0; k < nh; k++) {
        const size_t j = j0 + hit[k];
        const double dx[3] = {xi[0] - x[j], xi[1] - y[j], xi[2] - z[j]};
        const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
        IACT_LOOP_NONSYM(p, i, j, r2, dx, hi, h[j]);
      }
    }
    IACT_LOOP_ACC_END(p, i);
  }
}

/** Pair of cells, gather: the particles of ci from those of cj; recurse into
 *  the octrees, pruning by bounding box against H_max of ci + the drifts. */
__attribute__((unused)) static void IACT_LOOP_FN(_pair_gather)(struct parts *p,
                                                               const struct cell *ci,
                                                               const struct cell *cj,
                                                               const double shift[3]) {
  if (ci->count == 0 || cj->count == 0) return;
  const double R = kernel_gamma * ci->h_max + ci->dx_max + cj->dx_max;
  if (cell_bbox_dist2(ci, cj, shift) > iact_loop_prune_r2(R, ci, cj, shift)) return;
  if (!iact_loop_leaf(ci) && !iact_loop_leaf(cj)) {
    for (int a = 0; a < 8; a++)
      if (ci->progeny[a])
        for (int b = 0; b < 8; b++)
          if (cj->progeny[b]) IACT_LOOP_FN(_pair_gather)(p, ci->progeny[a], cj->progeny[b], shift);
  } else if (!iact_loop_leaf(ci)) {
    for (int a = 0; a < 8; a++)
      if (ci->progeny[a]) IACT_LOOP_FN(_pair_gather)(p, ci->progeny[a], cj, shift);
  } else if (!iact_loop_leaf(cj)) {
    for (int b = 0; b < 8; b++)
      if (cj->progeny[b]) IACT_LOOP_FN(_pair_gather)(p, ci, cj->progeny[b], shift);
  } else {
    IACT_LOOP_FN(_pair_gather_leaf)(p, ci, cj, shift);
  }
}

/** One cell with itself, gather: every i of c from every other j of c. */
__attribute__((unused)) static void IACT_LOOP_FN(_self_gather)(struct parts *p,
                                                               const struct cell *c) {
  if (c->count < 2) return;
  if (iact_loop_leaf(c)) {
    IACT_LOOP_FN(_self_gather_leaf)(p, c);
    return;
  }
  for (int a = 0; a < 8; a++) {
    if (!c->progeny[a]) continue;
    IACT_LOOP_FN(_self_gather)(p, c->progeny[a]);
    for (int b = 0; b < 8; b++)
      if (b != a && c->progeny[b])
        IACT_LOOP_FN(_pair_gather)(p, c->progeny[a], c->progeny[b], iact_loop_no_shift);
  }
}

#endif /* IACT_LOOP_NONSYM */

#undef IACT_LOOP_FN
#undef IACT_LOOP_PASTE
#undef IACT_LOOP_PASTE2
#undef IACT_LOOP_NAME
#undef IACT_LOOP_SYM
#undef IACT_LOOP_NONSYM
#undef IACT_LOOP_ACTIVE
#undef IACT_LOOP_ACC_BEGIN
#undef IACT_LOOP_ACC_END
#undef IACT_LOOP_JACC_T
#undef IACT_LOOP_JACC_LOAD
#undef IACT_LOOP_JACC_STORE
#undef IACT_LOOP_SYM_J
#undef IACT_LOOP_ACC_END_J
