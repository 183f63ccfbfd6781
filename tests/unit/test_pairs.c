/* Neighbour search (theory/validation.md, "Neighbour search"): the
 * interacting pairs found by the cell
 * space and the loop skeleton (tasks/iact_loop.h) equal a brute-force O(N^2)
 * search, exactly.
 *
 * For random and clustered particles, uniform and variable h (a factor 10
 * spread), periodic (minimum image) and open boxes, several split sizes and
 * top-level grid limits, after a rebuild and again after a small drift and
 * growth of h without rebuild:
 *  - symmetric form: every pair with r < max(H_i, H_j) exactly once;
 *  - gather form: every ordered (i, j), i != j, with r < H_i exactly once;
 *  - the r2, dx and h passed to the interaction equal the brute-force ones;
 *  - every cell owns a contiguous range, progeny split their parent's range,
 *    particles lie in their cell's box and bounding box, h_max is right, no
 *    particle is lost, and particles outside an open box are counted;
 *  - space_should_rebuild answers 0 after a rebuild and 1 after a large drift
 *    or a large growth of h.
 * Exit 0 pass, 1 fail. */
#ifdef HAVE_CONFIG_H
#include "config.h"
#endif

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "tasks/hydro/kernel.h"
#include "src/part.h"
#include "src/space.h"

/** One interaction seen: key = id_i * N + id_j and its r2. */
struct rec {
  uint64_t key;
  double r2;
};

/** The interactions recorded by the skeleton (rec) and by brute force. */
static struct rec *rec;
static size_t rec_n, rec_cap;
static uint64_t rec_N;   /**< id multiplier */
static long rec_bad_arg; /**< calls whose r2, dx or h arguments are inconsistent */

static void rec_push(uint64_t key, double r2) {
  if (rec_n == rec_cap) {
    rec_cap = rec_cap ? 2 * rec_cap : 1 << 16;
    rec = error_realloc(rec, rec_cap * sizeof *rec, "records");
  }
  rec[rec_n].key = key;
  rec[rec_n].r2 = r2;
  rec_n++;
}

/** The interaction of the test: record the pair (symmetric: unordered). */
static void record(const struct parts *p, size_t i, size_t j, double r2, const double dx[3],
                   double hi, double hj, int symmetric) {
  if (r2 != dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2] || hi != p->h[i] || hj != p->h[j])
    rec_bad_arg++;
  uint64_t a = (uint64_t)p->id[i], b = (uint64_t)p->id[j];
  if (symmetric && a > b) {
    const uint64_t t = a;
    a = b;
    b = t;
  }
  rec_push(a * rec_N + b, r2);
}

#define IACT_LOOP_NAME test
#define IACT_LOOP_SYM(p, i, j, r2, dx, hi, hj) record(p, i, j, r2, dx, hi, hj, 1)
#define IACT_LOOP_NONSYM(p, i, j, r2, dx, hi, hj) record(p, i, j, r2, dx, hi, hj, 0)
#include "tasks/iact_loop.h"

/** A density sum through the symmetric form: both sides, each with its own h
 *  (W vanishes beyond the support, so adding both is right). */
static void rho_sym(struct parts *p, size_t i, size_t j, double r2, double hi, double hj) {
  const double r = sqrt(r2);
  p->rho[i] += p->m[j] * kernel_W(r, hi);
  p->rho[j] += p->m[i] * kernel_W(r, hj);
}

/* the same skeleton again, included a second time under another name */
#define IACT_LOOP_NAME rho
#define IACT_LOOP_SYM(p, i, j, r2, dx, hi, hj) rho_sym(p, i, j, r2, hi, hj)
#define IACT_LOOP_NONSYM(p, i, j, r2, dx, hi, hj) \
  ((p)->rho[i] += (p)->m[j] * kernel_W(sqrt(r2), hi))
#include "tasks/iact_loop.h"

static int failures = 0;

#define CHECK(cond, ...)              \
  do {                                \
    if (!(cond)) {                    \
      printf("  FAIL: " __VA_ARGS__); \
      printf("\n");                   \
      failures++;                     \
    }                                 \
  } while (0)

