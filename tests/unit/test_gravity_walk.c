/* The walk with an explicit stack on index arrays (gravity_walk.h, the one
 * the GPU's walk kernel runs) against the CPU's recursive walks, both
 * recording instead of computing: every root as gpu_grav_tree_all walks
 * them (the self walk of each top-level cell, the symmetric walk of each
 * near pair, the long-range walk of each far pair), and the four lists
 * (part, field, part_sym, field_sym) must hold the same (target, source)
 * entries, as multisets.  Sets: a uniform sphere and two clustered Plummer
 * spheres (lopsided M2P and P2L), each at the first pass (no acceleration
 * scale: the tighter geometric angle) and at a second pass (the adaptive
 * criterion on |ga| of the first), with the constant softening and with
 * the softening tied to h; and a third pass of a time-bins step of active
 * particles only (gravity_props.active: half the particles and every third
 * of the rest sleep), where both walks must skip the same cells and turn
 * the same pairs one-way.  Exit 0 pass, 1 fail. */
#ifdef HAVE_CONFIG_H
#include "config.h"
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "tasks/gravity/gravity_cpu.h"
#include "tasks/gravity/gravity_walk.h"
#include "tests/helpers/gravity_sets.h"
#include "tests/helpers/gravity_walk_set.h"
#include "src/part.h"
#include "src/space.h"

#define BOX 4.0

/** Entries a walker takes from its stack before it hands the rest on, in
 *  the test of the GPU's division of the walks (small: many rounds). */
#define GRAVITY_TEST_BUDGET 5

/** Stack of a walker that walks a root to its end (the GPU's walkers
 *  hold GRAVITY_WALK_STACK entries and hand on what does not fit). */
#define TEST_STACK 8192

static int failures = 0;

/** (target, source) entries as 64-bit keys, for sorting. */
static int cmp_u64(const void *a, const void *b) {
  const unsigned long long x = *(const unsigned long long *)a, y = *(const unsigned long long *)b;
  return x < y ? -1 : x > y;
}

static unsigned long long *keys(const int *t, const int *s, size_t n) {
  unsigned long long *k = malloc((n ? n : 1) * sizeof *k);
  for (size_t i = 0; i < n; i++)
    k[i] = ((unsigned long long)(unsigned)t[i] << 32) | (unsigned long long)(unsigned)s[i];
  qsort(k, n, sizeof *k, cmp_u64);
  return k;
}

/** Compare list k of the recursive walks (a) with the stack walk's (b). */
static void compare(const char *what, const char *kind, const struct gravity_rec_list *a,
                    const int *bt, const int *bs, unsigned long long bn) {
  int ok = a->n == bn;
  if (ok) {
    unsigned long long *ka = keys(a->target, a->source, a->n), *kb = keys(bt, bs, bn);
    ok = memcmp(ka, kb, a->n * sizeof *ka) == 0;
    free(ka);
    free(kb);
  }
  printf("  %-44s %-10s %9zu recursive, %9llu stack: %s\n", what, kind, a->n, bn,
         ok ? "same" : "FAIL");
  failures += !ok;
}

