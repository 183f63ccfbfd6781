/* The engine's side of the GPU runner (gpu_engine.h). */
#include "gpu_engine.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "engine_tasks.h"
#include "error.h"
#include "kernel.h"
#include "params.h"

/** The engine's GPU state. */
struct gpu_engine {
  struct gpu *gpu;        /**< the device */
  struct gpu_cells cells; /**< leaves and lists */
  int dev_valid;          /**< the device holds the current particles */
  int host_stale;         /**< the device has changed them since the last copy back */
  double t_bounds;        /**< host seconds updating cell bounds after drifts */
  long steps;             /**< FORCE phases run */
  double *tc_h_cap;       /**< cap on h per task cell */
  int nr_tc;              /**< its length */
};

/** Grow the per-leaf arrays to n. */
static void gpu_cells_reserve(struct gpu_cells *gc, int n) {
  if (n <= gc->cap) return;
  gc->cap = n + n / 2 + 16;
  gc->offset = error_realloc(gc->offset, gc->cap * sizeof(size_t), "GPU leaves");
  gc->count = error_realloc(gc->count, gc->cap * sizeof(int), "GPU leaves");
  gc->top = error_realloc(gc->top, gc->cap * sizeof(int), "GPU leaves");
  gc->h_cap = error_realloc(gc->h_cap, gc->cap * sizeof(double), "GPU leaves");
  gc->h_list_cap = error_realloc(gc->h_list_cap, gc->cap * sizeof(double), "GPU leaves");
  gc->ngb_start = error_realloc(gc->ngb_start, (gc->cap + 1) * sizeof(int), "GPU leaves");
}

/** Append one list entry. */
static void gpu_cells_add(struct gpu_cells *gc, int leaf, const double shift[3]) {
  if (gc->nr_ngb == gc->ngb_cap) {
    gc->ngb_cap = gc->ngb_cap ? 2 * gc->ngb_cap : 4096;
    gc->ngb_leaf = error_realloc(gc->ngb_leaf, gc->ngb_cap * sizeof(int), "GPU neighbour lists");
    gc->ngb_shift = error_realloc(gc->ngb_shift, 3 * (size_t)gc->ngb_cap * sizeof(double),
                                  "GPU neighbour lists");
  }
  gc->ngb_leaf[gc->nr_ngb] = leaf;
  for (int k = 0; k < 3; k++) gc->ngb_shift[3 * (size_t)gc->nr_ngb + k] = shift[k];
  gc->nr_ngb++;
}

/** Number the non-empty leaves below c. */
static void gpu_cells_collect(struct gpu_cells *gc, const struct cell *c, int top) {
  if (c->count == 0) return;
  if (c->split) {
    for (int k = 0; k < 8; k++)
      if (c->progeny[k]) gpu_cells_collect(gc, c->progeny[k], top);
    return;
  }
  gpu_cells_reserve(gc, gc->n + 1);
  gc->leaf_of_cell[c->index] = gc->n;
  gc->offset[gc->n] = c->offset;
  gc->count[gc->n] = (int)c->count;
  gc->top[gc->n] = top;
  gc->n++;
}

/** Add the leaves below node that leaf l (cell cl) can reach at shift. */
static void gpu_cells_walk(struct gpu_cells *gc, const struct cell *cl, const struct cell *node,
                           const double shift[3], double growth) {
  if (node->count == 0) return;
  const double hm = cl->h_max > node->h_max ? cl->h_max : node->h_max;
  const double R = growth * kernel_gamma * hm + cl->dx_max + node->dx_max;
  /* widened as the CPU loops' pruning (iact_loop.h): never drop a pair the
   * particle test keeps */
  double scale = 0.0;
  for (int k = 0; k < 3; k++)
    scale += fabs(cl->loc[k]) + cl->width[k] + fabs(node->loc[k]) + node->width[k] + fabs(shift[k]);
  const double Rs = R * (1.0 + 1e-10) + 1e-13 * scale;
  if (cell_bbox_dist2(cl, node, shift) > Rs * Rs) return;
  if (node->split) {
    for (int k = 0; k < 8; k++)
      if (node->progeny[k]) gpu_cells_walk(gc, cl, node->progeny[k], shift, growth);
    return;
  }
  gpu_cells_add(gc, gc->leaf_of_cell[node->index], shift);
}

/** Fill the neighbour lists of the leaves below c (ct: its task cell's
 *  neighbours, numbers in tcells). */