/** Uniform random number in [0, 1). */
static double urand(void) {
  return rand() / (RAND_MAX + 1.0);
}

/** Standard normal deviate (Box-Muller). */
static double nrand(void) {
  const double u = urand() + 1e-300, v = urand();
  return sqrt(-2.0 * log(u)) * cos(2.0 * M_PI * v);
}

static int cmp_rec(const void *a, const void *b) {
  const uint64_t x = ((const struct rec *)a)->key, y = ((const struct rec *)b)->key;
  return x < y ? -1 : x > y;
}

/** Minimum-image separation in one direction, as the skeleton computes it:
 *  (x_i - x_j) - shift with shift in {0, +L, -L}. */
static double sep(double xi, double xj, double L, int periodic) {
  double d = xi - xj;
  if (periodic) {
    if (d > 0.5 * L)
      d = d - L;
    else if (d < -0.5 * L)
      d = d - (-L);
  }
  return d;
}

/** Brute-force interactions into rec (symmetric: i < j with r < max H;
 *  gather: i != j with r < H_i). */
static void brute_force(const struct parts *p, const double L[3], int periodic, int symmetric) {
  rec_n = 0;
  for (size_t i = 0; i < p->count; i++) {
    const double Hi = kernel_gamma * p->h[i], Hi2 = Hi * Hi;
    for (size_t j = symmetric ? i + 1 : 0; j < p->count; j++) {
      if (j == i) continue;
      const double dx[3] = {sep(p->x[i], p->x[j], L[0], periodic),
                            sep(p->y[i], p->y[j], L[1], periodic),
                            sep(p->z[i], p->z[j], L[2], periodic)};
      const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
      const double Hj = kernel_gamma * p->h[j];
      if (symmetric ? (r2 < Hi2 || r2 < Hj * Hj) : r2 < Hi2) {
        uint64_t a = (uint64_t)p->id[i], b = (uint64_t)p->id[j];
        if (symmetric && a > b) {
          const uint64_t t = a;
          a = b;
          b = t;
        }
        rec_push(a * rec_N + b, r2);
      }
    }
  }
  qsort(rec, rec_n, sizeof *rec, cmp_rec);
}

/** The skeleton's interactions into rec, over the tasks the engine makes:
 *  one self per non-empty top-level cell, one pair per space_top_pairs. */
static void skeleton(struct space *s, int symmetric) {
  struct space_pair *pairs;
  const size_t npairs = space_top_pairs(s, &pairs);
  rec_n = 0;
  rec_bad_arg = 0;
  for (int c = 0; c < s->nr_top; c++) {
    if (symmetric)
      loop_test_self(s->parts, &s->cells[c]);
    else
      loop_test_self_gather(s->parts, &s->cells[c]);
  }
  for (size_t k = 0; k < npairs; k++) {
    const struct cell *ci = &s->cells[pairs[k].ci], *cj = &s->cells[pairs[k].cj];
    if (symmetric) {
      loop_test_pair(s->parts, ci, cj, pairs[k].shift);
    } else {
      const double back[3] = {-pairs[k].shift[0], -pairs[k].shift[1], -pairs[k].shift[2]};
      loop_test_pair_gather(s->parts, ci, cj, pairs[k].shift);
      loop_test_pair_gather(s->parts, cj, ci, back);
    }
  }
  free(pairs);
  qsort(rec, rec_n, sizeof *rec, cmp_rec);
}

