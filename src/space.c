/* The space: top-level grid, octrees and the particle sort (see space.h). */
#ifdef HAVE_CONFIG_H
#include "config.h"
#endif

#include "src/space.h"

#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "tasks/hydro/kernel.h"
#include "src/part.h"

/** Particles removed from an open box that are logged one by one at level 0
 *  (the rest at level 1; the count is always logged). */
#define SPACE_LOG_REMOVED 100

void space_init(struct space *s, struct parts *parts, const double box[3], int periodic,
                int split_size, int max_top_level_cells) {
  memset(s, 0, sizeof *s);
  for (int k = 0; k < 3; k++) {
    if (!(box[k] > 0.0) || !isfinite(box[k]))
      error_exit("space: box size %g in direction %d must be positive and finite", box[k], k);
    s->dim[k] = box[k];
  }
  if (split_size < 1) error_exit("space: split size %d must be at least 1", split_size);
  if (max_top_level_cells < 1 || max_top_level_cells > 1024)
    error_exit("space: maximum number of top-level cells per direction %d must be in [1, 1024]",
               max_top_level_cells);
  s->periodic = periodic ? 1 : 0;
  s->parts = parts;
  s->split_size = split_size;
  s->max_top_level_cells = max_top_level_cells;
  s->max_depth = SPACE_MAX_DEPTH;
  s->cell_stretch = 1.1;
  s->max_drift_fraction = 0.25;
  s->nr_threads = 1;
}

void space_free(struct space *s) {
  free(s->cells);
  free(s->progeny_index);
  free(s->sort_index);
  s->cells = NULL;
  s->progeny_index = NULL;
  s->sort_index = NULL;
  s->nr_cells = s->nr_top = s->cells_capacity = 0;
  s->sort_capacity = 0;
}

/** Index of a new, zeroed cell at the end of s->cells (may move the array:
 *  callers hold indices, never pointers, while the tree is being built). */
static int space_new_cell(struct space *s) {
  if (s->nr_cells == s->cells_capacity) {
    if (s->cells_capacity > INT_MAX / 2) error_exit("space: too many cells");
    const int cap = s->cells_capacity < 64 ? 64 : 2 * s->cells_capacity;
    s->cells = error_realloc(s->cells, (size_t)cap * sizeof *s->cells, "cells");
    s->progeny_index =
        error_realloc(s->progeny_index, (size_t)cap * 8 * sizeof(int), "cell progeny");
    s->cells_capacity = cap;
  }
  const int c = s->nr_cells++;
  memset(&s->cells[c], 0, sizeof s->cells[c]);
  for (int k = 0; k < 8; k++) s->progeny_index[8 * c + k] = -1;
  s->cells[c].index = c;
  return c;
}

/** Add what particle i takes with it out of the box to the budget r: its
 *  kinetic and internal energy, its potential energy m phi (both halves of
 *  its pair terms leave with it), momentum, angular momentum, and what the
 *  kick's floor and the plastic returns had counted on it. */
static void space_count_removed(struct budget_removed *r, const struct parts *p, size_t i) {
  const double m = p->m[i];
  const double x = p->x[i], y = p->y[i], z = p->z[i];
  const double vx = p->vx[i], vy = p->vy[i], vz = p->vz[i];
  r->m += m;
  r->E += m * (0.5 * (vx * vx + vy * vy + vz * vz) + p->u[i] + p->pot[i]);
  r->p[0] += m * vx;
  r->p[1] += m * vy;
  r->p[2] += m * vz;
  r->L[0] += m * (y * vz - z * vy);
  r->L[1] += m * (z * vx - x * vz);
  r->L[2] += m * (x * vy - y * vx);
  r->E_clamp += m * p->e_clamp[i];
  r->W_plastic += m * p->w_plastic[i];
}

/** Wrap positions into the periodic box, or remove the particles outside the
 *  open box (logged by id); check positions and smoothing lengths. Returns
 *  the number removed. */