static void gpu_cells_lists(struct gpu_cells *gc, struct cell *const *tcells, const struct cell *c,
                            const struct engine_cell_tasks *ct, double growth) {
  if (c->count == 0) return;
  if (c->split) {
    for (int k = 0; k < 8; k++)
      if (c->progeny[k]) gpu_cells_lists(gc, tcells, c->progeny[k], ct, growth);
    return;
  }
  const int l = gc->leaf_of_cell[c->index];
  gc->ngb_start[l] = gc->nr_ngb;
  gc->h_list_cap[l] = growth * c->h_max;
  for (int k = 0; k < ct->nr_ngb; k++)
    gpu_cells_walk(gc, c, tcells[ct->ngb[k]], ct->ngb_shift[k], growth);
}

void gpu_cells_build(struct gpu_cells *gc, const struct space *s, struct cell *const *tcells,
                     int nr, const struct engine_cell_tasks *ct, const double *tc_h_cap,
                     double growth) {
  if (s->nr_cells > gc->cells_cap) {
    gc->cells_cap = s->nr_cells + s->nr_cells / 2;
    gc->leaf_of_cell = error_realloc(gc->leaf_of_cell, gc->cells_cap * sizeof(int), "GPU leaves");
  }
  for (int k = 0; k < s->nr_cells; k++) gc->leaf_of_cell[k] = -1;
  gc->n = 0;
  gc->nr_ngb = 0;
  for (int t = 0; t < nr; t++) gpu_cells_collect(gc, tcells[t], t);
  for (int t = 0; t < nr; t++) gpu_cells_lists(gc, tcells, tcells[t], &ct[t], growth);
  gc->ngb_start[gc->n] = gc->nr_ngb;
  for (int l = 0; l < gc->n; l++) gc->h_cap[l] = tc_h_cap[gc->top[l]];
  gc->growth = growth;
}

void gpu_cells_free(struct gpu_cells *gc) {
  free(gc->offset);
  free(gc->count);
  free(gc->top);
  free(gc->h_cap);
  free(gc->h_list_cap);
  free(gc->ngb_start);
  free(gc->ngb_leaf);
  free(gc->ngb_shift);
  free(gc->leaf_of_cell);
  memset(gc, 0, sizeof *gc);
}

int gpu_cells_force(struct gpu *g, struct gpu_cells *gc, struct parts *p, struct space *s,
                    struct cell *const *tcells, int nr, const struct engine_cell_tasks *ct,
                    const double *tc_h_cap, const struct hydro_props *hp,
                    const struct material_table *mats, double dt_kick, int resident,
                    double *tc_dt_min) {
  /* lists a quarter wider than the current h_max, widened when h outgrows them */
  double growth = gc->growth > 1.25 ? 0.9 * gc->growth : 1.25;
  if (growth < 1.25) growth = 1.25;
  struct gpu_force_out out;
  double *leaf_dt = NULL;
  for (int attempt = 0;; attempt++) {
    const double w0 = error_walltime();
    gpu_cells_build(gc, s, tcells, nr, ct, tc_h_cap, growth);
    gc->t_build += error_walltime() - w0;
    leaf_dt = error_realloc(leaf_dt, (gc->n + 1) * sizeof(double), "GPU leaf time steps");
    const struct gpu_leaves lv = {gc->n,        gc->offset,     gc->count,
                                  gc->h_cap,    gc->h_list_cap, gc->ngb_start,
                                  gc->ngb_leaf, gc->ngb_shift,  gc->nr_ngb};
    gpu_force_phase(g, p, &lv, hp, mats, dt_kick, leaf_dt, resident, &out);
    if (!out.overflow) break;
    if (attempt > 30)
      error_bug("GPU neighbour lists did not cover the smoothing lengths after %d widenings",
                attempt);
    for (int c = 0; c < s->nr_top; c++) cell_update_bounds(p, &s->cells[c]);
    growth *= 1.5;
    error_log(2, "GPU: smoothing lengths outgrew the neighbour lists; widening them to %.2f h_max",
              growth);
  }
  for (int t = 0; t < nr; t++) tc_dt_min[t] = 1e300;
  for (int l = 0; l < gc->n; l++)
    if (leaf_dt[l] < tc_dt_min[gc->top[l]]) tc_dt_min[gc->top[l]] = leaf_dt[l];
  free(leaf_dt);
  /* h changed: the CPU's pruning and the rebuild test read the cells' bounds
   * (resident particles: the next drift brings h back) */
  if (!resident)
    for (int c = 0; c < s->nr_top; c++) cell_update_bounds(p, &s->cells[c]);
  return out.capped;
}

