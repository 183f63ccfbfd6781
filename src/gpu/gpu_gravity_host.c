/* Host side of self-gravity on the GPU (gpu_engine.h): the cell tree as
 * index arrays, the recorded interactions grouped by receiving cell (a
 * counting sort over the workers' lists, on host threads), the multipoles
 * packed for the upload, and the serial sequence of a whole evaluation. */
#include <limits.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "gpu_engine.h"

/* ------------------------------------------------------------------ tree */

/** Append the pairs (child, c) of c's non-empty progeny at level depth and
 *  c's leaves, recursively. */
static void tree_visit(struct gpu_grav_host *h, const struct cell *c, int depth) {
  if (c->count == 0) return;
  if (!c->split) {
    if (h->nr_leaf == h->leaf_cap) {
      h->leaf_cap = 2 * h->leaf_cap + 1024;
      h->leaf = error_realloc(h->leaf, h->leaf_cap * sizeof(int), "GPU gravity tree");
    }
    h->leaf[h->nr_leaf++] = c->index;
    return;
  }
  for (int q = 0; q < 8; q++) {
    const struct cell *cp = c->progeny[q];
    if (cp == NULL || cp->count == 0) continue;
    if (h->nr_l2l == h->l2l_cap) {
      h->l2l_cap = 2 * h->l2l_cap + 1024;
      h->l2l_tmp = error_realloc(h->l2l_tmp, 3 * h->l2l_cap * sizeof(int), "GPU gravity tree");
    }
    int *e = h->l2l_tmp + 3 * h->nr_l2l++;
    e[0] = cp->index;
    e[1] = c->index;
    e[2] = depth;
    tree_visit(h, cp, depth + 1);
  }
}

void gpu_grav_tree_build(struct gpu_grav_host *h, const struct space *s) {
  const int nc = s->nr_cells;
  if (nc > h->cells_cap) {
    h->cells_cap = nc + nc / 4 + 16;
    h->offset = error_realloc(h->offset, h->cells_cap * sizeof(size_t), "GPU gravity tree");
    h->count = error_realloc(h->count, h->cells_cap * sizeof(int), "GPU gravity tree");
  }
  for (int k = 0; k < nc; k++) {
    if (s->cells[k].index != k) error_bug("cell %d has index %d", k, s->cells[k].index);
    h->offset[k] = s->cells[k].offset;
    h->count[k] = (int)s->cells[k].count;
  }
  h->nr_l2l = h->nr_leaf = 0;
  for (int c = 0; c < s->nr_top; c++) tree_visit(h, &s->cells[c], 0);
  /* the pairs by level (counting sort; within a level, in visiting order) */
  int nlev = 0;
  for (int k = 0; k < h->nr_l2l; k++)
    if (h->l2l_tmp[3 * k + 2] + 1 > nlev) nlev = h->l2l_tmp[3 * k + 2] + 1;
  h->level_start = error_realloc(h->level_start, (nlev + 2) * sizeof(int), "GPU gravity tree");
  memset(h->level_start, 0, (nlev + 2) * sizeof(int));
  for (int k = 0; k < h->nr_l2l; k++) h->level_start[h->l2l_tmp[3 * k + 2] + 2]++;
  for (int L = 0; L < nlev; L++) h->level_start[L + 2] += h->level_start[L + 1];
  h->l2l_child = error_realloc(h->l2l_child, (h->l2l_cap + 1) * sizeof(int), "GPU gravity tree");
  h->l2l_parent = error_realloc(h->l2l_parent, (h->l2l_cap + 1) * sizeof(int), "GPU gravity tree");
  for (int k = 0; k < h->nr_l2l; k++) {
    const int q = h->level_start[h->l2l_tmp[3 * k + 2] + 1]++;
    h->l2l_child[q] = h->l2l_tmp[3 * k];
    h->l2l_parent[q] = h->l2l_tmp[3 * k + 1];
  }
  struct gpu_grav_tree *t = &h->tree;
  t->nr_cells = nc;
  t->offset = h->offset;
  t->count = h->count;
  t->nr_l2l = h->nr_l2l;
  t->l2l_child = h->l2l_child;
  t->l2l_parent = h->l2l_parent;
  t->nr_levels = nlev;
  t->level_start = h->level_start;
  t->nr_leaves = h->nr_leaf;
  t->leaf = h->leaf;
  h->built_rebuild = s->nr_rebuilds;
  h->built_cells = s->cells;
}

void gpu_grav_pack_multipoles(struct gravity_multipole *dst, const struct cell *c,
                              const struct gravity_cell *gc) {
  dst[c->index] = gc[c->index].mp;
  if (c->split)
    for (int q = 0; q < 8; q++)
      if (c->progeny[q]) gpu_grav_pack_multipoles(dst, c->progeny[q], gc);
}