static size_t space_wrap_or_remove(struct space *s) {
  struct parts *p = s->parts;
  double *xs[3] = {p->x, p->y, p->z};
  size_t removed = 0;
  size_t i = 0;
  while (i < p->count) {
    if (!isfinite(p->x[i]) || !isfinite(p->y[i]) || !isfinite(p->z[i]))
      error_exit("space: particle id %lld has a non-finite position (%g, %g, %g)",
                 (long long)p->id[i], p->x[i], p->y[i], p->z[i]);
    if (!(p->h[i] > 0.0) || !isfinite(p->h[i]))
      error_exit("space: particle id %lld has smoothing length %g (must be positive and finite)",
                 (long long)p->id[i], p->h[i]);
    int outside = 0;
    for (int k = 0; k < 3; k++) {
      double x = xs[k][i];
      const double L = s->dim[k];
      if (s->periodic) {
        if (x < 0.0 || x >= L) {
          x -= L * floor(x / L);
          if (x >= L || x < 0.0) x = 0.0; /* rounding of x just below 0 or at L */
          xs[k][i] = x;
        }
      } else if (x < 0.0 || x >= L) {
        outside = 1;
      }
    }
    if (!outside) {
      i++;
      continue;
    }
    removed++;
    space_count_removed(&s->removed, p, i);
    error_log(removed <= SPACE_LOG_REMOVED ? 0 : 1,
              "space: removed particle id %lld at (%g, %g, %g), outside the open box",
              (long long)p->id[i], p->x[i], p->y[i], p->z[i]);
    /* the last particle takes its place (order is restored by the sort) */
    if (i != p->count - 1) parts_copy_one(p, i, p->count - 1);
    p->count--;
  }
  if (removed) {
    s->nr_removed += removed;
    error_log(0, "space: %zu particle(s) left the open box and were removed (%zu in total)",
              removed, s->nr_removed);
  }
  return removed;
}

/** Choose the top-level grid from the largest kernel support. */
static void space_choose_grid(struct space *s) {
  const struct parts *p = s->parts;
  double h_max = 0.0;
  size_t i_max = 0;
  for (size_t i = 0; i < p->count; i++)
    if (p->h[i] > h_max) {
      h_max = p->h[i];
      i_max = i;
    }
  if (s->restore_h_max > 0.0) h_max = s->restore_h_max;
  s->h_max = h_max;
  const double H = kernel_gamma * h_max;
  for (int k = 0; k < 3; k++) {
    /* minimum image must be unique: no particle may see two images of another */
    if (s->periodic && 2.0 * H > s->dim[k])
      error_exit("space: kernel support %g of particle id %lld exceeds half the periodic box (%g)",
                 H, (long long)p->id[i_max], s->dim[k]);
    /* no particles: one cell */
    const double n = H > 0.0 ? floor(s->dim[k] / (s->cell_stretch * H)) : 1.0;
    int c = n >= s->max_top_level_cells ? s->max_top_level_cells : (int)n;
    if (c < 1) c = 1;
    s->cdim[k] = c;
    s->width[k] = s->dim[k] / c;
    s->iwidth[k] = 1.0 / s->width[k];
  }
}

/** Top-level cell coordinate of position x in direction k, consistent with
 *  the cell boxes loc = i * width (corrected for rounding of x / width). */
static int space_top_coord(const struct space *s, int k, double x) {
  int i = (int)(x * s->iwidth[k]);
  if (i >= s->cdim[k]) i = s->cdim[k] - 1;
  if (i < 0) i = 0;
  if (i > 0 && x < i * s->width[k]) i--;
  if (i < s->cdim[k] - 1 && x >= (i + 1) * s->width[k]) i++;
  return i;
}

/** Split cell c (range idx[0 .. count) of the permutation) into octants,
 *  recursively, while it holds more than split_size particles. buf: work
 *  array of the same length. */