static void run(const char *name, int two_bodies, double h_factor) {
  const size_t n = 30000;
  struct gset_tree W;
  gset_tree_make(&W, n, 7, two_bodies, BOX, 8);
  W.gp.h_factor = h_factor;
  const int nc = W.sp.nr_cells, nt = W.sp.nr_top;
  /* the tree as index arrays */
  int *progeny = malloc(8 * (size_t)nc * sizeof(int)), *count = malloc((size_t)nc * sizeof(int));
  unsigned char *split = malloc((size_t)nc);
  gravity_walk_tree_arrays(W.sp.cells, nc, progeny, count, split);
  struct gravity_multipole *mp = malloc((size_t)nc * sizeof *mp);
  double *a_min = malloc((size_t)nc * sizeof(double)), *hs = malloc((size_t)nc * sizeof(double));
  int *stack = malloc(3 * (size_t)TEST_STACK * sizeof(int));
  unsigned char *act = malloc((size_t)nc);
  size_t entries_all = 0;
  for (int pass = 0; pass < 3; pass++) {
    if (pass == 1)
      gravity_tree_all(&W.p, W.sp.cells, nt, W.gc, &W.gp); /* |ga| for the adaptive pass */
    if (pass == 2) {
      /* time bins, a step of active particles only (gravity_props.active):
       * the particles of the lower half in x and every third one elsewhere
       * sleep, so that whole cells, and parts of cells, do not receive (the
       * upward pass reads the bins: at tick 2 those of bin 1 end their step,
       * those of bin 2 are in the middle of theirs) */
      for (size_t i = 0; i < n; i++) {
        const int sleeps = W.p.x[i] < 0.5 * BOX || i % 3 == 0;
        W.p.flags[i] = sleeps ? PART_INACTIVE : 0;
        W.p.time_bin[i] = sleeps ? 2 : 1;
      }
      W.gp.active = act;
      W.gp.active_ti = 2;
    }
    for (int i = 0; i < nt; i++) gravity_up(&W.p, W.sp.cells + i, W.gc, &W.gp);
    /* the recursive walks, recorded */
    struct gravity_gpu_rec rec;
    memset(&rec, 0, sizeof rec);
    gravity_gpu_record(&rec);
    for (int i = 0; i < nt; i++) {
      gravity_interact_cells(&W.p, W.sp.cells + i, W.sp.cells + i, W.gc, &W.gp);
      for (int j = i + 1; j < nt; j++)
        if (gravity_top_pair_is_near(W.sp.cells + i, W.sp.cells + j, &W.gp))
          gravity_interact_cells(&W.p, W.sp.cells + i, W.sp.cells + j, W.gc, &W.gp);
    }
    for (int i = 0; i < nt; i++)
      gravity_long_range(&W.p, W.sp.cells + i, W.sp.cells, nt, W.gc, &W.gp);
    gravity_gpu_record(NULL);
    /* the stack walk from every root: as one walker per root (budget
     * unlimited), and as the GPU's kernels divide it (gravity_gpu.cu):
     * walkers of GRAVITY_TEST_BUDGET entries (or fewer: a full stack) that
     * hand what is left on their stack to a queue (one too small to take it all: the rest stays
     * with its walker), the queue then walked by the next round */
    for (int k = 0; k < nc; k++)
      mp[k] = W.gc[k].mp, a_min[k] = W.gc[k].a_min, hs[k] = W.gc[k].h_support;
    const struct gravity_walk_tree T = {progeny, count, split, mp, a_min, hs, W.gp.active};
    const size_t entries = rec.part.n + rec.field.n + rec.part_sym.n + rec.field_sym.n;
    if (pass == 1) entries_all = entries;
    if (pass == 2) {
      int marked = 0, top_marked = 0;
      for (int k = 0; k < nc; k++) marked += act[k];
      for (int k = 0; k < nt; k++) top_marked += act[k];
      printf(
          "  %s, active cells only: %d of %d cells receive (%d of %d top-level), %zu of %zu "
          "recorded entries\n",
          name, marked, nc, top_marked, nt, entries, entries_all);
      if (!(marked > 0 && marked < nc && entries < entries_all)) {
        printf("  %s: the active-only walk was not exercised: FAIL\n", name);
        failures++;
      }
    }
    const struct gravity_walk_params wp = {W.gp.G,         W.gp.theta,    W.gp.epsilon_fmm,
                                           W.gp.h_support, W.gp.h_factor, W.gp.order};
    double *lo_hi = malloc(6 * (size_t)nt * sizeof(double));
    for (int i = 0; i < nt; i++)
      for (int d = 0; d < 3; d++)
        lo_hi[6 * i + d] = W.sp.cells[i].bmin[d], lo_hi[6 * i + 3 + d] = W.sp.cells[i].bmax[d];
    const size_t capk = 4 * (rec.part.n + rec.field.n + rec.part_sym.n + rec.field_sym.n) + 16;
    /* the roots among the non-empty cells only (top, as the GPU's walk
     * takes them), in the walkers' mode that hands on */
    int *ctop = malloc((size_t)nt * sizeof(int)), ne = 0;
    double *clo_hi = malloc(6 * (size_t)nt * sizeof(double));
    for (int i = 0; i < nt; i++)
      if (W.sp.cells[i].count > 0) {
        memcpy(clo_hi + 6 * ne, lo_hi + 6 * i, 6 * sizeof(double));
        ctop[ne++] = i;
      }
    for (int mode = 0; mode < 2; mode++) {
      unsigned long long cnt[4] = {0, 0, 0, 0};
      struct gravity_walk_lists L;
      L.n = cnt;
      for (int k = 0; k < 4; k++) {
        L.target[k] = malloc(capk * sizeof(int));
        L.source[k] = malloc(capk * sizeof(int));
        L.cap[k] = capk;
      }
      int deep = 0, rounds = 0;
      unsigned long long handed = 0, kept = 0;
      struct gravity_walk_buf B;
      memset(B.n, 0, sizeof B.n);
      const long long budget = mode ? GRAVITY_TEST_BUDGET : (long long)1 << 62;
      /* handed on: a stack of 48 entries (one self entry's 36 successors
       * fill it), so that walkers also stop and hand on for want of room */
      const int scap = mode ? 48 : TEST_STACK;
      const unsigned long long qcap = 2048;
      int *qi[2] = {malloc(3 * qcap * sizeof(int)), malloc(3 * qcap * sizeof(int))};
      unsigned long long qn[2] = {0, 0};
/* walk: the stack's n entries with the budget, the rest to queue o */
#define WALK_ITEMS(n0, o)                                                                       \
  do {                                                                                          \
    const struct gravity_walk_queue Q = {qi[o], qn + (o), qcap};                                \
    int nw = gravity_walk_run(&T, &wp, &L, &B, stack, scap, (n0), budget);                      \
    if (nw > 0) {                                                                               \
      const int left = gravity_walk_spill(&Q, stack, nw);                                       \
      handed += (unsigned long long)(nw - left), kept += (unsigned long long)left;              \
      nw = left > 0                                                                             \
               ? gravity_walk_run(&T, &wp, &L, &B, stack, TEST_STACK, left, (long long)1 << 62) \
               : 0;                                                                             \
    }                                                                                           \
    deep += nw > 0;                                                                             \
  } while (0)
      const int rn = mode ? ne : nt;
      for (long long r = 0; r < (long long)rn * rn; r++)
        if (gravity_walk_root(count, mode ? clo_hi : lo_hi, rn, W.gp.theta, W.gp.h_support, NULL,
                              mode ? ctop : NULL, r, stack))
          WALK_ITEMS(1, 0);
      for (int cur = 0; qn[cur] > 0; cur ^= 1, rounds++) {
        const unsigned long long m = qn[cur] < qcap ? qn[cur] : qcap;
        qn[cur ^ 1] = 0;
        for (unsigned long long q = 0; q < m; q++) {
          memcpy(stack, qi[cur] + 3 * q, 3 * sizeof(int));
          WALK_ITEMS(1, cur ^ 1);
        }
        qn[cur] = 0;
      }
#undef WALK_ITEMS
      for (int k = 0; k < 4; k++) gravity_walk_flush(&L, &B, k);
      char what[160];
      snprintf(what, sizeof what, "%s, %s, %s, %s", name,
               pass == 2 ? "active only"
               : pass    ? "adaptive pass"
                         : "first pass",
               h_factor > 0.0 ? "eps tied to h" : "constant eps",
               mode ? "handed on" : "one walker per root");
      if (deep) {
        printf("  %s: %d walks ran out of stack: FAIL\n", what, deep);
        failures++;
      }
      if (mode) {
        printf("  %s: %d rounds, %llu entries handed on, %llu kept for want of room\n", what,
               rounds, handed, kept);
        if (rounds < 2 || kept == 0) {
          printf("  %s: the hand-on scheme was not exercised (rounds, a full queue): FAIL\n", what);
          failures++;
        }
      }
      compare(what, "part", &rec.part, L.target[0], L.source[0], cnt[0]);
      compare(what, "field", &rec.field, L.target[1], L.source[1], cnt[1]);
      compare(what, "part_sym", &rec.part_sym, L.target[2], L.source[2], cnt[2]);
      compare(what, "field_sym", &rec.field_sym, L.target[3], L.source[3], cnt[3]);
      for (int k = 0; k < 4; k++) free(L.target[k]), free(L.source[k]);
      free(qi[0]), free(qi[1]);
    }
    free(lo_hi), free(clo_hi), free(ctop);
    size_t n_m2p = 0;
    for (size_t k = 0; k < rec.part.n; k++) n_m2p += rec.part.source[k] < 0;
    if (rec.field_sym.n == 0 || rec.part_sym.n == 0 || rec.field.n == 0 ||
        (two_bodies && n_m2p == 0)) {
      printf("  %s, %s: a list the case must exercise is empty: FAIL\n", name,
             pass ? "adaptive pass" : "first pass");
      failures++;
    }
    gravity_gpu_rec_free(&rec);
  }
  free(progeny), free(count), free(split), free(mp), free(a_min), free(hs), free(stack), free(act);
  gset_tree_free(&W);
}