/** Compare the skeleton's and the brute-force interactions. */
static void compare(struct space *s, int symmetric, const char *when) {
  const char *form = symmetric ? "symmetric" : "gather";
  brute_force(s->parts, s->dim, s->periodic, symmetric);
  struct rec *ref = error_malloc(rec_n * sizeof *ref + 1, "reference");
  memcpy(ref, rec, rec_n * sizeof *ref);
  const size_t nref = rec_n;
  skeleton(s, symmetric);
  size_t dup = 0, missing = 0, extra = 0, r2diff = 0, a = 0, b = 0;
  for (size_t k = 1; k < rec_n; k++)
    if (rec[k].key == rec[k - 1].key) dup++;
  while (a < nref || b < rec_n) {
    if (b == rec_n || (a < nref && ref[a].key < rec[b].key)) {
      missing++;
      a++;
    } else if (a == nref || rec[b].key < ref[a].key) {
      extra++;
      b++;
    } else {
      if (ref[a].r2 != rec[b].r2) r2diff++;
      a++;
      b++;
    }
  }
  printf(
      "  %-9s %-12s %8zu pairs: %zu missing, %zu extra, %zu twice, %zu r2 differ, %ld bad "
      "arguments\n",
      form, when, nref, missing, extra, dup, r2diff, rec_bad_arg);
  CHECK(nref > 0, "no interacting pairs: the test set-up is wrong");
  CHECK(missing == 0 && extra == 0 && dup == 0 && r2diff == 0 && rec_bad_arg == 0,
        "%s pairs differ from brute force (%s)", form, when);
  free(ref);
}

/** Density sums rho_i = sum_j m_j W(r_ij, h_i) (j = i included) from the
 *  symmetric and the gather forms against a brute-force sum: the gather form
 *  that the GPU uses and the symmetric CPU form give the same result. */
static void compare_density(struct space *s, const char *when) {
  struct parts *p = s->parts;
  const size_t n = p->count;
  double *ref = error_malloc(n * sizeof *ref + 1, "reference densities");
  for (size_t i = 0; i < n; i++) {
    double rho = p->m[i] * kernel_W(0.0, p->h[i]);
    for (size_t j = 0; j < n; j++) {
      if (j == i) continue;
      const double dx = sep(p->x[i], p->x[j], s->dim[0], s->periodic);
      const double dy = sep(p->y[i], p->y[j], s->dim[1], s->periodic);
      const double dz = sep(p->z[i], p->z[j], s->dim[2], s->periodic);
      const double r = sqrt(dx * dx + dy * dy + dz * dz);
      if (r < kernel_gamma * p->h[i]) rho += p->m[j] * kernel_W(r, p->h[i]);
    }
    ref[i] = rho;
  }
  struct space_pair *pairs;
  const size_t npairs = space_top_pairs(s, &pairs);
  double err[2] = {0.0, 0.0};
  for (int form = 0; form < 2; form++) {
    for (size_t i = 0; i < n; i++) p->rho[i] = p->m[i] * kernel_W(0.0, p->h[i]);
    for (int c = 0; c < s->nr_top; c++) {
      if (form == 0)
        loop_rho_self(p, &s->cells[c]);
      else
        loop_rho_self_gather(p, &s->cells[c]);
    }
    for (size_t k = 0; k < npairs; k++) {
      const struct cell *ci = &s->cells[pairs[k].ci], *cj = &s->cells[pairs[k].cj];
      const double back[3] = {-pairs[k].shift[0], -pairs[k].shift[1], -pairs[k].shift[2]};
      if (form == 0) {
        loop_rho_pair(p, ci, cj, pairs[k].shift);
      } else {
        loop_rho_pair_gather(p, ci, cj, pairs[k].shift);
        loop_rho_pair_gather(p, cj, ci, back);
      }
    }
    for (size_t i = 0; i < n; i++) err[form] = fmax(err[form], fabs(p->rho[i] / ref[i] - 1.0));
  }
  printf(
      "  density   %-12s max relative difference to brute force: symmetric %.1e, gather "
      "%.1e\n",
      when, err[0], err[1]);
  CHECK(err[0] < 1e-12 && err[1] < 1e-12, "densities differ from brute force (%s)", when);
  free(pairs);
  free(ref);
}

