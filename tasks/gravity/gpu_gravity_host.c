/* Host side of self-gravity on the GPU (gpu_gravity.h): the cell tree as
 * index arrays, the multipoles packed for the upload, and the serial
 * sequence of a whole evaluation. */
#include "tasks/gravity/gpu_gravity.h"

#include <stdlib.h>
#include <string.h>

#include "src/cell.h"
#include "src/error.h"
#include "src/space.h"

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
    h->centre =
        error_realloc(h->centre, 3 * (size_t)h->cells_cap * sizeof(double), "GPU gravity tree");
    h->progeny =
        error_realloc(h->progeny, 8 * (size_t)h->cells_cap * sizeof(int), "GPU gravity tree");
    h->split = error_realloc(h->split, (size_t)h->cells_cap, "GPU gravity tree");
  }
  /* counts, split flags and progeny as the walks read them (index checked there) */
  gravity_walk_tree_arrays(s->cells, nc, h->progeny, h->count, h->split);
  for (int k = 0; k < nc; k++) {
    const struct cell *c = &s->cells[k];
    h->offset[k] = c->offset;
    for (int d = 0; d < 3; d++) h->centre[3 * k + d] = c->loc[d] + 0.5 * c->width[d];
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
  t->centre = h->centre;
  t->progeny = h->progeny;
  t->split = h->split;
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

void gpu_grav_host_free(struct gpu_grav_host *h) {
  free(h->offset);
  free(h->count);
  free(h->centre);
  free(h->progeny);
  free(h->split);
  free(h->lo_hi);
  free(h->top);
  free(h->top_skip);
  free(h->l2l_tmp);
  free(h->l2l_child);
  free(h->l2l_parent);
  free(h->level_start);
  free(h->leaf);
  memset(h, 0, sizeof *h);
}

void gpu_grav_up_cells(struct gpu_grav *gg, struct parts *p, const struct space *s,
                       struct gravity_cell *gc, const struct gravity_props *gp, int resident,
                       int nr_fill, struct gravity_back *back) {
  if (!gc) {
    gpu_grav_up(gg, p, gp->order, gp->h_factor, resident, NULL, NULL, NULL);
    return;
  }
  const struct gravity_multipole *mp;
  const double *a_min, *h_support;
  gpu_grav_up(gg, p, gp->order, gp->h_factor, resident, &mp, &a_min, &h_support);
  const struct gravity_back b = {mp, a_min, h_support};
  if (back) *back = b;
  if (nr_fill < 0 || nr_fill > s->nr_cells) nr_fill = s->nr_cells;
  for (int k = 0; k < nr_fill; k++) gravity_back_fill_cell(&b, k, gc);
}

void gpu_grav_walk_cells(struct gpu_grav *gg, struct gpu_grav_host *h, const struct space *s,
                         const struct gravity_props *gp, const unsigned char *skip) {
  const int nt = s->nr_top;
  if (nt > h->lo_hi_cap) {
    h->lo_hi_cap = nt;
    h->lo_hi = error_realloc(h->lo_hi, 6 * (size_t)nt * sizeof(double), "GPU gravity walks");
    h->top = error_realloc(h->top, (size_t)nt * sizeof(int), "GPU gravity walks");
    h->top_skip = error_realloc(h->top_skip, (size_t)nt, "GPU gravity walks");
  }
  /* the roots among the non-empty cells only: a grid of 64^3 cells, most
   * of them empty, made 6.9e10 roots */
  int ne = 0;
  for (int i = 0; i < nt; i++) {
    if (s->cells[i].count == 0 || (skip && skip[i] == 2)) continue;
    h->top[ne] = i;
    h->top_skip[ne] = skip ? skip[i] : 0;
    for (int d = 0; d < 3; d++) {
      h->lo_hi[6 * ne + d] = s->cells[i].bmin[d];
      h->lo_hi[6 * ne + 3 + d] = s->cells[i].bmax[d];
    }
    ne++;
  }
  gpu_grav_walk(gg, h->lo_hi, ne, gp->theta, gp->h_support, gp->G, gp->epsilon_fmm, gp->h_factor,
                gp->order, skip ? h->top_skip : NULL, h->top);
}

/* ------------------------------------------------------------------ serial */

void gpu_grav_tree_all(struct gpu_grav *gg, struct gpu_grav_host *h, struct gravity_gpu_rec *rec,
                       struct parts *p, const struct space *s, struct gravity_cell *gc,
                       const struct gravity_props *gp, int resident, int up_on_device,
                       int walk_on_device) {
  const struct cell *tops = s->cells;
  const int nr_top = s->nr_top;
  /* a first evaluation: the adaptive criterion's scale from the host's
   * estimate, uploaded with ga (gravity_tree_all does the same) */
  if (!resident) gravity_estimate(p, tops, nr_top, gc, gp, 1);
  if (h->built_rebuild != s->nr_rebuilds || h->built_cells != s->cells || !h->tree.offset) {
    gpu_grav_tree_build(h, s);
    gpu_grav_set_tree(gg, &h->tree);
  }
  if (up_on_device) {
    /* the host's copy only where the host walks */
    gpu_grav_up_cells(gg, p, s, walk_on_device ? NULL : gc, gp, resident, -1, NULL);
  } else {
    struct gravity_multipole *mp = gpu_grav_multipoles(gg, s->nr_cells);
    for (int i = 0; i < nr_top; i++) {
      gravity_up(p, tops + i, gc, gp);
      gpu_grav_pack_multipoles(mp, tops + i, gc);
    }
  }
  rec->part.n = rec->field.n = rec->part_sym.n = rec->field_sym.n = 0;
  if (up_on_device && walk_on_device) {
    gpu_grav_walk_cells(gg, h, s, gp, NULL);
    gpu_grav_run(gg, p, rec, 1, gp->G, gp->eps, gp->softening, gp->eps2_expansion, gp->order,
                 resident, 0);
    return;
  }
  gravity_gpu_record(rec);
  /* the walks of gravity_tree_all, recorded */
  for (int i = 0; i < nr_top; i++) {
    gravity_interact_cells(p, tops + i, tops + i, gc, gp);
    for (int j = i + 1; j < nr_top; j++)
      if (gravity_top_pair_is_near(tops + i, tops + j, gp))
        gravity_interact_cells(p, tops + i, tops + j, gc, gp);
  }
  for (int i = 0; i < nr_top; i++) gravity_long_range(p, tops + i, tops, nr_top, gc, gp);
  gravity_gpu_record(NULL);
  gpu_grav_run(gg, p, rec, 1, gp->G, gp->eps, gp->softening, gp->eps2_expansion, gp->order,
               resident, 0);
}