/* ------------------------------------------------------------------ grouping */

/** The shared state of one grouping (one kind, struct gravity_rec_list of
 *  every worker): lists [0, nl1) one way, [nl1, nl) mutual (each entry
 *  also counts from source to target). */
struct group_job {
  const struct gravity_rec_list *const *lists; /**< the workers' lists */
  int nl, nl1;                                 /**< their number; the one-way ones */
  int nc;                                      /**< cells */
  int *cnt;                                    /**< nl * nc counters, then positions */
  int *tot;                                    /**< nc totals */
  int *source;                                 /**< the grouped sources */
};

/** One thread's share of par_for. */
struct par_arg {
  void (*fn)(void *, int, int); /**< the work */
  void *arg;                    /**< its argument */
  int t, nt;                    /**< this thread, of nt */
};

/** Thread body of par_for. */
static void *par_body(void *p) {
  struct par_arg *a = p;
  a->fn(a->arg, a->t, a->nt);
  return NULL;
}

/** Run fn(arg, t, nt) for t = 0 .. nt - 1 on nt threads (t = 0 here). */
static void par_for(int nt, void (*fn)(void *, int, int), void *arg) {
  struct par_arg a[64];
  pthread_t tid[64];
  if (nt > 64) nt = 64;
  if (nt < 1) nt = 1;
  for (int t = 0; t < nt; t++) a[t] = (struct par_arg){fn, arg, t, nt};
  for (int t = 1; t < nt; t++)
    if (pthread_create(&tid[t], NULL, par_body, &a[t]))
      error_exit("cannot start a thread to group the gravity interactions");
  fn(arg, 0, nt);
  for (int t = 1; t < nt; t++) pthread_join(tid[t], NULL);
}

/** Phase 1, by list: count each list's entries per target cell. */
static void group_count(void *arg, int t, int nt) {
  struct group_job *j = arg;
  for (int w = t; w < j->nl; w += nt) {
    int *cnt = j->cnt + (size_t)w * j->nc;
    memset(cnt, 0, j->nc * sizeof(int));
    const struct gravity_rec_list *l = j->lists[w];
    for (size_t k = 0; k < l->n; k++) cnt[l->target[k]]++;
    if (w >= j->nl1)
      for (size_t k = 0; k < l->n; k++) cnt[l->source[k]]++;
  }
}

/** Phase 2, by range of cells: each cell's total. */
static void group_total(void *arg, int t, int nt) {
  struct group_job *j = arg;
  const int c0 = (int)((long)j->nc * t / nt), c1 = (int)((long)j->nc * (t + 1) / nt);
  for (int c = c0; c < c1; c++) {
    long s = 0;
    for (int w = 0; w < j->nl; w++) s += j->cnt[(size_t)w * j->nc + c];
    j->tot[c] = (int)s;
  }
}

/** Phase 3, by range of cells: each list's first position in each cell's
 *  slice (tot now holds the slices' starts). */
static void group_position(void *arg, int t, int nt) {
  struct group_job *j = arg;
  const int c0 = (int)((long)j->nc * t / nt), c1 = (int)((long)j->nc * (t + 1) / nt);
  for (int c = c0; c < c1; c++) {
    int run = j->tot[c];
    for (int w = 0; w < j->nl; w++) {
      int *q = j->cnt + (size_t)w * j->nc + c;
      const int n = *q;
      *q = run;
      run += n;
    }
  }
}

/** Phase 4, by list: scatter the sources. */
static void group_scatter(void *arg, int t, int nt) {
  struct group_job *j = arg;
  for (int w = t; w < j->nl; w += nt) {
    int *pos = j->cnt + (size_t)w * j->nc;
    const struct gravity_rec_list *l = j->lists[w];
    if (w < j->nl1)
      for (size_t k = 0; k < l->n; k++) j->source[pos[l->target[k]]++] = l->source[k];
    else
      for (size_t k = 0; k < l->n; k++) {
        j->source[pos[l->target[k]]++] = l->source[k];
        j->source[pos[l->source[k]]++] = l->target[k];
      }
  }
}