/** Structure of the space: ranges, boxes, h_max, no particle lost. */
static void check_cells(const struct space *s, size_t n_expected, int64_t id_total) {
  const struct parts *p = s->parts;
  CHECK(p->count == n_expected, "%zu particles after rebuild, expected %zu", p->count, n_expected);
  /* top-level cells partition [0, N) in order */
  size_t next = 0;
  for (int c = 0; c < s->nr_top; c++) {
    CHECK(s->cells[c].offset == next, "top cell %d starts at %zu, expected %zu", c,
          s->cells[c].offset, next);
    next = s->cells[c].offset + s->cells[c].count;
  }
  CHECK(next == p->count, "top cells hold %zu of %zu particles", next, p->count);
  long bad_range = 0, bad_box = 0, bad_h = 0, bad_leaf = 0;
  const double tol = 1e-12;
  for (int c = 0; c < s->nr_cells; c++) {
    const struct cell *cell = &s->cells[c];
    if (cell->split) {
      size_t pos = cell->offset;
      double hm = 0.0;
      for (int q = 0; q < 8; q++) {
        const struct cell *child = cell->progeny[q];
        if (!child) continue;
        if (child->offset != pos || child->parent != cell || child->depth != cell->depth + 1 ||
            child->count == 0)
          bad_range++;
        pos += child->count;
        hm = fmax(hm, child->h_max);
      }
      if (pos != cell->offset + cell->count) bad_range++;
      if (hm != cell->h_max) bad_h++;
    } else {
      if (cell->count > (size_t)s->split_size && cell->depth < s->max_depth) bad_leaf++;
      double hm = 0.0;
      for (size_t i = cell->offset; i < cell->offset + cell->count; i++) hm = fmax(hm, p->h[i]);
      if (hm != cell->h_max) bad_h++;
    }
    for (size_t i = cell->offset; i < cell->offset + cell->count; i++) {
      const double x[3] = {p->x[i], p->y[i], p->z[i]};
      for (int k = 0; k < 3; k++) {
        const double lo = cell->loc[k], hi = cell->loc[k] + cell->width[k];
        if (x[k] < lo - tol * s->dim[k] || x[k] >= hi + tol * s->dim[k]) bad_box++;
        if (x[k] < cell->bmin[k] || x[k] > cell->bmax[k]) bad_box++;
        if (x[k] < 0.0 || x[k] >= s->dim[k]) bad_box++;
      }
      if (p->x0[i] != p->x[i] || p->y0[i] != p->y[i] || p->z0[i] != p->z[i]) bad_box++;
    }
  }
  CHECK(bad_range == 0, "%ld cells whose progeny do not split their range", bad_range);
  CHECK(bad_box == 0, "%ld particle coordinates outside their cell or box", bad_box);
  CHECK(bad_h == 0, "%ld cells with a wrong h_max", bad_h);
  CHECK(bad_leaf == 0, "%ld leaves above the split size", bad_leaf);
  /* no particle lost or duplicated: ids distinct, and their sum is kept */
  int64_t sum = 0;
  for (size_t i = 0; i < p->count; i++) sum += p->id[i];
  CHECK(sum == id_total, "particle ids sum to %lld, expected %lld", (long long)sum,
        (long long)id_total);
}

/** Particle distributions: uniform; 4 Gaussian clumps over a uniform fifth;
 *  uniform with 40 particles at each of 50 positions (coincident particles:
 *  leaves at the deepest level hold more than split_size). */
enum distribution { DIST_UNIFORM, DIST_CLUMPS, DIST_DUPLICATES };

/** One configuration. */
struct config {
  const char *name;
  enum distribution dist;
  int periodic;
  size_t n;
  double H_min, H_max; /**< kernel support H = kernel_gamma h, log-uniform in [H_min, H_max] */
  int split_size;
  int max_top;
};

