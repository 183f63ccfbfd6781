/* Friends-of-friends groups: see fof.h. */
#include "tools/fof/fof.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"

/** Bits per axis of a cell key; cell coordinates wrap modulo 2^FOF_BITS, so
 *  far-apart cells may share a key (their particles are still compared by
 *  distance, so the result stays exact). */
#define FOF_BITS 21
#define FOF_MASK ((int64_t)((1 << FOF_BITS) - 1))

/** Union-find root of i with path halving. */
static int64_t fof_find(int64_t *parent, int64_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

/** Merge the sets of i and j (union by size). */
static void fof_union(int64_t *parent, int64_t *size, int64_t i, int64_t j) {
  i = fof_find(parent, i);
  j = fof_find(parent, j);
  if (i == j) return;
  if (size[i] < size[j]) {
    const int64_t t = i;
    i = j;
    j = t;
  }
  parent[j] = i;
  size[i] += size[j];
}

/** Number the sets: group[i] in order of the lowest member; -1 if not kept. */
static int64_t fof_label(size_t n, const unsigned char *keep, int64_t *parent, int64_t *group) {
  int64_t *label = error_malloc((n ? n : 1) * sizeof *label, "fof labels");
  for (size_t i = 0; i < n; i++) label[i] = -1;
  int64_t ng = 0;
  for (size_t i = 0; i < n; i++) {
    if (keep && !keep[i]) {
      group[i] = -1;
      continue;
    }
    const int64_t r = fof_find(parent, (int64_t)i);
    if (label[r] < 0) label[r] = ng++;
    group[i] = label[r];
  }
  free(label);
  return ng;
}

/** Cell coordinate of position t (relative to the lower corner) wrapped to
 *  FOF_BITS bits. */
static int64_t fof_cell(double t, double invL) {
  double q = floor(t * invL);
  q -= ldexp(floor(ldexp(q, -FOF_BITS)), FOF_BITS); /* q mod 2^FOF_BITS, exact */
  return (int64_t)q & FOF_MASK;
}

/** Key of cell (a, b, c), each already in [0, 2^FOF_BITS). */
static inline int64_t fof_key(int64_t a, int64_t b, int64_t c) {
  return a | (b << FOF_BITS) | (c << (2 * FOF_BITS));
}

void fof_radix_sort(size_t n, int64_t *key, int64_t *idx) {
  int64_t *k2 = error_malloc((n ? n : 1) * sizeof *k2, "fof sort");
  int64_t *i2 = error_malloc((n ? n : 1) * sizeof *i2, "fof sort");
  size_t *count = error_malloc(65537 * sizeof *count, "fof sort");
  for (int shift = 0; shift < 64; shift += 16) {
    memset(count, 0, 65537 * sizeof *count);
    for (size_t i = 0; i < n; i++) count[((key[i] >> shift) & 0xffff) + 1]++;
    for (int b = 0; b < 65536; b++) count[b + 1] += count[b];
    for (size_t i = 0; i < n; i++) {
      const size_t dst = count[(key[i] >> shift) & 0xffff]++;
      k2[dst] = key[i];
      i2[dst] = idx[i];
    }
    memcpy(key, k2, n * sizeof *key);
    memcpy(idx, i2, n * sizeof *idx);
  }
  free(k2);
  free(i2);
  free(count);
}

int64_t fof_groups(size_t n, const double *x, const double *y, const double *z,
                   const unsigned char *keep, double L, int64_t *group) {
  if (!(L > 0.0) || !isfinite(L)) error_bug("fof_groups: linking length %g", L);
  int64_t *parent = error_malloc((n ? n : 1) * sizeof *parent, "fof parents");
  for (size_t i = 0; i < n; i++) parent[i] = (int64_t)i;
  /* the kept particles, their cells, sorted by cell */
  double lo[3] = {INFINITY, INFINITY, INFINITY};
  size_t m = 0;
  for (size_t i = 0; i < n; i++) {
    if (keep && !keep[i]) continue;
    m++;
    if (x[i] < lo[0]) lo[0] = x[i];
    if (y[i] < lo[1]) lo[1] = y[i];
    if (z[i] < lo[2]) lo[2] = z[i];
  }
  int64_t *key = error_malloc((m ? m : 1) * sizeof *key, "fof keys");
  int64_t *idx = error_malloc((m ? m : 1) * sizeof *idx, "fof index");
  const double invL = 1.0 / L;
  m = 0;
  for (size_t i = 0; i < n; i++) {
    if (keep && !keep[i]) continue;
    key[m] = fof_key(fof_cell(x[i] - lo[0], invL), fof_cell(y[i] - lo[1], invL),
                     fof_cell(z[i] - lo[2], invL));
    idx[m++] = (int64_t)i;
  }
  fof_radix_sort(m, key, idx);

  /* occupied cells: start of each in the sorted list, their keys */
  size_t nc = 0;
  for (size_t i = 0; i < m; i++) nc += i == 0 || key[i] != key[i - 1];
  size_t *start = error_malloc((nc + 1) * sizeof *start, "fof cells");
  int64_t *ckey = error_malloc((nc ? nc : 1) * sizeof *ckey, "fof cells");
  nc = 0;
  for (size_t i = 0; i < m; i++)
    if (i == 0 || key[i] != key[i - 1]) {
      ckey[nc] = key[i];
      start[nc++] = i;
    }
  start[nc] = m;

  /* each pair of neighbouring cells once: (A, B) with key B >= key A.  The
   * cells are sorted by key, and for a fixed offset the key of the
   * neighbour grows with A (except where coordinates wrap), so one cursor
   * per offset finds the neighbours in a single sweep; a wrapped target
   * falls back to binary search. */
  size_t cursor[27] = {0};
  const double L2 = L * L;
  /* positions and union-find in cell order: the pair loop then reads
   * memory sequentially instead of jumping through idx */
  double *xs = error_malloc((m ? m : 1) * 3 * sizeof *xs, "fof positions");
  int64_t *sp = error_malloc((m ? m : 1) * sizeof *sp, "fof parents");
  int64_t *ssize = error_malloc((m ? m : 1) * sizeof *ssize, "fof sizes");
  for (size_t p = 0; p < m; p++) {
    xs[3 * p] = x[idx[p]], xs[3 * p + 1] = y[idx[p]], xs[3 * p + 2] = z[idx[p]];
    sp[p] = (int64_t)p;
    ssize[p] = 1;
  }
  for (size_t a = 0; a < nc; a++) {
    const int64_t ka = ckey[a];
    const int64_t ca[3] = {ka & FOF_MASK, (ka >> FOF_BITS) & FOF_MASK,
                           (ka >> (2 * FOF_BITS)) & FOF_MASK};
    for (int d = 0; d < 27; d++) {
      const int64_t kb =
          fof_key((ca[0] + d % 3 - 1) & FOF_MASK, (ca[1] + (d / 3) % 3 - 1) & FOF_MASK,
                  (ca[2] + d / 9 - 1) & FOF_MASK);
      if (kb < ka) continue; /* that pair is done from the other side */
      int64_t b = -1;
      if (kb == ka) {
        b = (int64_t)a;
      } else if (cursor[d] > 0 && ckey[cursor[d] - 1] >= kb) {
        size_t s_lo = a, s_hi = nc; /* the target went backwards: search */
        while (s_lo < s_hi) {
          const size_t mid = s_lo + (s_hi - s_lo) / 2;
          if (ckey[mid] < kb)
            s_lo = mid + 1;
          else
            s_hi = mid;
        }
        if (s_lo < nc && ckey[s_lo] == kb) b = (int64_t)s_lo;
      } else {
        size_t c = cursor[d];
        while (c < nc && ckey[c] < kb) c++;
        cursor[d] = c;
        if (c < nc && ckey[c] == kb) b = (int64_t)c;
      }
      if (b < 0) continue;
      for (size_t p = start[a]; p < start[a + 1]; p++) {
        const size_t q0 = b == (int64_t)a ? p + 1 : start[b];
        for (size_t q = q0; q < start[b + 1]; q++) {
          const double dx = xs[3 * p] - xs[3 * q], dy = xs[3 * p + 1] - xs[3 * q + 1],
                       dz = xs[3 * p + 2] - xs[3 * q + 2];
          if (dx * dx + dy * dy + dz * dz < L2) fof_union(sp, ssize, (int64_t)p, (int64_t)q);
        }
      }
    }
  }
  /* back to particle order: every particle points at its set's root */
  for (size_t p = 0; p < m; p++) parent[idx[p]] = idx[fof_find(sp, (int64_t)p)];
  free(xs);
  free(sp);
  free(ssize);
  const int64_t ng = fof_label(n, keep, parent, group);
  free(ckey);
  free(start);
  free(key);
  free(idx);
  free(parent);
  return ng;
}

/** Index of the occupied cell with key kb among the nc sorted keys, -1. */
static int64_t fof_cell_find(const int64_t *ckey, size_t nc, int64_t kb) {
  size_t lo = 0, hi = nc;
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    if (ckey[mid] < kb)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < nc && ckey[lo] == kb ? (int64_t)lo : -1;
}

/** Order of doubles (qsort). */
static int fof_cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int64_t fof_groups_local(size_t n, const double *x, const double *y, const double *z,
                         const unsigned char *keep, const double *ell, int64_t *group) {
  int64_t *parent = error_malloc((n ? n : 1) * sizeof *parent, "fof parents");
  for (size_t i = 0; i < n; i++) parent[i] = (int64_t)i;
  double lo[3] = {INFINITY, INFINITY, INFINITY};
  size_t m = 0;
  for (size_t i = 0; i < n; i++) {
    if (keep && !keep[i]) continue;
    if (!(ell[i] > 0.0) || !isfinite(ell[i]))
      error_bug("fof_groups_local: linking length %g", ell[i]);
    m++;
    if (x[i] < lo[0]) lo[0] = x[i];
    if (y[i] < lo[1]) lo[1] = y[i];
    if (z[i] < lo[2]) lo[2] = z[i];
  }
  /* cells of the median linking length: most particles search their own
   * and the 26 neighbouring cells, one with a k times longer reach the
   * (2k + 1)^3 around it */
  double *tmp = error_malloc((m ? m : 1) * sizeof *tmp, "fof lengths");
  m = 0;
  for (size_t i = 0; i < n; i++)
    if (!keep || keep[i]) tmp[m++] = ell[i];
  qsort(tmp, m, sizeof *tmp, fof_cmp_double);
  const double c = m ? tmp[m / 2] : 1.0, invc = 1.0 / c;
  free(tmp);
  int64_t *key = error_malloc((m ? m : 1) * sizeof *key, "fof keys");
  int64_t *idx = error_malloc((m ? m : 1) * sizeof *idx, "fof index");
  m = 0;
  for (size_t i = 0; i < n; i++) {
    if (keep && !keep[i]) continue;
    key[m] = fof_key(fof_cell(x[i] - lo[0], invc), fof_cell(y[i] - lo[1], invc),
                     fof_cell(z[i] - lo[2], invc));
    idx[m++] = (int64_t)i;
  }
  fof_radix_sort(m, key, idx);
  size_t nc = 0;
  for (size_t i = 0; i < m; i++) nc += i == 0 || key[i] != key[i - 1];
  size_t *start = error_malloc((nc + 1) * sizeof *start, "fof cells");
  int64_t *ckey = error_malloc((nc ? nc : 1) * sizeof *ckey, "fof cells");
  nc = 0;
  for (size_t i = 0; i < m; i++)
    if (i == 0 || key[i] != key[i - 1]) {
      ckey[nc] = key[i];
      start[nc++] = i;
    }
  start[nc] = m;
  double *xs = error_malloc((m ? m : 1) * 4 * sizeof *xs, "fof positions");
  int64_t *sp = error_malloc((m ? m : 1) * sizeof *sp, "fof parents");
  int64_t *ssize = error_malloc((m ? m : 1) * sizeof *ssize, "fof sizes");
  for (size_t q = 0; q < m; q++) {
    xs[4 * q] = x[idx[q]], xs[4 * q + 1] = y[idx[q]], xs[4 * q + 2] = z[idx[q]];
    xs[4 * q + 3] = ell[idx[q]];
    sp[q] = (int64_t)q;
    ssize[q] = 1;
  }
  /* a pair is linked when closer than the longer of its two lengths: each
   * particle finds every particle within its own length (cell a's stencil
   * covers the longest length in a), the pair then being found from the
   * side of the particle with the longer one */
  for (size_t a = 0; a < nc; a++) {
    double lmax = 0.0;
    for (size_t p = start[a]; p < start[a + 1]; p++) lmax = fmax(lmax, xs[4 * p + 3]);
    const int64_t k = (int64_t)ceil(lmax * invc);
    const int64_t ka = ckey[a];
    const int64_t ca[3] = {ka & FOF_MASK, (ka >> FOF_BITS) & FOF_MASK,
                           (ka >> (2 * FOF_BITS)) & FOF_MASK};
    for (int64_t dz = -k; dz <= k; dz++)
      for (int64_t dy = -k; dy <= k; dy++)
        for (int64_t dx = -k; dx <= k; dx++) {
          const int64_t kb =
              fof_key((ca[0] + dx) & FOF_MASK, (ca[1] + dy) & FOF_MASK, (ca[2] + dz) & FOF_MASK);
          const int64_t b = kb == ka ? (int64_t)a : fof_cell_find(ckey, nc, kb);
          if (b < 0) continue;
          for (size_t p = start[a]; p < start[a + 1]; p++) {
            const double lp = xs[4 * p + 3];
            const size_t q0 = b == (int64_t)a ? p + 1 : start[b];
            for (size_t q = q0; q < start[b + 1]; q++) {
              const double ex = xs[4 * p] - xs[4 * q], ey = xs[4 * p + 1] - xs[4 * q + 1],
                           ez = xs[4 * p + 2] - xs[4 * q + 2];
              const double l = fmax(lp, xs[4 * q + 3]);
              if (ex * ex + ey * ey + ez * ez < l * l) fof_union(sp, ssize, (int64_t)p, (int64_t)q);
            }
          }
        }
  }
  for (size_t q = 0; q < m; q++) parent[idx[q]] = idx[fof_find(sp, (int64_t)q)];
  free(xs);
  free(sp);
  free(ssize);
  const int64_t ng = fof_label(n, keep, parent, group);
  free(ckey);
  free(start);
  free(key);
  free(idx);
  free(parent);
  return ng;
}

int64_t fof_groups_local_brute(size_t n, const double *x, const double *y, const double *z,
                               const unsigned char *keep, const double *ell, int64_t *group) {
  int64_t *parent = error_malloc((n ? n : 1) * sizeof *parent, "fof parents");
  int64_t *size = error_malloc((n ? n : 1) * sizeof *size, "fof sizes");
  for (size_t i = 0; i < n; i++) {
    parent[i] = (int64_t)i;
    size[i] = 1;
  }
  for (size_t i = 0; i < n; i++)
    for (size_t j = i + 1; j < n; j++) {
      if (keep && (!keep[i] || !keep[j])) continue;
      const double dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
      const double l = fmax(ell[i], ell[j]);
      if (dx * dx + dy * dy + dz * dz < l * l) fof_union(parent, size, (int64_t)i, (int64_t)j);
    }
  const int64_t ng = fof_label(n, keep, parent, group);
  free(size);
  free(parent);
  return ng;
}

int64_t fof_groups_brute(size_t n, const double *x, const double *y, const double *z,
                         const unsigned char *keep, double L, int64_t *group) {
  int64_t *parent = error_malloc((n ? n : 1) * sizeof *parent, "fof parents");
  int64_t *size = error_malloc((n ? n : 1) * sizeof *size, "fof sizes");
  for (size_t i = 0; i < n; i++) {
    parent[i] = (int64_t)i;
    size[i] = 1;
  }
  for (size_t i = 0; i < n; i++)
    for (size_t j = i + 1; j < n; j++) {
      if (keep && (!keep[i] || !keep[j])) continue;
      const double dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
      if (dx * dx + dy * dy + dz * dz < L * L) fof_union(parent, size, (int64_t)i, (int64_t)j);
    }
  const int64_t ng = fof_label(n, keep, parent, group);
  free(size);
  free(parent);
  return ng;
}