/** Several MPI ranks as the GPU's walk sees them (gravity_walk_root's
 *  skips): some top-level cells of copies only (1), some of which only
 *  some particles are here (2, read by their records on the host), the
 *  rest this rank's.  The stack walk from the skipped roots among the
 *  non-empty cells must record what the CPU's tasks walk there
 *  (gravity_task.c): the self walk of each cell of this rank, the near
 *  pairs of two such cells both ways and of one with a cell of copies one
 *  way (for it), no walk with a cell of the second kind, and the
 *  long-range walk of each cell of this rank against every far cell of
 *  the first two kinds (the copies' multipoles being their records'). */
static void run_ranks(const char *name, int two_bodies) {
  const size_t n = 30000;
  struct gset_tree W;
  gset_tree_make(&W, n, 11, two_bodies, BOX, 8);
  const int nc = W.sp.nr_cells, nt = W.sp.nr_top;
  gravity_tree_all(&W.p, W.sp.cells, nt, W.gc, &W.gp); /* |ga| for the adaptive criterion */
  for (int i = 0; i < nt; i++) gravity_up(&W.p, W.sp.cells + i, W.gc, &W.gp);
  /* the kinds: of the non-empty cells, every third of copies only, every
   * seventh (of the rest) of some particles only */
  unsigned char *skip = calloc((size_t)(nt > 0 ? nt : 1), 1);
  int k = 0, kinds[3] = {0, 0, 0};
  for (int i = 0; i < nt; i++) {
    if (W.sp.cells[i].count == 0) continue;
    skip[i] = k % 3 == 1 ? 1 : (k % 7 == 2 ? 2 : 0);
    kinds[skip[i]]++;
    k++;
  }
  /* the CPU's tasks, recorded */
  struct gravity_gpu_rec rec;
  memset(&rec, 0, sizeof rec);
  gravity_gpu_record(&rec);
  int one_way = 0;
  for (int i = 0; i < nt; i++) {
    const struct cell *ci = W.sp.cells + i;
    if (ci->count == 0 || skip[i] == 2) continue;
    if (skip[i] == 0) gravity_interact_cells(&W.p, ci, ci, W.gc, &W.gp);
    for (int j = 0; j < nt; j++) {
      const struct cell *cj = W.sp.cells + j;
      if (j == i || cj->count == 0 || skip[j] == 2) continue;
      if (gravity_top_pair_is_near(ci, cj, &W.gp)) {
        if (j < i) continue;
        if (!skip[i] && !skip[j])
          gravity_interact_cells(&W.p, ci, cj, W.gc, &W.gp);
        else if (!skip[i] || !skip[j]) {
          gravity_interact_pair_one_way(&W.p, skip[i] ? cj : ci, skip[i] ? ci : cj, W.gc, &W.gp);
          one_way++;
        }
      } else if (!skip[i])
        gravity_interact_pair_one_way(&W.p, ci, cj, W.gc, &W.gp);
    }
  }
  gravity_gpu_record(NULL);
  /* the stack walk from the non-empty cells' roots with the skips */
  int *progeny = malloc(8 * (size_t)nc * sizeof(int)), *count = malloc((size_t)nc * sizeof(int));
  unsigned char *split = malloc((size_t)nc);
  gravity_walk_tree_arrays(W.sp.cells, nc, progeny, count, split);
  struct gravity_multipole *mp = malloc((size_t)nc * sizeof *mp);
  double *a_min = malloc((size_t)nc * sizeof(double)), *hs = malloc((size_t)nc * sizeof(double));
  for (int q = 0; q < nc; q++)
    mp[q] = W.gc[q].mp, a_min[q] = W.gc[q].a_min, hs[q] = W.gc[q].h_support;
  const struct gravity_walk_tree T = {progeny, count, split, mp, a_min, hs, NULL};
  const struct gravity_walk_params wp = {W.gp.G,         W.gp.theta,    W.gp.epsilon_fmm,
                                         W.gp.h_support, W.gp.h_factor, W.gp.order};
  int *top = malloc((size_t)nt * sizeof(int)), ne = 0;
  unsigned char *cskip = malloc((size_t)nt);
  double *lo_hi = malloc(6 * (size_t)nt * sizeof(double));
  for (int i = 0; i < nt; i++) {
    if (W.sp.cells[i].count == 0 || skip[i] == 2) continue;
    top[ne] = i, cskip[ne] = skip[i];
    for (int d = 0; d < 3; d++)
      lo_hi[6 * ne + d] = W.sp.cells[i].bmin[d], lo_hi[6 * ne + 3 + d] = W.sp.cells[i].bmax[d];
    ne++;
  }
  const size_t capk = 4 * (rec.part.n + rec.field.n + rec.part_sym.n + rec.field_sym.n) + 16;
  unsigned long long cnt[4] = {0, 0, 0, 0};
  struct gravity_walk_lists L;
  L.n = cnt;
  for (int q = 0; q < 4; q++) {
    L.target[q] = malloc(capk * sizeof(int));
    L.source[q] = malloc(capk * sizeof(int));
    L.cap[q] = capk;
  }
  struct gravity_walk_buf B;
  memset(B.n, 0, sizeof B.n);
  int *stack = malloc(3 * (size_t)TEST_STACK * sizeof(int));
  int deep = 0;
  for (long long r = 0; r < (long long)ne * ne; r++)
    if (gravity_walk_root(count, lo_hi, ne, W.gp.theta, W.gp.h_support, cskip, top, r, stack))
      deep += gravity_walk_run(&T, &wp, &L, &B, stack, TEST_STACK, 1, (long long)1 << 62) > 0;
  for (int q = 0; q < 4; q++) gravity_walk_flush(&L, &B, q);
  char what[200];
  snprintf(what, sizeof what, "%s, ranks' skips (%d, %d, %d cells; %d one way)", name, kinds[0],
           kinds[1], kinds[2], one_way);
  if (deep || !kinds[1] || !kinds[2] || !one_way) {
    printf("  %s: %d walks out of stack, or a kind of cell missing: FAIL\n", what, deep);
    failures++;
  }
  compare(what, "part", &rec.part, L.target[0], L.source[0], cnt[0]);
  compare(what, "field", &rec.field, L.target[1], L.source[1], cnt[1]);
  compare(what, "part_sym", &rec.part_sym, L.target[2], L.source[2], cnt[2]);
  compare(what, "field_sym", &rec.field_sym, L.target[3], L.source[3], cnt[3]);
  for (int q = 0; q < 4; q++) free(L.target[q]), free(L.source[q]);
  gravity_gpu_rec_free(&rec);
  free(stack), free(lo_hi), free(cskip), free(top), free(progeny), free(count), free(split);
  free(mp), free(a_min), free(hs), free(skip);
  gset_tree_free(&W);
}