static void run(const struct config *cf, unsigned seed) {
  const double L[3] = {1.0, 1.3, 0.8};
  struct parts p;
  parts_alloc(&p, cf->n);
  srand(seed);
  double clump[4][3];
  for (int c = 0; c < 4; c++)
    for (int k = 0; k < 3; k++) clump[c][k] = L[k] * (0.1 + 0.8 * urand());
  size_t outside = 0;
  int64_t id_inside = 0;
  for (size_t i = 0; i < cf->n; i++) {
    double x[3];
    const int c = rand() % 5; /* clumps: 4 Gaussian clumps + a uniform fifth */
    for (int k = 0; k < 3; k++) {
      if (cf->dist == DIST_CLUMPS && c < 4)
        x[k] = clump[c][k] + 0.07 * L[k] * nrand();
      else
        x[k] = L[k] * urand();
      /* an open box loses a few particles placed just outside */
      if (!cf->periodic && i % 97 == 0) x[k] = (k == (int)(i % 3)) ? -1e-9 * i - 1e-9 : x[k];
    }
    if (cf->periodic && cf->dist == DIST_UNIFORM && i % 89 == 0) x[0] += 3.0 * L[0]; /* wrap */
    if (cf->dist == DIST_DUPLICATES && i >= 50) {
      x[0] = p.x[i % 50];
      x[1] = p.y[i % 50];
      x[2] = p.z[i % 50];
    }
    p.x[i] = x[0];
    p.y[i] = x[1];
    p.z[i] = x[2];
    p.m[i] = 1.0 + urand();
    p.h[i] = cf->H_min * pow(cf->H_max / cf->H_min, urand()) / kernel_gamma;
    p.id[i] = (int64_t)i;
    int out = 0;
    for (int k = 0; k < 3; k++)
      if (x[k] < 0.0 || x[k] >= L[k]) out = 1;
    if (!cf->periodic && out)
      outside++;
    else
      id_inside += (int64_t)i;
  }
  rec_N = cf->n;

  struct space s;
  space_init(&s, &p, L, cf->periodic, cf->split_size, cf->max_top);
  const size_t removed = space_rebuild(&s);
  printf("%s: N = %zu, %s, split %d, top grid %d x %d x %d, %d cells, %zu removed\n", cf->name,
         cf->n, cf->periodic ? "periodic" : "open", cf->split_size, s.cdim[0], s.cdim[1], s.cdim[2],
         s.nr_cells, removed);
  CHECK(removed == outside, "%zu particles removed, %zu were outside the open box", removed,
        outside);
  CHECK(!cf->periodic || outside == 0, "test set-up");
  check_cells(&s, cf->n - outside, id_inside);
  CHECK(space_should_rebuild(&s) == 0, "should_rebuild right after a rebuild");

  compare(&s, 1, "at rebuild");
  compare(&s, 0, "at rebuild");
  compare_density(&s, "at rebuild");

  /* drift and grow h without rebuilding, within what the grid allows */
  const double wmin = fmin(s.width[0], fmin(s.width[1], s.width[2]));
  const double Lmin = fmin(L[0], fmin(L[1], L[2])), H_grown = kernel_gamma * s.h_max * 1.03;
  double dmax = 0.2 * fmin(s.max_drift_fraction * wmin, 0.5 * (wmin - H_grown));
  if (cf->periodic) dmax = fmin(dmax, 0.2 * (0.5 * Lmin - H_grown));
  CHECK(dmax > 0.0, "test set-up: no room to drift");
  for (size_t i = 0; i < p.count; i++) {
    double d[3] = {nrand(), nrand(), nrand()};
    const double nd = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-300;
    const double len = dmax * urand() / nd;
    p.x[i] += d[0] * len;
    p.y[i] += d[1] * len;
    p.z[i] += d[2] * len;
    p.h[i] *= 1.0 + 0.03 * urand();
  }
  CHECK(space_should_rebuild(&s) == 0, "should_rebuild after a small drift");
  for (int c = 0; c < s.nr_top; c++) cell_update_bounds(&p, &s.cells[c]);
  compare(&s, 1, "after drift");
  compare(&s, 0, "after drift");
  compare_density(&s, "after drift");

  /* a large drift, then a large h, ask for a rebuild */
  const double x_keep = p.x[0], h_keep = p.h[0];
  p.x[0] += 0.6 * s.width[0];
  CHECK(space_should_rebuild(&s) == 1, "should_rebuild after a drift of 0.6 cell widths");
  p.x[0] = x_keep;
  p.h[0] = 2.0 * wmin / kernel_gamma;
  CHECK(space_should_rebuild(&s) == 1, "should_rebuild after h grew beyond the cell width");
  p.h[0] = h_keep;

  /* a second rebuild of the drifted particles is still exact */
  const size_t n_before = p.count;
  space_rebuild(&s);
  int64_t ids = 0;
  for (size_t i = 0; i < p.count; i++) ids += p.id[i];
  if (!cf->periodic) {
    check_cells(&s, p.count, ids); /* drifted particles may have left the open box */
  } else {
    check_cells(&s, n_before, id_inside);
  }
  compare(&s, 1, "2nd rebuild");

  space_free(&s);
  parts_free(&p);
}