void gpu_engine_init(struct engine *e) {
  const char *policy = params_get_string(e->params, "Scheduler:gpu");
  if (strcmp(policy, "auto") && strcmp(policy, "all") && strcmp(policy, "off"))
    params_error(e->params, "Scheduler:gpu",
                 "expected auto, off or all, got '%s' (lists of task families are "
                 "not implemented yet)",
                 policy);
  const int required = e->opt.use_gpu == 2 || strcmp(policy, "all") == 0;
  if (e->opt.use_gpu == 0 || strcmp(policy, "off") == 0) {
    error_log(0, "GPU off (%s): every task runs on the CPU",
              e->opt.use_gpu == 0 ? "--no-gpu" : "Scheduler:gpu: off");
    return;
  }
  char why[256];
  struct gpu *g = gpu_init(why, sizeof why);
  if (g && !gpu_supports(e->mats, why, sizeof why)) {
    gpu_free(g);
    g = NULL;
  }
  if (!g) {
    if (required)
      error_exit("a GPU was required (%s) but cannot be used: %s",
                 e->opt.use_gpu == 2 ? "--gpu" : "Scheduler:gpu: all", why);
    error_log(0, "no GPU (%s): every task runs on the CPU", why);
    return;
  }
  struct gpu_engine *ge = error_calloc(1, sizeof *ge, "GPU state");
  ge->gpu = g;
  e->gpu = ge;
  error_log(0,
            "GPU %s: drift, density, ghost, force and kick2 of every cell run on it, the particles "
            "stay on it between steps",
            gpu_name(g));
}

void gpu_engine_force(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  if (e->nr_tcells > ge->nr_tc) {
    ge->tc_h_cap = error_realloc(ge->tc_h_cap, e->nr_tcells * sizeof(double), "GPU caps");
    ge->nr_tc = e->nr_tcells;
  }
  /* the caps of the CPU ghost (engine_runtask.c): a pair is found while
   * H_i + |dx_i| + |dx_j| stays below the reach of the task graph */
  const double H_limit = engine_H_limit(e);
  for (int t = 0; t < e->nr_tcells; t++) {
    double dx_max = 0.0;
    for (int k = 0; k < e->ct[t].nr_ngb; k++)
      if (e->tcells[e->ct[t].ngb[k]]->dx_max > dx_max) dx_max = e->tcells[e->ct[t].ngb[k]]->dx_max;
    ge->tc_h_cap[t] = (H_limit - 2.0 * dx_max) / kernel_gamma;
  }
  const double dt_kick = e->first_force ? 0.0 : 0.5 * e->dt;
  if (!ge->dev_valid) {
    gpu_upload_all(ge->gpu, &e->parts);
    ge->dev_valid = 1;
  }
  ge->host_stale = 1;
  if (gpu_cells_force(ge->gpu, &ge->cells, &e->parts, &e->space, e->tcells, e->nr_tcells, e->ct,
                      ge->tc_h_cap, &e->hp, e->mats, dt_kick, 1, e->cell_dt_min))
    e->need_rebuild = 1;
}

void gpu_engine_drift(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  if (!ge->dev_valid) {
    gpu_upload_all(ge->gpu, &e->parts);
    ge->dev_valid = 1;
  }
  gpu_drift(ge->gpu, &e->parts, 0.5 * e->dt, e->dt);
  ge->host_stale = 1;
  /* positions and h are back: the bounds the rebuild test and the lists read */
  const double w0 = error_walltime();
  for (int c = 0; c < e->space.nr_top; c++) cell_update_bounds(&e->parts, &e->space.cells[c]);
  ge->t_bounds += error_walltime() - w0;
  ge->steps++;
}

void gpu_engine_to_host(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  if (!ge || !ge->host_stale) return;
  gpu_download_all(ge->gpu, &e->parts);
  ge->host_stale = 0;
}

void gpu_engine_host_modified(struct engine *e) {
  if (e->gpu) e->gpu->dev_valid = 0;
}

void gpu_engine_print(const struct engine *e, FILE *f) {
  const struct gpu_engine *ge = e->gpu;
  if (!ge) return;
  gpu_print_timers(ge->gpu, f);
  if (ge->steps)
    fprintf(f, "GPU host side, ms per step: neighbour lists %.3f, cell bounds %.3f\n",
            1e3 * ge->cells.t_build / ge->steps, 1e3 * ge->t_bounds / ge->steps);
}

void gpu_engine_free(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  if (!ge) return;
  gpu_unpin(ge->gpu);
  gpu_free(ge->gpu);
  gpu_cells_free(&ge->cells);
  free(ge->tc_h_cap);
  free(ge);
  e->gpu = NULL;
}