/** gravity_walk_root with the skips of several MPI ranks, on four
 *  top-level cells in a row (0, 1 and 2 near each other, 3 far from all):
 *  cell 0 of this rank, 1 of copies only, 2 read by its record (some of
 *  its particles here), 3 of this rank.  Each root's walk (or none). */
static void roots_skip(void) {
  const int nt = 4, count[4] = {10, 10, 10, 10};
  const double x[4] = {0.0, 1.0, 2.0, 40.0};
  double lo_hi[24];
  for (int c = 0; c < nt; c++)
    for (int d = 0; d < 3; d++) {
      lo_hi[6 * c + d] = (d == 0 ? x[c] : 0.0) - 0.5;
      lo_hi[6 * c + 3 + d] = (d == 0 ? x[c] : 0.0) + 0.5;
    }
  const unsigned char skip[4] = {0, 1, 2, 0};
  /* the expected (a, b, sym) of root (i, j); a = -1: no walk */
  const int want[4][4][3] = {
      {{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}, {0, 3, 0}}, /* 0: self; one way from 1; 2 skipped; far 3 */
      {{-1, 0, 0}, {-1, 0, 0}, {-1, 0, 0}, {-1, 0, 0}}, /* 1: copies only receive nothing */
      {{-1, 0, 0}, {-1, 0, 0}, {-1, 0, 0}, {-1, 0, 0}}, /* 2: read by its record */
      {{3, 0, 0}, {3, 1, 0}, {-1, 0, 0}, {3, 3, 1}}};   /* 3: far from 0 and 1 */
  int bad = 0;
  for (int i = 0; i < nt; i++)
    for (int j = 0; j < nt; j++) {
      int item[3] = {-1, -1, -1};
      const int ok =
          gravity_walk_root(count, lo_hi, nt, 0.5, 0.0, skip, NULL, (long long)i * nt + j, item);
      const int *w = want[i][j];
      if (ok != (w[0] >= 0) || (ok && (item[0] != w[0] || item[1] != w[1] || item[2] != w[2]))) {
        printf("  root (%d, %d) with skips: %d (%d, %d, %d), expected %s (%d, %d, %d): FAIL\n", i,
               j, ok, item[0], item[1], item[2], w[0] >= 0 ? "a walk" : "none", w[0], w[1], w[2]);
        bad++;
      }
    }
  /* without skips every root of the four has its walk as on one rank */
  int n = 0;
  for (long long r = 0; r < nt * nt; r++) {
    int item[3];
    n += gravity_walk_root(count, lo_hi, nt, 0.5, 0.0, NULL, NULL, r, item);
  }
  /* the same four among six cells, two of them empty, by the non-empty
   * ones only (top): the same walks, on the cells' own numbers */
  {
    const int count6[6] = {10, 0, 10, 10, 0, 10}, top[4] = {0, 2, 3, 5};
    for (int i = 0; i < nt; i++)
      for (int j = 0; j < nt; j++) {
        int item[3] = {-1, -1, -1};
        const int ok =
            gravity_walk_root(count6, lo_hi, nt, 0.5, 0.0, skip, top, (long long)i * nt + j, item);
        const int *w = want[i][j];
        if (ok != (w[0] >= 0) ||
            (ok && (item[0] != top[w[0]] || item[1] != top[w[1]] || item[2] != w[2]))) {
          printf("  root (%d, %d) of the non-empty cells: %d (%d, %d, %d): FAIL\n", i, j, ok,
                 item[0], item[1], item[2]);
          bad++;
        }
      }
  }
  if (n != 4 + 3 + 6) {
    printf("  roots without skips: %d walks, expected 13 (4 self, 3 near pairs, 6 far): FAIL\n", n);
    bad++;
  }
  printf("  roots with the skips of several MPI ranks (copies only, read by record): %s\n",
         bad ? "FAIL" : "same as the CPU's tasks");
  failures += bad;
}

int main(int argc, char **argv) {
  error_init(argc > 0 ? argv[0] : "test_gravity_walk");
  roots_skip();
  printf("stack walk (gravity_walk.h) against the recursive walks, recorded:\n");
  run("uniform sphere", 0, 0.0);
  run("two Plummer spheres", 1, 0.0);
  run("two Plummer spheres", 1, 1.0);
  run_ranks("uniform sphere", 0);
  run_ranks("two Plummer spheres", 1);
  printf(failures ? "FAIL\n" : "PASS\n");
  return failures ? 1 : 0;
}