/** The rebuild on several threads (space.nr_threads: the octrees of the
 *  top-level cells built at the same time, the fields reordered in
 *  ranges) gives the particles of the one-thread rebuild, bit for bit, in
 *  every field, and the same cells with the same numbers. */
static void check_threaded_rebuild(int clustered) {
  const size_t n = 300000;
  const double L[3] = {1.0, 1.0, 1.0};
  struct parts a, b;
  parts_alloc(&a, n);
  parts_alloc(&b, n);
  srand(77);
  for (size_t i = 0; i < n; i++) {
    a.x[i] = urand(), a.y[i] = urand(), a.z[i] = urand();
    if (clustered && i % 4) {
      /* three quarters in one top-level cell (of 16^3): its large octants
       * are octree jobs of their own (space_split) */
      a.x[i] = 0.53 + 0.02 * (a.x[i] - 0.5);
      a.y[i] = 0.53 + 0.02 * (a.y[i] - 0.5);
      a.z[i] = 0.53 + 0.02 * (a.z[i] - 0.5);
    }
    a.m[i] = 1.0 + urand();
    a.h[i] = 0.01 * (1.0 + urand());
    a.u[i] = urand();
    a.id[i] = (int64_t)i;
    a.mat[i] = rand() % 3;
  }
  for (int f = 0; f < part_nr_fields; f++)
    memcpy(part_field_array(&b, &part_fields[f]), part_field_array(&a, &part_fields[f]),
           n * part_fields[f].size);
  struct space sa, sb;
  space_init(&sa, &a, L, 0, 32, 16);
  space_init(&sb, &b, L, 0, 32, 16);
  sb.nr_threads = 5;
  space_rebuild(&sa);
  space_rebuild(&sb);
  int differ = 0;
  for (int f = 0; f < part_nr_fields; f++)
    if (memcmp(part_field_array(&a, &part_fields[f]), part_field_array(&b, &part_fields[f]),
               n * part_fields[f].size)) {
      printf("  field %s differs\n", part_fields[f].name);
      differ++;
    }
  int cells_differ = sa.nr_cells != sb.nr_cells;
  for (int c = 0; c < sa.nr_cells && !cells_differ; c++) {
    const struct cell *x = &sa.cells[c], *y = &sb.cells[c];
    cells_differ |= memcmp(x->loc, y->loc, sizeof x->loc) ||
                    memcmp(x->width, y->width, sizeof x->width) ||
                    memcmp(x->bmin, y->bmin, sizeof x->bmin) ||
                    memcmp(x->bmax, y->bmax, sizeof x->bmax) || x->offset != y->offset ||
                    x->count != y->count || x->depth != y->depth || x->split != y->split ||
                    x->index != c || y->index != c || x->top != y->top || x->h_max != y->h_max ||
                    (x->parent ? x->parent->index : -1) != (y->parent ? y->parent->index : -1);
    for (int q = 0; q < 8; q++)
      cells_differ |= (x->progeny[q] ? x->progeny[q]->index : -1) !=
                      (y->progeny[q] ? y->progeny[q]->index : -1);
  }
  CHECK(a.count == b.count && differ == 0 && !cells_differ && sa.nr_cells > sa.nr_top,
        "the rebuild on 5 threads reordered %d of %d fields differently from 1 thread, cells %s",
        differ, part_nr_fields, cells_differ ? "differ" : "equal");
  /* the bounds after a drift: space_update_bounds on 5 threads against
   * cell_update_bounds top-level cell by top-level cell */
  for (size_t i = 0; i < n && !differ; i++) {
    const double dx = 1e-3 * (urand() - 0.5), dh = 1.0 + 0.2 * urand();
    a.x[i] += dx, b.x[i] += dx;
    a.h[i] *= dh, b.h[i] *= dh;
  }
  for (int c = 0; c < sa.nr_top; c++) cell_update_bounds(&a, &sa.cells[c]);
  space_update_bounds(&sb, 5);
  int bounds_differ = 0;
  for (int c = 0; c < sa.nr_cells && !cells_differ; c++)
    bounds_differ += sa.cells[c].h_max != sb.cells[c].h_max ||
                     sa.cells[c].dx_max != sb.cells[c].dx_max ||
                     !(sa.cells[c].h_max > 0.0) != (sa.cells[c].count == 0);
  CHECK(bounds_differ == 0, "space_update_bounds on 5 threads: %d cells differ from one thread",
        bounds_differ);
  printf(
      "threaded rebuild (%s): %zu particles, %d fields, %d cells, 1 and 5 threads identical: "
      "%s\n",
      clustered ? "clustered" : "uniform", n, part_nr_fields, sa.nr_cells,
      differ || cells_differ ? "no" : "yes");
  space_free(&sa);
  space_free(&sb);
  parts_free(&a);
  parts_free(&b);
}