static void space_split(struct space *s, int c, size_t *idx, size_t *buf) {
  const struct parts *p = s->parts;
  const double *xs[3] = {p->x, p->y, p->z};
  const size_t count = s->cells[c].count;
  if (count <= (size_t)s->split_size || s->cells[c].depth >= s->max_depth) return;
  double mid[3], half[3], loc[3];
  for (int k = 0; k < 3; k++) {
    loc[k] = s->cells[c].loc[k];
    half[k] = 0.5 * s->cells[c].width[k];
    mid[k] = loc[k] + half[k];
  }
  /* counting sort of the range by octant (bits x 4, y 2, z 1) */
  size_t n[8] = {0}, start[8];
  unsigned char small[256];
  unsigned char *o = count <= sizeof small ? small : error_malloc(count, "octants");
  for (size_t a = 0; a < count; a++) {
    const size_t i = idx[a];
    o[a] = (unsigned char)((xs[0][i] >= mid[0]) << 2 | (xs[1][i] >= mid[1]) << 1 |
                           (xs[2][i] >= mid[2]));
    n[o[a]]++;
  }
  start[0] = 0;
  for (int q = 1; q < 8; q++) start[q] = start[q - 1] + n[q - 1];
  size_t pos[8];
  memcpy(pos, start, sizeof pos);
  for (size_t a = 0; a < count; a++) buf[pos[o[a]]++] = idx[a];
  memcpy(idx, buf, count * sizeof *idx);
  if (o != small) free(o);

  s->cells[c].split = 1;
  for (int q = 0; q < 8; q++) {
    if (n[q] == 0) continue;
    const int d = space_new_cell(s); /* may move s->cells */
    struct cell *child = &s->cells[d];
    const struct cell *parent = &s->cells[c];
    for (int k = 0; k < 3; k++) {
      const int bit = (q >> (2 - k)) & 1;
      child->loc[k] = bit ? mid[k] : loc[k];
      child->width[k] = half[k];
    }
    child->offset = parent->offset + start[q];
    child->count = n[q];
    child->depth = parent->depth + 1;
    child->top = parent->top;
    s->progeny_index[8 * c + q] = d;
    space_split(s, d, idx + start[q], buf + start[q]);
  }
}

/** Reorder every particle field, new[i] = old[perm[i]], through the work
 *  array buf of n 8-byte words: parts_permute with one typed gather loop per
 *  field (no per-element memcpy of a run-time size), about twice as fast. */
_Static_assert(sizeof(size_t) >= 8, "space_permute reuses a size_t array for 8-byte fields");
/** Gather field k's elements [lo, hi) through perm into buf. */
static void space_gather(struct parts *p, int k, const size_t *perm, void *buf, size_t lo,
                         size_t hi) {
  const struct part_field *f = &part_fields[k];
  const void *a = part_field_array(p, f);
  if (f->size == 8) {
    uint64_t *dst = buf;
    const uint64_t *src = a;
    for (size_t i = lo; i < hi; i++) dst[i] = src[perm[i]];
  } else if (f->size == 4) {
    uint32_t *dst = buf;
    const uint32_t *src = a;
    for (size_t i = lo; i < hi; i++) dst[i] = src[perm[i]];
  } else {
    error_bug("particle field %s has an element size of %zu bytes", f->name, f->size);
  }
}

/** 1 if the elements [lo, hi) of field k are all bits zero. */
static int space_field_zero(struct parts *p, int k, size_t lo, size_t hi) {
  const struct part_field *f = &part_fields[k];
  const void *a = part_field_array(p, f);
  if (f->size == 8) {
    const uint64_t *v = a;
    uint64_t any = 0;
    for (size_t i = lo; i < hi; i++) any |= v[i];
    return any == 0;
  }
  const uint32_t *v = a;
  uint32_t any = 0;
  for (size_t i = lo; i < hi; i++) any |= v[i];
  return any == 0;
}

/** One thread's share of space_permute: elements [lo, hi) of every field.
 *  A field whose elements are all zero (many at the first rebuild after
 *  reading a file: stresses, damage, derivatives not yet computed) stays
 *  as it is: its permutation is itself, and the random gathers it would
 *  cost are most of a first rebuild. */
struct space_permute_job {
  struct parts *p;
  const size_t *perm;
  void *buf;
  size_t lo, hi;
  pthread_barrier_t *bar;
  unsigned char *nonzero; /**< [field][thread]: whether the thread's range of it is not all zero */
  int thread, nr_threads;
};

static void *space_permute_run(void *arg) {
  struct space_permute_job *j = arg;
  for (int k = 0; k < part_nr_fields; k++)
    j->nonzero[k * j->nr_threads + j->thread] = !space_field_zero(j->p, k, j->lo, j->hi);
  pthread_barrier_wait(j->bar); /* every range scanned */
  for (int k = 0; k < part_nr_fields; k++) {
    int any = 0;
    for (int t = 0; t < j->nr_threads; t++) any |= j->nonzero[k * j->nr_threads + t];
    if (!any) continue; /* the same decision in every thread */
    const size_t sz = part_fields[k].size;
    space_gather(j->p, k, j->perm, j->buf, j->lo, j->hi);
    pthread_barrier_wait(j->bar); /* every gather of field k read the old order */
    memcpy((char *)part_field_array(j->p, &part_fields[k]) + j->lo * sz,
           (char *)j->buf + j->lo * sz, (j->hi - j->lo) * sz);
    pthread_barrier_wait(j->bar); /* buf is free for the next field */
  }
  return NULL;
}

