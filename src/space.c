/* The space: top-level grid, octrees and the particle sort (see space.h). */
#ifdef HAVE_CONFIG_H
#include "config.h"
#endif

#include "src/space.h"

#include <float.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
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
  free(s->sort_oct);
  free(s->gone);
  s->gone = NULL;
  s->nr_gone = s->gone_cap = 0;
  s->cells = NULL;
  s->progeny_index = NULL;
  s->sort_index = NULL;
  s->sort_oct = NULL;
  s->oct_capacity = 0;
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
 *  kick's floor and the plastic returns had counted on it.
 *
 *  A rebuild of the kick-drift-kick step (c->set) comes after the drift:
 *  the particle's velocity is that of its step's middle, its potential
 *  that of its last evaluation, c->since_eval ago (the global step's dt;
 *  with time bins the time since its step began).  The energy it takes is
 *  that of now, as the statistics count it (engine_sync_view): the
 *  predicted velocity and energy of the drift (vp = v + a (t - t_mid),
 *  up), and the potential moved with it, phi - g . v since_eval (first
 *  order; the others' motion adds m sum_j g_j . v_j, nothing in the centre
 *  of mass's frame).  Its momentum and angular momentum stay those of the
 *  middle: the half kick it missed is the one its pairs would have given
 *  the others, so that the momentum of the particles left and the one it
 *  took add up as before (theory/sph.md, "Conservation budget"). */
static void space_count_removed(struct budget_removed *r, const struct parts *p, size_t i,
                                const struct space_clock *c) {
  const double m = p->m[i];
  const double x = p->x[i], y = p->y[i], z = p->z[i];
  const double vx = p->vx[i], vy = p->vy[i], vz = p->vz[i];
  double e = 0.5 * (vx * vx + vy * vy + vz * vz) + p->u[i] + p->pot[i];
  if (c->set) {
    double since = c->since_eval;
    if (c->tl) {
      const integertime_t step = timeline_step_of_bin(p->time_bin[i]);
      const integertime_t ti0 = c->ti > 0 ? (c->ti - 1) / step * step : 0;
      since = timeline_time(c->tl, c->ti) - timeline_time(c->tl, ti0);
    }
    const double wx = p->vpx[i], wy = p->vpy[i], wz = p->vpz[i];
    e = 0.5 * (wx * wx + wy * wy + wz * wz) + p->up[i] + p->pot[i] -
        since * (p->gax[i] * vx + p->gay[i] * vy + p->gaz[i] * vz);
  }
  r->m += m;
  r->E += m * e;
  r->p[0] += m * vx;
  r->p[1] += m * vy;
  r->p[2] += m * vz;
  r->L[0] += m * (y * vz - z * vy);
  r->L[1] += m * (z * vx - x * vz);
  r->L[2] += m * (x * vy - y * vx);
  r->E_clamp += m * p->e_clamp[i];
  if (p->w_plastic) r->W_plastic += m * p->w_plastic[i];
}

/** Run fn on nt threads (at most SPACE_MAX_THREADS), the calling thread
 *  as the first: thread k gets (char *)args + k * stride (stride 0: all the
 *  same argument); returns when all are done. */
#define SPACE_MAX_THREADS 256

static void space_team(int nt, void *(*fn)(void *), void *args, size_t stride) {
  if (nt > SPACE_MAX_THREADS) nt = SPACE_MAX_THREADS;
  pthread_t th[SPACE_MAX_THREADS];
  for (int k = 1; k < nt; k++)
    if (pthread_create(&th[k], NULL, fn, (char *)args + (size_t)k * stride))
      /* (a barrier in fn would wait for ever: stop) */
      error_exit("space: cannot start the threads of the rebuild (pthread_create)");
  fn(args);
  for (int k = 1; k < nt; k++) pthread_join(th[k], NULL);
}

/** Threads of a rebuild pass over whole cells: s->nr_threads, one below
 *  50,000 particles. */
static int space_cell_threads(const struct space *s) {
  const int nt = s->nr_threads < 1 ? 1 : s->nr_threads;
  return s->parts->count < 50000 ? 1 : nt;
}

/** fn(arg, lo, hi) over ranges of [0, n) on up to s->nr_threads threads
 *  (ranges of at least 65,536 elements; thread k takes range k). */
struct space_range_job {
  void (*fn)(void *arg, int k, size_t lo, size_t hi);
  void *arg;
  int k;
  size_t lo, hi;
};

static void *space_range_run(void *a) {
  struct space_range_job *j = a;
  j->fn(j->arg, j->k, j->lo, j->hi);
  return NULL;
}

#define SPACE_MAX_RANGES 64

/** The number of ranges space_ranges uses for n elements. */
static int space_nr_ranges(const struct space *s, size_t n) {
  int t = s->nr_threads < 1 ? 1 : s->nr_threads;
  if ((size_t)t > n / 65536 + 1) t = (int)(n / 65536 + 1);
  return t > SPACE_MAX_RANGES ? SPACE_MAX_RANGES : t;
}

static void space_ranges(const struct space *s, size_t n,
                         void (*fn)(void *arg, int k, size_t lo, size_t hi), void *arg) {
  const int t = space_nr_ranges(s, n);
  struct space_range_job job[SPACE_MAX_RANGES];
  for (int k = 0; k < t; k++)
    job[k] = (struct space_range_job){fn, arg, k, n * (size_t)k / (size_t)t,
                                      n * (size_t)(k + 1) / (size_t)t};
  space_team(t, space_range_run, job, sizeof *job);
}

/** space_scan's results per range: whether a particle needs
 *  space_wrap_or_remove's attention (outside the box, or a position or h to
 *  report), and the largest h. */
struct space_scan {
  const struct space *s;
  unsigned char any[SPACE_MAX_RANGES];
  double h_max[SPACE_MAX_RANGES]; /**< largest h of the range */
  size_t i_max[SPACE_MAX_RANGES]; /**< its first particle */
};

static void space_scan_range(void *arg, int k, size_t lo, size_t hi) {
  struct space_scan *sc = arg;
  const struct space *s = sc->s;
  const struct parts *p = s->parts;
  int any = 0;
  double h_max = 0.0;
  size_t i_max = lo;
  for (size_t i = lo; i < hi; i++) {
    const double x = p->x[i], y = p->y[i], z = p->z[i], h = p->h[i];
    /* (NaN fails every comparison: caught as outside) */
    any |= !(x >= 0.0 && x < s->dim[0] && y >= 0.0 && y < s->dim[1] && z >= 0.0 && z < s->dim[2] &&
             h > 0.0 && h <= DBL_MAX);
    if (h > h_max) {
      h_max = h;
      i_max = i;
    }
  }
  sc->any[k] = (unsigned char)any;
  sc->h_max[k] = h_max;
  sc->i_max[k] = i_max;
}

/** One pass over the particles on the threads: *any = 1 if a particle is
 *  outside the box or has a non-finite position or h (space_wrap_or_remove
 *  has work), and the largest h with its first particle. */
static void space_scan(const struct space *s, int *any, double *h_max, size_t *i_max) {
  struct space_scan sc;
  sc.s = s;
  const size_t n = s->parts->count;
  space_ranges(s, n, space_scan_range, &sc);
  *any = 0;
  *h_max = 0.0;
  *i_max = 0;
  for (int k = 0; k < space_nr_ranges(s, n); k++) {
    *any |= sc.any[k];
    if (sc.h_max[k] > *h_max) {
      *h_max = sc.h_max[k];
      *i_max = sc.i_max[k];
    }
  }
}

/** Wrap positions into the periodic box, or remove the particles outside the
 *  open box (logged by id); check positions and smoothing lengths. Returns
 *  the number removed. */
static size_t space_wrap_or_remove(struct space *s) {
  struct parts *p = s->parts;
  double *xs[3] = {p->x, p->y, p->z};
  size_t removed = 0;
  size_t i = 0;
  s->nr_gone = 0;
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
    space_count_removed(&s->removed, p, i, &s->clock);
    if (s->nr_gone == s->gone_cap) {
      s->gone_cap = 2 * s->gone_cap + 16;
      s->gone = error_realloc(s->gone, 5 * s->gone_cap * sizeof(double), "removed particles");
    }
    double *g = s->gone + 5 * s->nr_gone++;
    g[0] = p->x[i];
    g[1] = p->y[i];
    g[2] = p->z[i];
    g[3] = p->m[i];
    g[4] = p->h[i];
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

/** Choose the top-level grid from the largest kernel support: h_max, the
 *  largest smoothing length, first held by particle i_max. */
static void space_choose_grid(struct space *s, double h_max, size_t i_max) {
  const struct parts *p = s->parts;
  if (s->restore_h_max > 0.0) h_max = s->restore_h_max;
  if (h_max < s->h_max_floor) h_max = s->h_max_floor;
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

int space_top_cell_of(const struct space *s, double x, double y, double z) {
  return space_top_index(s, space_top_coord(s, 0, x), space_top_coord(s, 1, y),
                         space_top_coord(s, 2, z));
}

/** The counting sort by top-level cell on the threads: each range of the
 *  particles counts its cells, and scatters its particles after those of
 *  the ranges before it, which gives the serial sort's order (stable). */
struct space_topc {
  const struct space *s;
  int *topc;    /**< the top-level cell of each particle */
  size_t *hist; /**< [range][cell]: the range's count, then its first position */
  size_t *idx;  /**< the permutation */
  int pass;     /**< 0: cells and counts, 1: scatter */
};

static void space_topc_range(void *arg, int k, size_t lo, size_t hi) {
  const struct space_topc *tc = arg;
  const struct space *s = tc->s;
  const struct parts *p = s->parts;
  size_t *h = tc->hist + (size_t)k * (size_t)s->nr_top;
  if (tc->pass == 0) {
    for (size_t i = lo; i < hi; i++) {
      const int c = space_top_cell_of(s, p->x[i], p->y[i], p->z[i]);
      tc->topc[i] = c;
      h[c]++;
    }
  } else {
    for (size_t i = lo; i < hi; i++) tc->idx[h[tc->topc[i]]++] = i;
  }
}

/** Sort the particles by top-level cell into idx (n entries): the counts
 *  and offsets of the top-level cells, and the permutation. */
static void space_sort_top(struct space *s, size_t *idx) {
  const size_t n = s->parts->count;
  int t = space_nr_ranges(s, n);
  /* (one range where the ranges' counts would outweigh the particles) */
  if ((size_t)t * (size_t)s->nr_top > n) t = 1;
  struct space_topc tc = {
      s, error_malloc(n * sizeof(int) + 1, "particle cell index"),
      error_calloc((size_t)t * (size_t)s->nr_top, sizeof(size_t), "cell counts per range"), idx, 0};
  struct space_range_job job[SPACE_MAX_RANGES];
  for (int k = 0; k < t; k++)
    job[k] = (struct space_range_job){space_topc_range, &tc, k, n * (size_t)k / (size_t)t,
                                      n * (size_t)(k + 1) / (size_t)t};
  space_team(t, space_range_run, job, sizeof *job);
  size_t off = 0;
  for (int c = 0; c < s->nr_top; c++) {
    s->cells[c].offset = off;
    for (int k = 0; k < t; k++) {
      size_t *h = &tc.hist[(size_t)k * (size_t)s->nr_top + (size_t)c];
      const size_t m = *h;
      *h = off;
      off += m;
    }
    s->cells[c].count = off - s->cells[c].offset;
  }
  tc.pass = 1;
  space_team(t, space_range_run, job, sizeof *job);
  free(tc.topc);
  free(tc.hist);
}

/** The cells of one subtree while it is built (one thread each): local cell
 *  0 is the subtree's root (a top-level cell, or an octant handed to another
 *  job), the others are numbered in the order space_split makes them, which
 *  is the order of the serial build (pre-order, octants in order), so that
 *  merging the trees depth first numbers every cell as one thread would. */
struct space_tree {
  struct cell *cells; /**< the cells, 0: the root */
  int *progeny;       /**< 8 per cell: the local index of each octant, -1 where empty */
  int *graft;         /**< per cell: the job that builds its subtree, -1: none (built here) */
  int n, cap;         /**< cells in use, allocated */
};

/** Index of a new, zeroed cell of t. */
static int space_tree_new(struct space_tree *t) {
  if (t->n == t->cap) {
    if (t->cap > INT_MAX / 2) error_exit("space: too many cells");
    const int cap = t->cap < 16 ? 16 : 2 * t->cap;
    t->cells = error_realloc(t->cells, (size_t)cap * sizeof *t->cells, "cells");
    t->progeny = error_realloc(t->progeny, (size_t)cap * 8 * sizeof(int), "cell progeny");
    t->graft = error_realloc(t->graft, (size_t)cap * sizeof(int), "cell subtrees");
    t->cap = cap;
  }
  const int c = t->n++;
  memset(&t->cells[c], 0, sizeof t->cells[c]);
  for (int k = 0; k < 8; k++) t->progeny[8 * c + k] = -1;
  t->graft[c] = -1;
  return c;
}

/** A cell's range of the rebuild's work arrays while its subtree is split:
 *  the permutation and, in its order, each particle's octant of the cell's
 *  level (space_split).  A level's counting sort goes from one array of
 *  each pair to the other (no copy back: a leaf whose range ended in buf
 *  copies it to idx). */
struct space_range {
  size_t *idx, *buf;         /**< the permutation, its work array */
  unsigned char *oct, *obuf; /**< the octants (x 4, y 2, z 1), their work array */
  int in_buf;                /**< 1: the range's order is in buf and obuf */
  int have;                  /**< 1: oct holds the octants (0: a top-level cell) */
  size_t n[8];               /**< with have: the count of each octant */
};

/** The subtrees of a rebuild, one job each, on the rebuild's threads: the
 *  top-level cells to split, and the octants so large that another thread
 *  builds them (space_split hands an octant of more than spawn particles to
 *  a new job), so that one dense top-level cell does not keep the other
 *  threads waiting. */
struct space_tree_job {
  struct cell root;     /**< the subtree's root cell */
  struct space_range r; /**< its range of the work arrays */
  struct space_tree tree;
};

struct space_trees {
  const struct space *s;
  struct space_tree_job **job; /**< the jobs, in the order they were made */
  int n, cap;                  /**< jobs made, allocated */
  int next;                    /**< the next job to take */
  int busy;                    /**< jobs taken and not finished */
  size_t spawn;                /**< an octant of more particles is a new job (0: never) */
  pthread_mutex_t lock;
  pthread_cond_t more; /**< a job was added, or the last one finished */
};

/** Add a job for root (range r of root->count); returns its number. */
static int space_trees_add(struct space_trees *j, const struct cell *root,
                           const struct space_range *r) {
  struct space_tree_job *b = error_calloc(1, sizeof *b, "octree job");
  b->root = *root;
  b->r = *r;
  pthread_mutex_lock(&j->lock);
  if (j->n == j->cap) {
    j->cap = j->cap < 64 ? 64 : 2 * j->cap;
    j->job = error_realloc(j->job, (size_t)j->cap * sizeof *j->job, "octree jobs");
  }
  const int k = j->n++;
  j->job[k] = b;
  pthread_cond_signal(&j->more);
  pthread_mutex_unlock(&j->lock);
  return k;
}

/** Split cell c of t (range r of the work arrays) into octants,
 *  recursively, while it holds more than split_size particles; an octant
 *  of more than j->spawn particles is handed to a new job.  A particle's
 *  octant is x >= mid per direction (mid = loc + half, half = 0.5 width,
 *  an octant's loc mid or loc).  A top-level cell finds them from the
 *  positions in a pass of its own; below, the level above found them in
 *  its counting sort, by the same arithmetic with the octant's mid, for
 *  the octants that it will split (one pass over the range per level, not
 *  two and a copy back: the positions, read in increasing order within a
 *  range, cost less than the pass; keys of several levels' octants cost
 *  more in arithmetic than they saved at 1.1e6). */
static void space_split(struct space_trees *j, struct space_tree *t, int c, struct space_range r) {
  const struct space *s = j->s;
  const struct parts *p = s->parts;
  const double *xs[3] = {p->x, p->y, p->z};
  const size_t count = t->cells[c].count;
  const int depth = t->cells[c].depth;
  if (count <= (size_t)s->split_size || depth >= s->max_depth) {
    if (r.in_buf) memcpy(r.idx, r.buf, count * sizeof *r.idx);
    return;
  }
  size_t *idx = r.in_buf ? r.buf : r.idx, *buf = r.in_buf ? r.idx : r.buf;
  unsigned char *o = r.in_buf ? r.obuf : r.oct, *ob = r.in_buf ? r.oct : r.obuf;
  double mid[3], half[3], loc[3];
  for (int k = 0; k < 3; k++) {
    loc[k] = t->cells[c].loc[k];
    half[k] = 0.5 * t->cells[c].width[k];
    mid[k] = loc[k] + half[k];
  }
  size_t n[8] = {0}, start[8];
  if (r.have)
    memcpy(n, r.n, sizeof n);
  else
    /* counted in 8 bytes of a register, 255 at a time (no chain of
       increments of one counter in memory: neighbours share an octant) */
    for (size_t a0 = 0; a0 < count; a0 += 255) {
      const size_t a1 = count - a0 < 255 ? count : a0 + 255;
      uint64_t w = 0;
      for (size_t a = a0; a < a1; a++) {
        const size_t i = idx[a];
        const unsigned q = (unsigned)((xs[0][i] >= mid[0]) << 2 | (xs[1][i] >= mid[1]) << 1 |
                                      (xs[2][i] >= mid[2]));
        o[a] = (unsigned char)q;
        w += (uint64_t)1 << 8 * q;
      }
      for (int q = 0; q < 8; q++) n[q] += w >> 8 * q & 255;
    }
  /* each octant's mids, where it will be split */
  double cm[8][3];
  int next[8];
  for (int q = 0; q < 8; q++) {
    next[q] = n[q] > (size_t)s->split_size && depth + 1 < s->max_depth;
    for (int k = 0; k < 3; k++) {
      const double cl = (q >> (2 - k)) & 1 ? mid[k] : loc[k], ch = 0.5 * half[k];
      cm[q][k] = cl + ch;
    }
  }
  /* counting sort of the range by octant (bits x 4, y 2, z 1) */
  start[0] = 0;
  for (int q = 1; q < 8; q++) start[q] = start[q - 1] + n[q - 1];
  size_t pos[8], n2[8][8] = {{0}};
  memcpy(pos, start, sizeof pos);
  for (size_t a = 0; a < count; a++) {
    const int q = o[a];
    const size_t b = pos[q]++, i = idx[a];
    buf[b] = i;
    if (next[q]) {
      const unsigned char d = (unsigned char)((xs[0][i] >= cm[q][0]) << 2 |
                                              (xs[1][i] >= cm[q][1]) << 1 | (xs[2][i] >= cm[q][2]));
      ob[b] = d;
      n2[q][d]++;
    }
  }

  t->cells[c].split = 1;
  for (int q = 0; q < 8; q++) {
    if (n[q] == 0) continue;
    const int d = space_tree_new(t); /* may move t->cells */
    struct cell *child = &t->cells[d];
    const struct cell *parent = &t->cells[c];
    for (int k = 0; k < 3; k++) {
      const int bit = (q >> (2 - k)) & 1;
      child->loc[k] = bit ? mid[k] : loc[k];
      child->width[k] = half[k];
    }
    child->offset = parent->offset + start[q];
    child->count = n[q];
    child->depth = parent->depth + 1;
    child->top = parent->top;
    t->progeny[8 * c + q] = d;
    struct space_range rq = {.idx = r.idx + start[q],
                             .buf = r.buf + start[q],
                             .oct = r.oct + start[q],
                             .obuf = r.obuf + start[q],
                             .in_buf = !r.in_buf,
                             .have = next[q]};
    memcpy(rq.n, n2[q], sizeof rq.n);
    if (j->spawn && n[q] > j->spawn)
      t->graft[d] = space_trees_add(j, child, &rq);
    else
      space_split(j, t, d, rq);
  }
}

/** A thread of space_build_trees: take jobs until none is left and none
 *  running can add more. */
static void *space_trees_run(void *arg) {
  struct space_trees *j = arg;
  for (;;) {
    pthread_mutex_lock(&j->lock);
    while (j->next == j->n && j->busy > 0) pthread_cond_wait(&j->more, &j->lock);
    if (j->next == j->n) {
      pthread_mutex_unlock(&j->lock);
      break;
    }
    struct space_tree_job *b = j->job[j->next++];
    j->busy++;
    pthread_mutex_unlock(&j->lock);
    space_tree_new(&b->tree);
    b->tree.cells[0] = b->root;
    space_split(j, &b->tree, 0, b->r);
    pthread_mutex_lock(&j->lock);
    if (--j->busy == 0 && j->next == j->n) pthread_cond_broadcast(&j->more);
    pthread_mutex_unlock(&j->lock);
  }
  return NULL;
}

/** Number, depth first, the cells below local cell l of job b's tree,
 *  which is cell g of the space, from *next: each octant gets the next
 *  cell, then its subtree (the serial build's order).  The space's cell
 *  arrays hold every cell already (space_merge_trees). */
static void space_merge_tree(struct space *s, struct space_trees *j, struct space_tree_job *b,
                             int l, int g, int *next) {
  const struct space_tree *t = &b->tree;
  for (int q = 0; q < 8; q++) {
    const int d = t->progeny[8 * l + q];
    if (d < 0) continue;
    const int e = (*next)++;
    s->progeny_index[8 * g + q] = e;
    for (int k = 0; k < 8; k++) s->progeny_index[8 * e + k] = -1;
    if (t->graft[d] >= 0) {
      struct space_tree_job *sub = j->job[t->graft[d]];
      s->cells[e] = sub->tree.cells[0];
      s->cells[e].index = e;
      space_merge_tree(s, j, sub, 0, e, next);
    } else {
      s->cells[e] = t->cells[d];
      s->cells[e].index = e;
      space_merge_tree(s, j, b, d, e, next);
    }
  }
}

/** The cells below the root of job b, its subtrees' jobs' included: every
 *  cell of a tree but its root is an octant that the merge numbers. */
static long space_tree_cells(const struct space_trees *j, const struct space_tree_job *b) {
  long n = b->tree.n - 1;
  for (int d = 1; d < b->tree.n; d++)
    if (b->tree.graft[d] >= 0) n += space_tree_cells(j, j->job[b->tree.graft[d]]);
  return n;
}

/** Free job b's tree and those of its subtrees' jobs. */
static void space_tree_free(struct space_trees *j, struct space_tree_job *b) {
  for (int d = 1; d < b->tree.n; d++)
    if (b->tree.graft[d] >= 0) space_tree_free(j, j->job[b->tree.graft[d]]);
  free(b->tree.cells);
  free(b->tree.progeny);
  free(b->tree.graft);
  free(b);
}

/** The merge of the trees on the threads: top-level cell order[k] (the
 *  largest first) is numbered from first[order[k]]; a thread takes the
 *  next cell in that order until none is left. */
struct space_merge {
  struct space *s;
  struct space_trees *j;
  const int *job_of, *order, *first;
  int n;
  atomic_int next;
};

static void *space_merge_run(void *arg) {
  struct space_merge *m = arg;
  for (;;) {
    const int k = atomic_fetch_add(&m->next, 1);
    if (k >= m->n) break;
    const int c = m->order[k];
    struct space_tree_job *b = m->j->job[m->job_of[c]];
    m->s->cells[c].split = b->tree.cells[0].split;
    int next = m->first[c];
    space_merge_tree(m->s, m->j, b, 0, c, &next);
    space_tree_free(m->j, b);
  }
  return NULL;
}

/** Number the cells of every tree after the top-level cells, in the order
 *  of one thread (top-level cell by top-level cell, each depth first), on
 *  nt threads: each top-level cell's cells are counted first, so that its
 *  first number is known, and the space's cell arrays are grown once. */
static void space_merge_trees(struct space *s, struct space_trees *j, const int *job_of,
                              const int *order, int n, int nt) {
  int *first = error_malloc((size_t)s->nr_top * sizeof(int), "octree merge");
  long total = s->nr_cells;
  for (int c = 0; c < s->nr_top; c++) {
    first[c] = (int)total;
    if (job_of[c] >= 0) total += space_tree_cells(j, j->job[job_of[c]]);
    if (total > INT_MAX / 16) error_exit("space: too many cells");
  }
  if (total > s->cells_capacity) {
    const int cap = (int)(total + total / 4);
    s->cells = error_realloc(s->cells, (size_t)cap * sizeof *s->cells, "cells");
    s->progeny_index =
        error_realloc(s->progeny_index, (size_t)cap * 8 * sizeof(int), "cell progeny");
    s->cells_capacity = cap;
  }
  struct space_merge m = {s, j, job_of, order, first, n, 0};
  space_team(nt < n ? nt : (n > 0 ? n : 1), space_merge_run, &m, 0);
  s->nr_cells = (int)total;
  free(first);
}

/** Order of space_build_trees's first jobs: the most particles first, then
 *  by top-level cell (deterministic; the result does not depend on it). */
struct space_tree_size {
  size_t count;
  int c;
};

static int space_cmp_size_desc(const void *a, const void *b) {
  const struct space_tree_size *x = a, *y = b;
  if (x->count != y->count) return x->count > y->count ? -1 : 1;
  return x->c - y->c;
}

/** Build the octree of every top-level cell that holds more than
 *  split_size particles on s->nr_threads threads (a dense top-level cell's
 *  large octants as jobs of their own), and number their cells after the
 *  top-level cells in the order of the serial build. */
static void space_build_trees(struct space *s, size_t *idx, size_t *buf, unsigned char *oct,
                              unsigned char *obuf) {
  if (s->max_depth < 1 || s->parts->count <= (size_t)s->split_size) return;
  /* one pass over the top-level cells (a cache miss each), into room for
     as many as can hold more than split_size particles */
  const size_t most = s->parts->count / ((size_t)s->split_size + 1);
  struct space_tree_size *sz = error_malloc(
      (most < (size_t)s->nr_top ? most : (size_t)s->nr_top) * sizeof *sz, "octree jobs");
  int *job_of = error_malloc((size_t)s->nr_top * sizeof(int), "octree jobs");
  int n = 0;
  for (int c = 0; c < s->nr_top; c++) {
    job_of[c] = -1;
    if (s->cells[c].count > (size_t)s->split_size)
      sz[n++] = (struct space_tree_size){s->cells[c].count, c};
  }
  if (n == 0) {
    free(sz);
    free(job_of);
    return;
  }
  qsort(sz, (size_t)n, sizeof *sz, space_cmp_size_desc);

  const int nt = space_cell_threads(s);
  /* octants of more than an eighth of a thread's share are jobs of their own */
  const size_t share = s->parts->count / (8 * (size_t)nt);
  struct space_trees j = {
      .s = s,
      .spawn = nt > 1 ? (share > (size_t)s->split_size ? share : (size_t)s->split_size) : 0};
  if (pthread_mutex_init(&j.lock, NULL) || pthread_cond_init(&j.more, NULL))
    error_exit("space: cannot set up the threads of the rebuild (pthread_mutex_init)");
  for (int k = 0; k < n; k++) {
    const struct cell *top = &s->cells[sz[k].c];
    const struct space_range r = {.idx = idx + top->offset,
                                  .buf = buf + top->offset,
                                  .oct = oct + top->offset,
                                  .obuf = obuf + top->offset};
    job_of[sz[k].c] = space_trees_add(&j, top, &r);
  }
  space_team(nt, space_trees_run, &j, 0);
  pthread_mutex_destroy(&j.lock);
  pthread_cond_destroy(&j.more);

  /* merge, in the order of the top-level cells (the largest taken first) */
  int *order = error_malloc((size_t)n * sizeof(int), "octree merge");
  for (int k = 0; k < n; k++) order[k] = sz[k].c;
  free(sz);
  space_merge_trees(s, &j, job_of, order, n, nt);
  free(order);
  free(j.job);
  free(job_of);
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
  const unsigned char *reorder; /**< the fields to reorder (NULL: all) */
  int thread, nr_threads;
};

static void *space_permute_run(void *arg) {
  struct space_permute_job *j = arg;
  for (int k = 0; k < part_nr_fields; k++)
    j->nonzero[k * j->nr_threads + j->thread] =
        (!j->reorder || j->reorder[k]) && !part_field_zero(j->p, k, j->lo, j->hi);
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
  /* x0 = x: the positions of the rebuild (each thread its range) */
  struct parts *p = j->p;
  const size_t m = (j->hi - j->lo) * sizeof(double);
  memcpy(p->x0 + j->lo, p->x + j->lo, m);
  memcpy(p->y0 + j->lo, p->y + j->lo, m);
  memcpy(p->z0 + j->lo, p->z + j->lo, m);
  return NULL;
}

/** Reorder every particle field: new element i = old element perm[i], then
 *  x0 = x (y0, z0 likewise); buf: n words.  On up to nr_threads threads, each a range of elements
 *  (the result does not depend on the count); the random gathers of the
 *  first rebuild after reading a file dominate a rebuild (about 2 s for
 *  1e6 particles on one core before all-zero fields were skipped). */
static void space_permute(struct parts *p, const size_t *perm, void *buf, int nr_threads,
                          const unsigned char *reorder) {
  const size_t n = p->count;
  int t = nr_threads;
  if ((size_t)t > n / 65536 + 1) t = (int)(n / 65536 + 1);
  if (t > SPACE_MAX_THREADS) t = SPACE_MAX_THREADS;
  if (t < 1) t = 1;
  struct space_permute_job job[SPACE_MAX_THREADS];
  pthread_barrier_t bar;
  unsigned char *nonzero = error_malloc((size_t)part_nr_fields * (size_t)t, "rebuild field flags");
  if (pthread_barrier_init(&bar, NULL, (unsigned)t) != 0)
    error_exit("space: cannot set up the threads of the rebuild (pthread_barrier_init)");
  for (int k = 0; k < t; k++)
    job[k] = (struct space_permute_job){p,
                                        perm,
                                        buf,
                                        n * (size_t)k / (size_t)t,
                                        n * (size_t)(k + 1) / (size_t)t,
                                        &bar,
                                        nonzero,
                                        reorder,
                                        k,
                                        t};
  space_team(t, space_permute_run, job, sizeof *job);
  pthread_barrier_destroy(&bar);
  free(nonzero);
}

/** h_max and the bounding box (of x0 = x) of a leaf from its particles;
 *  an empty (top-level) cell gets a degenerate box at its corner. */
static void space_finish_leaf(struct space *s, struct cell *cell) {
  const struct parts *p = s->parts;
  if (cell->count == 0) {
    cell->h_max = 0.0;
    for (int k = 0; k < 3; k++) cell->bmin[k] = cell->bmax[k] = cell->loc[k];
    return;
  }
  double h_max = 0.0, lo[3] = {INFINITY, INFINITY, INFINITY},
         hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  const size_t end = cell->offset + cell->count;
  /* (comparisons, not fmin/fmax: those are library calls without
   * -ffinite-math-only, and the positions are finite here: space_scan) */
  for (size_t i = cell->offset; i < end; i++) {
    const double x[3] = {p->x[i], p->y[i], p->z[i]};
    if (p->h[i] > h_max) h_max = p->h[i];
    for (int k = 0; k < 3; k++) {
      lo[k] = x[k] < lo[k] ? x[k] : lo[k];
      hi[k] = x[k] > hi[k] ? x[k] : hi[k];
    }
  }
  cell->h_max = h_max;
  for (int k = 0; k < 3; k++) {
    cell->bmin[k] = lo[k];
    cell->bmax[k] = hi[k];
  }
}

/** Progeny and parent pointers from progeny_index, dx_max = 0, and a split
 *  cell's h_max and bounding box from its progeny's, bottom-up from cell c
 *  (the leaves' are done: space_finish_leaf). */
static void space_finish_cell(struct space *s, int c) {
  struct cell *cell = &s->cells[c];
  cell->dx_max = 0.0;
  if (!cell->split) {
    for (int q = 0; q < 8; q++) cell->progeny[q] = NULL;
    return;
  }
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
}

/** A pass over the cells on up to s->nr_threads threads taking chunks of
 *  cells: first every leaf from its particles (pass 0), then the split
 *  cells from their progeny, one top-level cell's tree at a time (pass 1:
 *  the particles of a dense top-level cell are spread over many leaves, so
 *  the threads share them in the first pass).  bounds 0: the rebuild's
 *  boxes and links (space_finish_leaf, space_finish_cell); 1: h_max and
 *  dx_max (cell_leaf_bounds, cell_gather_bounds). */
struct space_finish_job {
  struct space *s;
  int pass, bounds;
  _Atomic int next; /**< first cell of the next chunk */
};

#define SPACE_FINISH_CHUNK 64

static void *space_finish_run(void *arg) {
  struct space_finish_job *j = arg;
  struct space *s = j->s;
  const int n = j->pass == 0 ? s->nr_cells : s->nr_top;
  for (;;) {
    /* (pass 1: a few top-level cells may hold most of the cells) */
    const int chunk = j->pass == 0 ? SPACE_FINISH_CHUNK : 4;
    const int c0 = atomic_fetch_add(&j->next, chunk);
    if (c0 >= n) break;
    const int c1 = c0 + chunk < n ? c0 + chunk : n;
    for (int c = c0; c < c1; c++) {
      struct cell *cell = &s->cells[c];
      if (j->pass == 1 && j->bounds)
        cell_gather_bounds(cell);
      else if (j->pass == 1)
        space_finish_cell(s, c);
      else if (!cell->split && j->bounds)
        cell_leaf_bounds(s->parts, cell);
      else if (!cell->split)
        space_finish_leaf(s, cell);
    }
  }
  return NULL;
}

static void space_finish_passes(struct space *s, int bounds, int nr_threads) {
  for (int pass = 0; pass < 2; pass++) {
    struct space_finish_job job = {s, pass, bounds, 0};
    space_team(nr_threads, space_finish_run, &job, 0);
  }
}

static void space_finish_cells(struct space *s) {
  space_finish_passes(s, 0, space_cell_threads(s));
}

void space_update_bounds(struct space *s, int nr_threads) {
  if (s->parts->count < 50000 || nr_threads < 1) nr_threads = 1;
  space_finish_passes(s, 1, nr_threads);
}

size_t space_prepare(struct space *s) {
  int any;
  double h_max;
  size_t i_max;
  space_scan(s, &any, &h_max, &i_max);
  size_t removed = 0;
  if (any) {
    /* wrap, remove or report (rare): then the largest h again */
    removed = space_wrap_or_remove(s);
    space_scan(s, &any, &h_max, &i_max);
  }
  space_choose_grid(s, h_max, i_max);
  return removed;
}

size_t space_rebuild(struct space *s) {
  struct parts *p = s->parts;
  const double w0 = error_walltime();
  const size_t removed = space_prepare(s);
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
  if (s->oct_capacity < 2 * n) {
    free(s->sort_oct);
    s->oct_capacity = 2 * n;
    s->sort_oct = error_malloc(s->oct_capacity * sizeof *s->sort_oct + 1, "octree octants");
  }
  size_t *idx = s->sort_index, *buf = s->sort_index + n;
  space_sort_top(s, idx);

  /* the octrees, then one reordering of every particle field */
  const double w1 = error_walltime();
  space_build_trees(s, idx, buf, s->sort_oct, s->sort_oct + n);
  const double w2 = error_walltime();
  /* buf (n words) is free after the split */
  /* (and x0 = x) */
  if (n) space_permute(p, idx, buf, s->nr_threads, s->reorder);
  const double w3 = error_walltime();
  space_finish_cells(s);
  const double w4 = error_walltime();
  if (s->nr_rebuilds > 1) {
    const double t[4] = {w1 - w0, w2 - w1, w3 - w2, w4 - w3};
    for (int k = 0; k < 4; k++) s->t_parts[k] += t[k];
    s->nr_timed++;
  }
  error_log(1,
            "space: rebuild %d: %zu particles, %d x %d x %d top-level cells, %d cells; "
            "s: wrap and sort by top-level cell %.3f, octrees %.3f, reorder %.3f, boxes %.3f",
            s->nr_rebuilds, n, s->cdim[0], s->cdim[1], s->cdim[2], s->nr_cells, w1 - w0, w2 - w1,
            w3 - w2, w4 - w3);
  return removed;
}

int space_rebuild_removes(const struct space *s) {
  const struct parts *p = s->parts;
  int any;
  double h_max;
  size_t i_max;
  space_scan(s, &any, &h_max, &i_max);
  if (!any) return 0;
  for (size_t i = 0; i < p->count; i++) {
    if (!isfinite(p->x[i]) || !isfinite(p->y[i]) || !isfinite(p->z[i]) || !(p->h[i] > 0.0) ||
        !isfinite(p->h[i]))
      return 1;
    if (!s->periodic && (p->x[i] < 0.0 || p->x[i] >= s->dim[0] || p->y[i] < 0.0 ||
                         p->y[i] >= s->dim[1] || p->z[i] < 0.0 || p->z[i] >= s->dim[2]))
      return 1;
  }
  return 0;
}

const size_t *space_order(const struct space *s) {
  return s->sort_index;
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
  return space_should_rebuild_at(s, sqrt(d2_max), h_max);
}

int space_should_rebuild_at(const struct space *s, double dmax, double h_max) {
  const double H = kernel_gamma * h_max;
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