int main(int argc, char **argv) {
  error_init(argc > 0 ? argv[0] : "test_pairs");
  /* supports H relative to the box (1 x 1.3 x 0.8); H_max must stay below
   * half the periodic box (0.4) */
  const struct config configs[] = {
      {"uniform", DIST_UNIFORM, 1, 3000, 0.146, 0.146, 8, 64},
      {"uniform", DIST_UNIFORM, 0, 3000, 0.146, 0.146, 8, 64},
      {"uniform-varh", DIST_UNIFORM, 1, 3000, 0.018, 0.18, 1, 64},
      {"uniform-varh", DIST_UNIFORM, 0, 3000, 0.018, 0.18, 32, 64},
      {"clumps", DIST_CLUMPS, 1, 4000, 0.046, 0.046, 16, 64},
      {"clumps", DIST_CLUMPS, 0, 4000, 0.046, 0.046, 4, 64},
      {"clumps-varh", DIST_CLUMPS, 1, 4000, 0.011, 0.11, 8, 64},
      {"clumps-varh", DIST_CLUMPS, 0, 4000, 0.011, 0.11, 64, 64},
      {"clumps-varh-top3", DIST_CLUMPS, 1, 2500, 0.011, 0.11, 8, 3},
      {"no-split", DIST_UNIFORM, 1, 2000, 0.128, 0.128, 100000, 64},
      {"big-h", DIST_UNIFORM, 1, 2000, 0.09, 0.365, 16, 64},
      {"big-h", DIST_UNIFORM, 0, 2000, 0.09, 0.365, 16, 64},
      {"one-cell", DIST_CLUMPS, 1, 2000, 0.18, 0.383, 16, 1},
      {"two-cells", DIST_UNIFORM, 1, 2000, 0.18, 0.383, 16, 2},
      {"coincident", DIST_DUPLICATES, 1, 2000, 0.05, 0.1, 8, 64},
      {"coincident", DIST_DUPLICATES, 0, 2000, 0.05, 0.1, 8, 64},
  };
  const int nconf = sizeof configs / sizeof configs[0];
  for (int c = 0; c < nconf; c++) run(&configs[c], 1234u + (unsigned)c);
  check_threaded_rebuild(0);
  check_threaded_rebuild(1);
  free(rec);
  printf("%s\n", failures ? "FAIL" : "PASS");
  return failures ? 1 : 0;
}