/** Reorder every particle field: new element i = old element perm[i];
 *  buf: n words.  On up to nr_threads threads, each a range of elements
 *  (the result does not depend on the count); the random gathers of the
 *  first rebuild after reading a file dominate a rebuild (about 2 s for
 *  1e6 particles on one core before all-zero fields were skipped). */
static void space_permute(struct parts *p, const size_t *perm, void *buf, int nr_threads) {
  const size_t n = p->count;
  int t = nr_threads;
  if ((size_t)t > n / 65536 + 1) t = (int)(n / 65536 + 1);
  if (t > 256) t = 256;
  if (t < 1) t = 1;
  struct space_permute_job job[256];
  pthread_t th[256];
  pthread_barrier_t bar;
  unsigned char *nonzero = error_malloc((size_t)part_nr_fields * (size_t)t, "rebuild field flags");
  if (pthread_barrier_init(&bar, NULL, (unsigned)t) != 0)
    error_exit("space: cannot set up the threads of the rebuild (pthread_barrier_init)");
  for (int k = 0; k < t; k++)
    job[k] = (struct space_permute_job){
        p,       perm, buf, n * (size_t)k / (size_t)t, n * (size_t)(k + 1) / (size_t)t, &bar,
        nonzero, k,    t};
  for (int k = 1; k < t; k++)
    if (pthread_create(&th[k], NULL, space_permute_run, &job[k]))
      /* a thread could not start: the barrier would wait for ever */
      error_exit("space: cannot start the threads of the rebuild (pthread_create)");
  space_permute_run(&job[0]);
  for (int k = 1; k < t; k++) pthread_join(th[k], NULL);
  pthread_barrier_destroy(&bar);
  free(nonzero);
}

/** Progeny and parent pointers from progeny_index; h_max, bounding boxes
 *  (of x0 = x) and dx_max = 0, bottom-up from cell c. */
static void space_finish_cell(struct space *s, int c) {
  struct cell *cell = &s->cells[c];
  const struct parts *p = s->parts;
  cell->dx_max = 0.0;
  if (cell->split) {
    cell->h_max = 0.0;
    for (int k = 0; k < 3; k++) {
      cell->bmin[k] = INFINITY;
      cell->bmax[k] = -INFINITY;
    }
    for (int q = 0; q < 8; q++) {
      const int d = s->progeny_index[8 * c + q];
      cell->progeny[q] = d < 0 ? NULL : &s->cells[d];
      if (d < 0) continue;
      struct cell *child = &s->cells[d];
      child->parent = cell;
      space_finish_cell(s, d);
      if (child->h_max > cell->h_max) cell->h_max = child->h_max;
      for (int k = 0; k < 3; k++) {
        cell->bmin[k] = fmin(cell->bmin[k], child->bmin[k]);
        cell->bmax[k] = fmax(cell->bmax[k], child->bmax[k]);
      }
    }
    return;
  }
  for (int q = 0; q < 8; q++) cell->progeny[q] = NULL;
  if (cell->count == 0) {
    /* an empty (top-level) cell: a degenerate box at its corner */
    cell->h_max = 0.0;
    for (int k = 0; k < 3; k++) cell->bmin[k] = cell->bmax[k] = cell->loc[k];
    return;
  }
  double h_max = 0.0, lo[3] = {INFINITY, INFINITY, INFINITY},
         hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  const size_t end = cell->offset + cell->count;
  for (size_t i = cell->offset; i < end; i++) {
    if (p->h[i] > h_max) h_max = p->h[i];
    lo[0] = fmin(lo[0], p->x[i]);
    hi[0] = fmax(hi[0], p->x[i]);
    lo[1] = fmin(lo[1], p->y[i]);
    hi[1] = fmax(hi[1], p->y[i]);
    lo[2] = fmin(lo[2], p->z[i]);
    hi[2] = fmax(hi[2], p->z[i]);
  }
  cell->h_max = h_max;
  for (int k = 0; k < 3; k++) {
    cell->bmin[k] = lo[k];
    cell->bmax[k] = hi[k];
  }
}