void gpu_grav_group(struct gpu_grav_host *h, const struct gravity_gpu_rec *rec, int nr_rec,
                    int nr_cells, int nthreads) {
  const struct gravity_rec_list *lists[2][512];
  if (nr_rec > 256) error_bug("more than 256 gravity recording lists");
  for (int w = 0; w < nr_rec; w++) {
    lists[0][w] = &rec[w].part;
    lists[1][w] = &rec[w].field;
    lists[0][nr_rec + w] = &rec[w].part_sym;
    lists[1][nr_rec + w] = &rec[w].field_sym;
  }
  const int nl = 2 * nr_rec;
  const size_t ncnt = (size_t)nl * (size_t)nr_cells;
  if (ncnt > h->cnt_cap) {
    h->cnt_cap = ncnt + ncnt / 4 + 64;
    h->cnt = error_realloc(h->cnt, h->cnt_cap * sizeof(int), "GPU gravity lists");
  }
  if ((size_t)nr_cells + 1 > h->tot_cap) {
    h->tot_cap = (size_t)nr_cells + nr_cells / 4 + 16;
    h->tot = error_realloc(h->tot, h->tot_cap * sizeof(int), "GPU gravity lists");
  }
  for (int k = 0; k < 2; k++) {
    struct gpu_grav_groups_host *g = &h->groups[k];
    size_t n = 0;
    for (int w = 0; w < nl; w++) n += (w < nr_rec ? 1 : 2) * lists[k][w]->n;
    if (n > (size_t)INT_MAX) error_exit("%zu recorded gravity interactions: more than the GPU lists hold", n);
    if (n > g->cap) {
      g->cap = n + n / 4 + 1024;
      /* pinned: uploaded every step (contents rebuilt below) */
      gpu_host_free(g->source);
      g->source = gpu_host_alloc(g->cap * sizeof(int), "the grouped gravity interactions");
    }
    if (nr_cells + 1 > g->tcap) {
      g->tcap = nr_cells + nr_cells / 4 + 16;
      g->cell = error_realloc(g->cell, g->tcap * sizeof(int), "GPU gravity lists");
      g->start = error_realloc(g->start, (g->tcap + 1) * sizeof(int), "GPU gravity lists");
    }
    struct group_job j = {lists[k], nl, nr_rec, nr_cells, h->cnt, h->tot, g->source};
    const int nt = nthreads < 1 ? 1 : nthreads;
    par_for(nt < nl ? nt : nl, group_count, &j);
    par_for(nt, group_total, &j);
    /* the receiving cells in index order, each with its slice */
    int ng = 0, run = 0;
    for (int c = 0; c < nr_cells; c++) {
      const int tc = h->tot[c];
      h->tot[c] = run;
      if (tc > 0) {
        g->cell[ng] = c;
        g->start[ng++] = run;
      }
      run += tc;
    }
    g->start[ng] = run;
    par_for(nt, group_position, &j);
    par_for(nt < nl ? nt : nl, group_scatter, &j);
    g->view.n = ng;
    g->view.cell = g->cell;
    g->view.start = g->start;
    g->view.source = g->source;
  }
}

void gpu_grav_host_free(struct gpu_grav_host *h) {
  free(h->offset);
  free(h->count);
  free(h->l2l_tmp);
  free(h->l2l_child);
  free(h->l2l_parent);
  free(h->level_start);
  free(h->leaf);
  free(h->cnt);
  free(h->tot);
  for (int k = 0; k < 2; k++) {
    free(h->groups[k].cell);
    free(h->groups[k].start);
    gpu_host_free(h->groups[k].source);
  }
  memset(h, 0, sizeof *h);
}

/* ------------------------------------------------------------------ serial */

void gpu_grav_tree_all(struct gpu_grav *gg, struct gpu_grav_host *h, struct parts *p,
                       const struct space *s, struct gravity_cell *gc,
                       const struct gravity_props *gp, int resident) {
  const struct cell *tops = s->cells;
  const int nr_top = s->nr_top;
  if (h->built_rebuild != s->nr_rebuilds || h->built_cells != s->cells || !h->tree.offset) {
    gpu_grav_tree_build(h, s);
    gpu_grav_set_tree(gg, &h->tree);
  }
  struct gravity_multipole *mp = gpu_grav_multipoles(gg, s->nr_cells);
  for (int i = 0; i < nr_top; i++) {
    gravity_up(p, tops + i, gc, gp);
    gpu_grav_pack_multipoles(mp, tops + i, gc);
  }
  struct gravity_gpu_rec rec;
  memset(&rec, 0, sizeof rec);
  gravity_gpu_record(&rec);
  /* the walks of gravity_tree_all, recorded */
  for (int i = 0; i < nr_top; i++) {
    gravity_interact_cells(p, tops + i, tops + i, gc, gp);
    for (int j = i + 1; j < nr_top; j++)
      if (gravity_top_pair_is_near(tops + i, tops + j, gp))
        gravity_interact_cells(p, tops + i, tops + j, gc, gp);
  }
  for (int i = 0; i < nr_top; i++) gravity_long_range(p, tops + i, tops, nr_top, gc, gp);
  gravity_gpu_record(NULL);
  gpu_grav_group(h, &rec, 1, s->nr_cells, 1);
  gpu_grav_run(gg, p, &h->groups[0].view, &h->groups[1].view, gp->G, gp->eps, gp->softening,
               gp->eps2_expansion, gp->order, resident, 0);
  gravity_gpu_rec_free(&rec);
}