size_t space_rebuild(struct space *s) {
  struct parts *p = s->parts;
  const double w0 = error_walltime();
  const size_t removed = space_wrap_or_remove(s);
  space_choose_grid(s);
  s->nr_rebuilds++;

  /* the top-level cells */
  const long ntop = (long)s->cdim[0] * s->cdim[1] * s->cdim[2];
  if (ntop > INT_MAX / 16) error_exit("space: %ld top-level cells are too many", ntop);
  s->nr_cells = 0;
  s->nr_top = (int)ntop;
  for (int i = 0; i < s->cdim[0]; i++)
    for (int j = 0; j < s->cdim[1]; j++)
      for (int k = 0; k < s->cdim[2]; k++) {
        const int c = space_new_cell(s);
        struct cell *cell = &s->cells[c];
        const int ijk[3] = {i, j, k};
        for (int d = 0; d < 3; d++) {
          cell->loc[d] = ijk[d] * s->width[d];
          cell->width[d] = s->width[d];
        }
        cell->top = c;
      }

  /* counting sort by top-level cell */
  const size_t n = p->count;
  if (s->sort_capacity < 2 * n) {
    free(s->sort_index);
    s->sort_capacity = 2 * n;
    s->sort_index = error_malloc(s->sort_capacity * sizeof(size_t) + 1, "particle sort index");
  }
  size_t *idx = s->sort_index, *buf = s->sort_index + n;
  int *topc = error_malloc(n * sizeof(int) + 1, "particle cell index");
  for (size_t i = 0; i < n; i++) {
    topc[i] = space_top_index(s, space_top_coord(s, 0, p->x[i]), space_top_coord(s, 1, p->y[i]),
                              space_top_coord(s, 2, p->z[i]));
    s->cells[topc[i]].count++;
  }
  size_t off = 0;
  for (int c = 0; c < s->nr_top; c++) {
    s->cells[c].offset = off;
    off += s->cells[c].count;
  }
  {
    size_t *pos = error_malloc((size_t)s->nr_top * sizeof(size_t), "cell positions");
    for (int c = 0; c < s->nr_top; c++) pos[c] = s->cells[c].offset;
    for (size_t i = 0; i < n; i++) idx[pos[topc[i]]++] = i;
    free(pos);
  }
  free(topc);

  /* the octrees, then one reordering of every particle field */
  const double w1 = error_walltime();
  for (int c = 0; c < s->nr_top; c++) {
    const size_t o = s->cells[c].offset;
    space_split(s, c, idx + o, buf + o);
  }
  const double w2 = error_walltime();
  if (n) space_permute(p, idx, buf, s->nr_threads); /* buf (n words) is free after the split */
  memcpy(p->x0, p->x, n * sizeof(double));
  memcpy(p->y0, p->y, n * sizeof(double));
  memcpy(p->z0, p->z, n * sizeof(double));
  const double w3 = error_walltime();
  for (int c = 0; c < s->nr_top; c++) space_finish_cell(s, c);
  const double w4 = error_walltime();
  error_log(1,
            "space: rebuild %d: %zu particles, %d x %d x %d top-level cells, %d cells; "
            "s: wrap and sort by top-level cell %.3f, octrees %.3f, reorder %.3f, boxes %.3f",
            s->nr_rebuilds, n, s->cdim[0], s->cdim[1], s->cdim[2], s->nr_cells, w1 - w0, w2 - w1,
            w3 - w2, w4 - w3);
  return removed;
}

void space_restore(struct space *s, double h_max, const double *cell_h, const double *cell_dx,
                   int nr_cells, const char *file) {
  struct parts *p = s->parts;
  const size_t n = p->count;
  /* the cells of the positions at the last rebuild (x0), then the positions back */
  double *keep = error_malloc(3 * n * sizeof(double) + 1, "restore positions");
  int64_t *ids = error_malloc(n * sizeof(int64_t) + 1, "restore ids");
  memcpy(keep, p->x, n * sizeof(double));
  memcpy(keep + n, p->y, n * sizeof(double));
  memcpy(keep + 2 * n, p->z, n * sizeof(double));
  memcpy(ids, p->id, n * sizeof(int64_t));
  memcpy(p->x, p->x0, n * sizeof(double));
  memcpy(p->y, p->y0, n * sizeof(double));
  memcpy(p->z, p->z0, n * sizeof(double));
  s->restore_h_max = h_max;
  const size_t removed = space_rebuild(s);
  s->restore_h_max = 0.0;
  if (removed)
    error_exit("%s: %zu particles were outside the box at the last rebuild", file, removed);
  if (memcmp(ids, p->id, n * sizeof(int64_t)))
    error_exit("%s: the particles are not in the order of the cells of their rebuild positions",
               file);
  memcpy(p->x, keep, n * sizeof(double));
  memcpy(p->y, keep + n, n * sizeof(double));
  memcpy(p->z, keep + 2 * n, n * sizeof(double));
  free(keep);
  free(ids);
  if (!cell_h || !cell_dx) {
    for (int c = 0; c < s->nr_top; c++) cell_update_bounds(p, &s->cells[c]);
    return;
  }
  if (nr_cells != s->nr_cells)
    error_exit("%s: the restored space has %d cells, the file %d (another build or parameters?)",
               file, s->nr_cells, nr_cells);
  for (int c = 0; c < nr_cells; c++) {
    s->cells[c].h_max = cell_h[c];
    s->cells[c].dx_max = cell_dx[c];
  }
}

int space_should_rebuild(const struct space *s) {
  const struct parts *p = s->parts;
  double d2_max = 0.0, h_max = 0.0;
  for (size_t i = 0; i < p->count; i++) {
    const double dx = p->x[i] - p->x0[i], dy = p->y[i] - p->y0[i], dz = p->z[i] - p->z0[i];
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 > d2_max) d2_max = d2;
    if (p->h[i] > h_max) h_max = p->h[i];
  }
  const double dmax = sqrt(d2_max), H = kernel_gamma * h_max;
  for (int k = 0; k < 3; k++) {
    if (dmax > s->max_drift_fraction * s->width[k]) return 1;
    if (s->periodic && 2.0 * (H + dmax) > s->dim[k]) return 1;
    /* a direction with one open cell has no neighbour to miss */
    if ((s->periodic || s->cdim[k] > 1) && H + 2.0 * dmax > s->width[k]) return 1;
  }
  return 0;
}

size_t space_top_pairs(const struct space *s, struct space_pair **pairs) {
  size_t n = 0, cap = 13 * (size_t)s->nr_top + 1;
  struct space_pair *list = error_malloc(cap * sizeof *list, "cell pairs");
  for (int i = 0; i < s->cdim[0]; i++)
    for (int j = 0; j < s->cdim[1]; j++)
      for (int k = 0; k < s->cdim[2]; k++) {
        const int ci = space_top_index(s, i, j, k);
        if (s->cells[ci].count == 0) continue;
        /* the 13 offsets of the upper half: each neighbour relation once */
        for (int oi = -1; oi <= 1; oi++)
          for (int oj = -1; oj <= 1; oj++)
            for (int ok = -1; ok <= 1; ok++) {
              if (!(oi > 0 || (oi == 0 && (oj > 0 || (oj == 0 && ok > 0))))) continue;
              const int o[3] = {oi, oj, ok}, a[3] = {i, j, k};
              int b[3], skip = 0;
              double shift[3];
              for (int d = 0; d < 3; d++) {
                b[d] = a[d] + o[d];
                shift[d] = 0.0;
                if (b[d] < 0 || b[d] >= s->cdim[d]) {
                  if (!s->periodic) {
                    skip = 1;
                    break;
                  }
                  /* the image of cell b across the boundary */
                  shift[d] = b[d] < 0 ? -s->dim[d] : s->dim[d];
                  b[d] = b[d] < 0 ? b[d] + s->cdim[d] : b[d] - s->cdim[d];
                }
              }
              if (skip) continue;
              const int cj = space_top_index(s, b[0], b[1], b[2]);
              if (s->cells[cj].count == 0) continue;
              list[n].ci = ci;
              list[n].cj = cj;
              for (int d = 0; d < 3; d++) list[n].shift[d] = shift[d];
              n++;
            }
      }
  *pairs = list;
  return n;
}
