/* The engine's side of the GPU runner (gpu_engine.h). */
#include "src/gpu/gpu_engine.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "src/engine_tasks.h"
#include "src/error.h"
#include "src/gpu/gpu_policy.h"
#include "src/gpu/gpu_lists.h"
#include "tasks/hydro/kernel.h"
#include "src/materials/material.h"
#include "src/io/params.h"
#include "src/mpi/halo.h"
#include "src/mpi/ranks.h"
#include "src/runner.h"
#include "tasks/task_families.h"

/** Where the work of a FORCE phase runs (Scheduler:gpu, gpu_policy.h). */
enum gpu_engine_mode {
  GPU_MODE_SERIAL,  /**< all: gravity's CPU part, its device part, then the hydrodynamics */
  GPU_MODE_HYBRID,  /**< the walks on the CPU beside the GPU's hydrodynamics, then gravity's
                         device part, then the kick */
  GPU_MODE_CPU_GRAV /**< the whole of self-gravity on the CPU beside the GPU's hydrodynamics */
};

/** The engine's GPU state. */
struct gpu_engine {
  int mode;                 /**< enum gpu_engine_mode */
  struct gpu *gpu;          /**< the device */
  struct gpu_cells cells;   /**< leaves and lists */
  int dev_valid;            /**< the device holds the current particles */
  int host_stale;           /**< the device has changed them since the last copy back */
  int xh_fresh;             /**< the host's x, y, z and h are the device's (a drift copied them
                                 back, and no force phase has changed h since) */
  double t_bounds;          /**< host seconds updating cell bounds after drifts */
  long steps;               /**< FORCE phases run */
  double *tc_h_cap;         /**< cap on h per task cell */
  int nr_tc;                /**< its length */
  struct gravity_gpu *grav; /**< self-gravity's part (tasks/gravity, through the
                                 registry's gravity_gpu_* entry points), NULL: none */
  int up_on_device;         /**< Scheduler:gpu_multipoles: device (P2M, M2M on the GPU) */
  int walk_on_device;       /**< Scheduler:gpu_walks: device (the walks on the GPU too) */
  double t_grav_walk;       /**< host seconds of the gravity tasks (up, walks) */
  double t_ranks[4];        /**< several ranks, walks on the device: seconds in the copies'
                                 refresh, the device's upward pass and walks, the records'
                                 exchange, the host's walks with the records */
  double t_grav_gpu;        /**< seconds of the device part (copies included) */
  long grav_evals;          /**< gravity evaluations */
  double t_phase;           /**< host seconds of the FORCE phases */
  long phases;              /**< FORCE phases */
  double t_cpu_side;        /**< hybrid: seconds of the CPU's gravity tasks */
  double t_gpu_side;        /**< hybrid: seconds of the hydro thread until the kick */
  double t_waited;          /**< hybrid: seconds the kick waited for the CPU */
  long hybrid_phases;       /**< FORCE phases run hybrid (with CPU work beside) */
  int rebuild_on_device;    /**< Scheduler:gpu_rebuild: device */
  long rebuilds_device;     /**< rebuilds that reordered the resident particles there */
  long rebuilds_host;       /**< rebuilds with every field copied back and up again */
  unsigned char *reorder;   /**< [part_nr_fields]: the fields the host reorders then */
  struct halo_device halo;  /**< several MPI ranks: the copies' records from and to the device */
  double *remote;           /**< several MPI ranks: ga and pot of the walks with other ranks'
                                 records, computed on the host (gpu_engine_grav_ranks) */
  size_t nr_remote;         /**< particles it holds room for */
};

/* Rebuilds of resident particles.  The host sorts the cells from x, y, z
 * and h (downloaded first unless the drift just copied them back) and
 * reorders them and the fields that no device kernel writes (mass,
 * material, id: gpu_rebuild_keep).  The device reorders its copy of every
 * field (gpu_permute), and the other fields the host reads while the
 * particles live on the device (gpu_rebuild_after) come back in the new
 * order.  The host's other fields stay in the old order, stale, until a
 * full download replaces them (host_stale stays set). */
static const char *const gpu_rebuild_down[] = {"x", "y", "z", "h"};
#define GPU_REBUILD_NR_DOWN ((int)(sizeof gpu_rebuild_down / sizeof *gpu_rebuild_down))
static const char *const gpu_rebuild_keep[] = {"x", "y", "z", "h", "m", "mat", "id"};
#define GPU_REBUILD_NR_KEEP ((int)(sizeof gpu_rebuild_keep / sizeof *gpu_rebuild_keep))
static const char *const gpu_rebuild_after[] = {"gax", "gay", "gaz", "pot", "flags", "time_bin"};
#define GPU_REBUILD_NR_AFTER ((int)(sizeof gpu_rebuild_after / sizeof *gpu_rebuild_after))

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
  gc->leaf_cell = error_realloc(gc->leaf_cell, gc->cap * sizeof(struct cell *), "GPU leaves");
  gc->dx_allow = error_realloc(gc->dx_allow, gc->cap * sizeof(double), "GPU leaves");
  gc->leaf_node = error_realloc(gc->leaf_node, gc->cap * sizeof(int), "GPU leaves");
}

/** 1 if the lists stop at c: a leaf of the tree, or a cell of at most
 *  leaf_size particles (Scheduler:gpu_leaf_size). */
static int gpu_cells_is_leaf(const struct gpu_cells *gc, const struct cell *c) {
  return !c->split || (size_t)gc->leaf_size >= c->count;
}

/** The bounds of c as the acceptance test reads them. */
static void gpu_cells_box(struct gpu_list_box *b, const struct cell *c) {
  for (int k = 0; k < 3; k++) {
    b->bmin[k] = c->bmin[k];
    b->bmax[k] = c->bmax[k];
    b->loc[k] = c->loc[k];
    b->width[k] = c->width[k];
  }
  b->h_max = c->h_max;
  b->dx_max = c->dx_max;
}

/** Number the non-empty leaves below c. */
static void gpu_cells_collect(struct gpu_cells *gc, const struct cell *c, int top) {
  if (c->count == 0) return;
  if (!gpu_cells_is_leaf(gc, c)) {
    for (int k = 0; k < 8; k++)
      if (c->progeny[k]) gpu_cells_collect(gc, c->progeny[k], top);
    return;
  }
  gpu_cells_reserve(gc, gc->n + 1);
  gc->leaf_of_cell[c->index] = gc->n;
  gc->offset[gc->n] = c->offset;
  gc->count[gc->n] = (int)c->count;
  gc->top[gc->n] = top;
  gc->leaf_cell[gc->n] = c;
  gc->n++;
}

/** One worker of the list build: the task cells [t0, t1), whose leaves are
 *  the contiguous range [l0, l1), and the entries it found. */
struct gpu_cells_job {
  struct gpu_cells *gc;               /**< leaves (read only here) */
  struct cell *const *tcells;         /**< the task cells */
  const struct engine_cell_tasks *ct; /**< their neighbours */
  double growth;                      /**< reach factor */
  int t0, t1, l0, l1;                 /**< task cells and leaves of this worker */
  int n, cap;                         /**< entries found and allocated */
  int *li, *lj;                       /**< leaf pairs: lj is a neighbour of li */
  double *shift;                      /**< 3 per entry */
  int *count;                         /**< entries per leaf of [l0, l1) */
  int *leaf;                          /**< the entries sorted by li: neighbouring leaf */
  double *sshift;                     /**< and its shift */
};

/** Record that leaf lj (at shift) is a neighbour of leaf li. */
static void gpu_cells_job_add(struct gpu_cells_job *jb, int li, int lj, const double shift[3]) {
  if (jb->n == jb->cap) {
    jb->cap = jb->cap ? 2 * jb->cap : 4096;
    jb->li = error_realloc(jb->li, jb->cap * sizeof(int), "GPU neighbour lists");
    jb->lj = error_realloc(jb->lj, jb->cap * sizeof(int), "GPU neighbour lists");
    jb->shift =
        error_realloc(jb->shift, 3 * (size_t)jb->cap * sizeof(double), "GPU neighbour lists");
  }
  jb->li[jb->n] = li;
  jb->lj[jb->n] = lj;
  for (int k = 0; k < 3; k++) jb->shift[3 * (size_t)jb->n + k] = shift[k];
  jb->n++;
}

/** Dual walk of the trees below ci and cj (cj at shift): every pair of
 *  list leaves that gpu_list_accept keeps, pruning whole sub-trees on both
 *  sides (internal pairs with the loosened bound: the pairs kept are exactly
 *  the leaf pairs that pass the exact test, as on the device). */
static void gpu_cells_walk(struct gpu_cells_job *jb, const struct cell *ci, const struct cell *cj,
                           const double shift[3]) {
  if (ci->count == 0 || cj->count == 0) return;
  const struct gpu_cells *gc = jb->gc;
  const int li = gpu_cells_is_leaf(gc, ci), lj = gpu_cells_is_leaf(gc, cj);
  if (!gpu_list_accept(&gc->box[ci->index], &gc->box[cj->index], shift, jb->growth, !(li && lj)))
    return;
  if (!li && (lj || ci->count >= cj->count)) {
    for (int k = 0; k < 8; k++)
      if (ci->progeny[k]) gpu_cells_walk(jb, ci->progeny[k], cj, shift);
  } else if (!lj) {
    for (int k = 0; k < 8; k++)
      if (cj->progeny[k]) gpu_cells_walk(jb, ci, cj->progeny[k], shift);
  } else {
    gpu_cells_job_add(jb, gc->leaf_of_cell[ci->index], gc->leaf_of_cell[cj->index], shift);
  }
}

/** Set h_list_cap of the leaves below c. */
static void gpu_cells_caps(struct gpu_cells *gc, const struct cell *c, double growth) {
  if (c->count == 0) return;
  if (!gpu_cells_is_leaf(gc, c)) {
    for (int k = 0; k < 8; k++)
      if (c->progeny[k]) gpu_cells_caps(gc, c->progeny[k], growth);
    return;
  }
  const int l = gc->leaf_of_cell[c->index];
  gc->h_list_cap[l] = growth * c->h_max;
  gc->dx_allow[l] = c->dx_max + GPU_LIST_SLACK * kernel_gamma * c->h_max;
}

/** Thread body: walk the task cells of the job, then sort its entries by
 *  leaf (counting sort over its leaf range). */
static void *gpu_cells_job_run(void *arg) {
  struct gpu_cells_job *jb = arg;
  jb->n = 0;
  for (int t = jb->t0; t < jb->t1; t++) {
    const struct engine_cell_tasks *ct = &jb->ct[t];
    gpu_cells_caps(jb->gc, jb->tcells[t], jb->growth);
    for (int k = 0; k < ct->nr_ngb; k++)
      gpu_cells_walk(jb, jb->tcells[t], jb->tcells[ct->ngb[k]], ct->ngb_shift[k]);
  }
  const int nl = jb->l1 - jb->l0;
  jb->count = error_realloc(jb->count, (nl + 1) * sizeof(int), "GPU neighbour lists");
  jb->leaf = error_realloc(jb->leaf, (jb->n + 1) * sizeof(int), "GPU neighbour lists");
  jb->sshift =
      error_realloc(jb->sshift, 3 * ((size_t)jb->n + 1) * sizeof(double), "GPU neighbour lists");
  int *pos = error_calloc(nl + 1, sizeof(int), "GPU neighbour lists");
  for (int e = 0; e < jb->n; e++) pos[jb->li[e] - jb->l0 + 1]++;
  for (int l = 0; l < nl; l++) {
    jb->count[l] = pos[l + 1];
    pos[l + 1] += pos[l];
  }
  for (int e = 0; e < jb->n; e++) {
    const int q = pos[jb->li[e] - jb->l0]++;
    jb->leaf[q] = jb->lj[e];
    for (int k = 0; k < 3; k++) jb->sshift[3 * (size_t)q + k] = jb->shift[3 * (size_t)e + k];
  }
  free(pos);
  return NULL;
}

/** Free the buffers of a job. */
static void gpu_cells_job_free(struct gpu_cells_job *jb) {
  free(jb->li);
  free(jb->lj);
  free(jb->shift);
  free(jb->count);
  free(jb->leaf);
  free(jb->sshift);
}

void gpu_cells_build(struct gpu_cells *gc, const struct space *s, struct cell *const *tcells,
                     int nr, const struct engine_cell_tasks *ct, const double *tc_h_cap,
                     double growth, int nr_threads) {
  if (s->nr_cells > gc->cells_cap) {
    gc->cells_cap = s->nr_cells + s->nr_cells / 2;
    gc->leaf_of_cell = error_realloc(gc->leaf_of_cell, gc->cells_cap * sizeof(int), "GPU leaves");
  }
  for (int k = 0; k < s->nr_cells; k++) gc->leaf_of_cell[k] = -1;
  /* the bounds of every cell as the acceptance test reads them */
  if (s->nr_cells > gc->box_cap) {
    gc->box_cap = gc->cells_cap;
    gc->box = error_realloc(gc->box, gc->box_cap * sizeof(struct gpu_list_box), "GPU leaves");
  }
  for (int k = 0; k < s->nr_cells; k++) gpu_cells_box(&gc->box[k], &s->cells[k]);
  gc->n = 0;
  int *first_leaf = error_malloc((nr + 1) * sizeof(int), "GPU leaves");
  for (int t = 0; t < nr; t++) {
    first_leaf[t] = gc->n;
    gpu_cells_collect(gc, tcells[t], t);
  }
  first_leaf[nr] = gc->n;
  gpu_cells_reserve(gc, gc->n + 1);

  /* workers over contiguous ranges of task cells, so that each one's leaves
   * are contiguous too and the lists join by concatenation */
  /* a thread per 4096 leaves at most: starting threads costs more than a small walk */
  int nt = nr_threads < 1 ? 1 : nr_threads;
  if (nt > 1 + gc->n / 4096) nt = 1 + gc->n / 4096;
  if (nt > nr) nt = nr > 0 ? nr : 1;
  if (nt > gc->nr_jobs) {
    /* the jobs and their buffers are kept between calls */
    gc->jobs = error_realloc(gc->jobs, nt * sizeof(struct gpu_cells_job), "GPU list jobs");
    memset(gc->jobs + gc->nr_jobs, 0, (nt - gc->nr_jobs) * sizeof(struct gpu_cells_job));
    gc->nr_jobs = nt;
  }
  struct gpu_cells_job *jobs = gc->jobs;
  pthread_t tid[256];
  if (nt > 256) nt = 256;
  for (int w = 0; w < nt; w++) {
    struct gpu_cells_job *jb = &jobs[w];
    jb->gc = gc;
    jb->tcells = tcells;
    jb->ct = ct;
    jb->growth = growth;
    /* split by leaves, a proxy for the work */
    jb->t0 = w == 0 ? 0 : jobs[w - 1].t1;
    const long target = (long)gc->n * (w + 1) / nt;
    int t = jb->t0;
    while (t < nr && (w == nt - 1 || first_leaf[t] < target)) t++;
    jb->t1 = t;
    jb->l0 = first_leaf[jb->t0];
    jb->l1 = first_leaf[jb->t1];
    if (w > 0 && pthread_create(&tid[w], NULL, gpu_cells_job_run, jb))
      error_exit("cannot start a thread to build the GPU neighbour lists");
  }
  gpu_cells_job_run(&jobs[0]);
  for (int w = 1; w < nt; w++) pthread_join(tid[w], NULL);

  int total = 0;
  for (int w = 0; w < nt; w++) total += jobs[w].n;
  if (total > gc->ngb_cap) {
    gc->ngb_cap = total + total / 4 + 1024;
    gc->ngb_leaf = error_realloc(gc->ngb_leaf, gc->ngb_cap * sizeof(int), "GPU neighbour lists");
    gc->ngb_shift = error_realloc(gc->ngb_shift, 3 * (size_t)gc->ngb_cap * sizeof(double),
                                  "GPU neighbour lists");
  }
  int at = 0;
  for (int w = 0; w < nt; w++) {
    const struct gpu_cells_job *jb = &jobs[w];
    for (int l = jb->l0; l < jb->l1; l++) {
      gc->ngb_start[l] = at;
      at += jb->count[l - jb->l0];
    }
    memcpy(gc->ngb_leaf + (at - jb->n), jb->leaf, jb->n * sizeof(int));
    memcpy(gc->ngb_shift + 3 * (size_t)(at - jb->n), jb->sshift,
           3 * (size_t)jb->n * sizeof(double));
  }
  gc->nr_ngb = total;
  gc->ngb_start[gc->n] = total;
  for (int l = 0; l < gc->n; l++) gc->h_cap[l] = tc_h_cap[gc->top[l]];
  gc->growth = growth;
  free(first_leaf);
}

/** The non-empty cells below c down to the list leaves (*nodes) and the
 *  list leaves among them (*leaves): what gpu_cells_flatten writes. */
static void gpu_cells_count(const struct gpu_cells *gc, const struct cell *c, int *nodes,
                            int *leaves) {
  if (c->count == 0) return;
  ++*nodes;
  if (gpu_cells_is_leaf(gc, c)) {
    ++*leaves;
    return;
  }
  for (int k = 0; k < 8; k++)
    if (c->progeny[k]) gpu_cells_count(gc, c->progeny[k], nodes, leaves);
}

/** Number the list leaves below c (task cell top) from *l as
 *  gpu_cells_collect, set their caps as gpu_cells_caps, and write the
 *  non-empty cells down to the list leaves to node[] depth first from *q.
 *  The leaf arrays must hold the leaves already (gpu_cells_reserve). */
static void gpu_cells_flatten(struct gpu_cells *gc, struct gpu_list_node *node,
                              const struct cell *c, int top, double growth, int *q_next,
                              int *l_next) {
  if (c->count == 0) return;
  const int q = (*q_next)++;
  gpu_cells_box(&node[q].box, c);
  if (gpu_cells_is_leaf(gc, c)) {
    const int l = (*l_next)++;
    gc->leaf_of_cell[c->index] = l;
    gc->offset[l] = c->offset;
    gc->count[l] = (int)c->count;
    gc->top[l] = top;
    gc->leaf_cell[l] = c;
    gc->leaf_node[l] = q;
    gc->h_list_cap[l] = growth * c->h_max;
    gc->dx_allow[l] = c->dx_max + GPU_LIST_SLACK * kernel_gamma * c->h_max;
    node[q].leaf = l;
  } else {
    node[q].leaf = -1;
    for (int k = 0; k < 8; k++)
      if (c->progeny[k]) gpu_cells_flatten(gc, node, c->progeny[k], top, growth, q_next, l_next);
  }
  node[q].skip = *q_next;
}

/** One thread of the flattening: the task cells [t0, t1), counted (pass 0:
 *  nodes and leaves of each, in tc_nodes and tc_leaves) or written (pass
 *  1: from the first node and leaf of each, the prefix sums in gc->tc_node
 *  and tc_leaves). */
struct gpu_flatten_job {
  struct gpu_cells *gc;
  struct gpu_list_node *node;
  struct cell *const *tcells;
  int *tc_nodes, *tc_leaves;
  double growth;
  int t0, t1, pass;
};

static void *gpu_flatten_run(void *arg) {
  struct gpu_flatten_job *jb = arg;
  struct gpu_cells *gc = jb->gc;
  for (int t = jb->t0; t < jb->t1; t++) {
    if (jb->pass == 0) {
      jb->tc_nodes[t] = jb->tc_leaves[t] = 0;
      gpu_cells_count(gc, jb->tcells[t], &jb->tc_nodes[t], &jb->tc_leaves[t]);
    } else {
      int q = gc->tc_node[t], l = jb->tc_leaves[t];
      gpu_cells_flatten(gc, jb->node, jb->tcells[t], t, jb->growth, &q, &l);
    }
  }
  return NULL;
}

/** Write the cells below the task cells to node[] (gpu_cells_flatten), in
 *  the order of one thread, on up to nt threads: the nodes and leaves of
 *  each task cell are counted first, so each thread knows where its task
 *  cells' start; the threads take ranges of task cells of about equal
 *  particles (an impact puts most of them in a few). */
static void gpu_cells_flatten_all(struct gpu_cells *gc, struct gpu_list_node *node,
                                  struct cell *const *tcells, int nr, double growth, int nt) {
  size_t np = 0;
  for (int t = 0; t < nr; t++) np += tcells[t]->count;
  if (nt < 1 || np < (size_t)(gc->min_parallel > 0 ? gc->min_parallel : 50000)) nt = 1;
  if (nt > nr) nt = nr > 0 ? nr : 1;
  if (nt > 64) nt = 64;
  int *tc_nodes = error_malloc(2 * ((size_t)nr + 1) * sizeof(int), "GPU task cells");
  int *tc_leaves = tc_nodes + nr + 1;
  struct gpu_flatten_job jobs[64];
  pthread_t tid[64];
  size_t acc = 0;
  int t = 0;
  for (int w = 0; w < nt; w++) {
    jobs[w] = (struct gpu_flatten_job){gc, node, tcells, tc_nodes, tc_leaves, growth, t, t, 0};
    const size_t target = np * (size_t)(w + 1) / (size_t)nt;
    while (t < nr && (w == nt - 1 || acc < target)) acc += tcells[t++]->count;
    jobs[w].t1 = t;
  }
  for (int pass = 0; pass < 2; pass++) {
    for (int w = 0; w < nt; w++) jobs[w].pass = pass;
    for (int w = 1; w < nt; w++)
      if (pthread_create(&tid[w], NULL, gpu_flatten_run, &jobs[w]))
        error_exit("cannot start a thread to build the GPU neighbour lists");
    gpu_flatten_run(&jobs[0]);
    for (int w = 1; w < nt; w++) pthread_join(tid[w], NULL);
    if (pass == 0) {
      /* the first node and leaf of each task cell */
      int q = 0, l = 0;
      for (int k = 0; k < nr; k++) {
        const int dq = tc_nodes[k], dl = tc_leaves[k];
        gc->tc_node[k] = q;
        tc_leaves[k] = l;
        q += dq;
        l += dl;
      }
      gc->tc_node[nr] = gc->nr_nodes = q;
      gc->n = l;
      gpu_cells_reserve(gc, gc->n + 1);
    }
  }
  free(tc_nodes);
}

void gpu_cells_build_dev(struct gpu *g, struct gpu_cells *gc, const struct space *s,
                         struct cell *const *tcells, int nr, const struct engine_cell_tasks *ct,
                         const double *tc_h_cap, double growth) {
  if (!gc->dev) gc->dev = gpu_lists_new(g);
  if (s->nr_cells > gc->cells_cap) {
    gc->cells_cap = s->nr_cells + s->nr_cells / 2;
    gc->leaf_of_cell = error_realloc(gc->leaf_of_cell, gc->cells_cap * sizeof(int), "GPU leaves");
  }
  for (int k = 0; k < s->nr_cells; k++) gc->leaf_of_cell[k] = -1;
  if (nr + 1 > gc->tc_cap) {
    gc->tc_cap = nr + 1 + nr / 2;
    gc->tc_node = error_realloc(gc->tc_node, gc->tc_cap * sizeof(int), "GPU task cells");
    gc->tc_ngb_start = error_realloc(gc->tc_ngb_start, gc->tc_cap * sizeof(int), "GPU task cells");
  }
  /* the neighbours of the task cells, as one array */
  int nk = 0;
  for (int t = 0; t < nr; t++) nk += ct[t].nr_ngb;
  if (nk > gc->tc_ngb_cap) {
    gc->tc_ngb_cap = nk + nk / 2;
    gc->tc_ngb = error_realloc(gc->tc_ngb, gc->tc_ngb_cap * sizeof(int), "GPU task cells");
    gc->tc_ngb_shift = error_realloc(gc->tc_ngb_shift, 3 * (size_t)gc->tc_ngb_cap * sizeof(double),
                                     "GPU task cells");
  }
  nk = 0;
  for (int t = 0; t < nr; t++) {
    gc->tc_ngb_start[t] = nk;
    for (int k = 0; k < ct[t].nr_ngb; k++, nk++) {
      gc->tc_ngb[nk] = ct[t].ngb[k];
      for (int d = 0; d < 3; d++) gc->tc_ngb_shift[3 * (size_t)nk + d] = ct[t].ngb_shift[k][d];
    }
  }
  gc->tc_ngb_start[nr] = nk;
  /* the cells below the task cells, written straight to the pinned staging */
  struct gpu_list_node *node = gpu_lists_nodes(gc->dev, s->nr_cells);
  gpu_cells_flatten_all(gc, node, tcells, nr, growth, gc->nr_threads);
  const struct gpu_list_input in = {.nr_leaves = gc->n,
                                    .leaf_node = gc->leaf_node,
                                    .leaf_tc = gc->top,
                                    .nr_tc = nr,
                                    .tc_node = gc->tc_node,
                                    .tc_ngb_start = gc->tc_ngb_start,
                                    .tc_ngb = gc->tc_ngb,
                                    .tc_ngb_shift = gc->tc_ngb_shift,
                                    .nr_nodes = gc->nr_nodes,
                                    .growth = growth};
  gc->nr_ngb = (int)gpu_lists_build(gc->dev, &in);
  for (int l = 0; l < gc->n; l++) gc->h_cap[l] = tc_h_cap[gc->top[l]];
  gc->growth = growth;
}

void gpu_cells_free(struct gpu_cells *gc) {
  gpu_lists_free(gc->dev);
  free(gc->box);
  free(gc->leaf_node);
  free(gc->tc_node);
  free(gc->tc_ngb_start);
  free(gc->tc_ngb);
  free(gc->tc_ngb_shift);
  for (int w = 0; w < gc->nr_jobs; w++) gpu_cells_job_free(&gc->jobs[w]);
  free(gc->jobs);
  free(gc->offset);
  free(gc->count);
  free(gc->top);
  free(gc->h_cap);
  free(gc->h_list_cap);
  free(gc->ngb_start);
  free(gc->ngb_leaf);
  free(gc->ngb_shift);
  free(gc->leaf_of_cell);
  free(gc->leaf_cell);
  free(gc->dx_allow);
  memset(gc, 0, sizeof *gc);
}

/** 1 if the lists built last still hold every pair: same cells, no leaf
 *  drifted past its allowance, no leaf's h beyond the lists' cap (h grown
 *  during the h iteration is caught on the device: overflow); and they are
 *  no wider than GPU_LIST_GROWTH: lists widened for an h iteration that
 *  outgrew them are built again narrower at the next phase (a build costs
 *  less than the candidates that wide lists add to every leaf kernel). */
static int gpu_cells_valid(const struct gpu_cells *gc, const struct space *s,
                           struct cell *const *tcells, int nr) {
  if (gc->n == 0 || gc->built_rebuild != s->nr_rebuilds || gc->built_tcells != tcells ||
      gc->built_nr != nr || gc->growth > GPU_LIST_GROWTH)
    return 0;
  for (int l = 0; l < gc->n; l++)
    if (gc->leaf_cell[l]->dx_max > gc->dx_allow[l] || gc->leaf_cell[l]->h_max > gc->h_list_cap[l])
      return 0;
  return 1;
}

int gpu_cells_force(struct gpu *g, struct gpu_cells *gc, struct parts *p, struct space *s,
                    struct cell *const *tcells, int nr, const struct engine_cell_tasks *ct,
                    const double *tc_h_cap, const struct hydro_props *hp,
                    const struct material_table *mats, const struct gpu_damage *dmg,
                    const struct gpu_gravity *grav, double dt_kick, int resident, double *tc_dt_min,
                    struct timeline_sums *tc_sums) {
  /* lists a quarter wider than the current h_max, widened when h outgrows
   * them; after a widening the next builds come back to that margin in a
   * few phases (a factor 0.85 each: 1.875 h_max, 1.59, 1.35, 1.25) */
  double growth = gc->growth > GPU_LIST_GROWTH ? 0.85 * gc->growth : GPU_LIST_GROWTH;
  if (growth < GPU_LIST_GROWTH) growth = GPU_LIST_GROWTH;
  struct gpu_force_out out;
  double *leaf_dt = NULL;
  for (int attempt = 0;; attempt++) {
    if (attempt > 0 || !gpu_cells_valid(gc, s, tcells, nr)) {
      const double w0 = error_walltime();
      if (gc->host_lists)
        gpu_cells_build(gc, s, tcells, nr, ct, tc_h_cap, growth, gc->nr_threads);
      else
        gpu_cells_build_dev(g, gc, s, tcells, nr, ct, tc_h_cap, growth);
      gc->t_build += error_walltime() - w0;
      gc->builds++;
      gc->built_rebuild = s->nr_rebuilds;
      gc->built_tcells = tcells;
      gc->built_nr = nr;
      /* lists from the h the last attempt reached; the sums from the h the
       * phase started with (with SPH:h_taylor the CPU's iteration may stop
       * short of a new sum where the repeat from the reached h would not) */
      if (attempt > 0) gpu_restore_h(g, p, resident);
    } else {
      /* same leaves and lists; only the cells' caps moved */
      for (int l = 0; l < gc->n; l++) gc->h_cap[l] = tc_h_cap[gc->top[l]];
    }
    leaf_dt = error_realloc(leaf_dt, 3 * (gc->n + 1) * sizeof(double), "GPU leaf time steps");
    const struct gpu_leaves lv = {
        gc->n,         gc->offset,   gc->count,     gc->h_cap,  gc->h_list_cap,
        gc->ngb_start, gc->ngb_leaf, gc->ngb_shift, gc->nr_ngb, gc->host_lists ? NULL : gc->dev};
    gpu_force_phase(g, p, &lv, hp, mats, dmg, grav, dt_kick, leaf_dt, resident, &out);
    gc->h_resummed += out.resummed;
    if (!out.overflow) break;
    if (attempt > 30)
      error_bug("GPU neighbour lists did not cover the smoothing lengths after %d widenings",
                attempt);
    for (int c = 0; c < s->nr_top; c++) cell_update_bounds(p, &s->cells[c]);
    growth *= 1.5;
    gc->widenings++;
    error_log(2, "GPU: smoothing lengths outgrew the neighbour lists; widening them to %.2f h_max",
              growth);
  }
  for (int t = 0; t < nr; t++) tc_dt_min[t] = 1e300;
  for (int l = 0; l < gc->n; l++)
    if (leaf_dt[l] < tc_dt_min[gc->top[l]]) tc_dt_min[gc->top[l]] = leaf_dt[l];
  if (tc_sums) {
    for (int t = 0; t < nr; t++) tc_sums[t] = (struct timeline_sums){INT64_MAX, 0};
    for (int l = 0; l < gc->n; l++) {
      int64_t ti_end, kicked;
      memcpy(&ti_end, &leaf_dt[gc->n + l], sizeof ti_end);
      memcpy(&kicked, &leaf_dt[2 * gc->n + l], sizeof kicked);
      struct timeline_sums *ts = &tc_sums[gc->top[l]];
      if (ti_end < ts->ti_end_min) ts->ti_end_min = ti_end;
      ts->active += kicked;
    }
  }
  free(leaf_dt);
  /* h changed: the CPU's pruning and the rebuild test read the cells' bounds
   * (resident particles: the next drift brings h back) */
  if (!resident)
    for (int c = 0; c < s->nr_top; c++) cell_update_bounds(p, &s->cells[c]);
  return out.capped;
}

/** The chains of the registry (tasks/task_families.h): predicate and family. */
struct gpu_engine_chain {
  int (*active)(const struct engine *); /**< 1: the run has the family's tasks */
  enum task_family family;              /**< the family */
};
#define GPU_ENGINE_CHAIN_chain(active) \
  {                                    \
    active, GPU_ENGINE_CHAIN_FAMILY_
#define GPU_ENGINE_CHAIN_FAMILY_(family) \
  task_family_##family                   \
  }                                      \
  ,
#define GPU_ENGINE_CHAIN_cell(family)
#define GPU_ENGINE_CHAIN_self(family)
#define GPU_ENGINE_CHAIN_pair(family)
#define GPU_ENGINE_CHAIN_ROW_(family, shape, type, subtype, cpu) GPU_ENGINE_CHAIN_##shape(family)
static const struct gpu_engine_chain gpu_engine_chains[] = {
    TASK_FAMILY_TASKS(GPU_ENGINE_CHAIN_ROW_){NULL, task_family_count}};
#undef GPU_ENGINE_CHAIN_ROW_

/** The reason why the run's tasks cannot run on the GPU's hydrodynamic
 *  phase: a family of the registry without a GPU implementation (policy CPU)
 *  whose chain tasks the run has; NULL if there is none. */
static const char *gpu_engine_cpu_only(const struct engine *e) {
  static char why[160];
  for (int k = 0; gpu_engine_chains[k].active; k++) {
    const enum task_family f = gpu_engine_chains[k].family;
    if (!(TASK_FAMILIES_GPU & (1u << f)) && gpu_engine_chains[k].active(e)) {
      snprintf(why, sizeof why, "the task family %s has no GPU implementation",
               task_family_names[f]);
      return why;
    }
  }
  return NULL;
}

/** The fields the host does not hold (engine_drop_unused_fields: the solid
 *  state and the fracture fields of a run without stress, without damage,
 *  with the kick-drift-kick scheme) are not held on the device either. */
static void gpu_engine_absent(struct engine *e) {
  const struct parts *p = &e->parts;
  const char *names[PART_NR_FIELDS];
  int n = 0;
  for (int k = 0; k < part_nr_fields; k++)
    if (p->absent[k]) names[n++] = part_fields[k].name;
  if (n == 0) return;
  const int saved = gpu_set_absent(e->gpu->gpu, names, n);
  error_log(1,
            "GPU: the solid and damage fields are not held on the device (no stress, no "
            "damage, kick-drift-kick): %d bytes per particle less",
            saved);
}

/** Whether --no-gpu or Scheduler:gpu (pol) keeps every task off the GPU. */
static int gpu_engine_off(const struct engine *e, const struct gpu_policy *pol) {
  return e->opt.use_gpu == 0 || pol->kind == GPU_POLICY_OFF ||
         (pol->kind == GPU_POLICY_LIST && pol->families == 0);
}

void gpu_engine_near(const struct engine *e) {
  const struct gpu_policy pol = gpu_policy_read(e->params);
  if (gpu_engine_off(e, &pol)) return;
  char ids[16][RUNNER_BUS_ID_LEN];
  const int n = gpu_bus_ids(&ids[0][0], RUNNER_BUS_ID_LEN, 16);
  runner_near_devices((const char(*)[RUNNER_BUS_ID_LEN])ids, n);
}

void gpu_engine_init(struct engine *e) {
  const struct gpu_policy pol = gpu_policy_read(e->params);
  char asked[300];
  snprintf(asked, sizeof asked, "Scheduler:gpu: %s%s", pol.text,
           e->opt.use_gpu == 2 ? ", --gpu" : "");
  if (gpu_engine_off(e, &pol)) {
    error_log(0, "GPU off (%s): every task runs on the CPU",
              e->opt.use_gpu == 0 ? "--no-gpu" : asked);
    return;
  }
  /* a GPU asked for by name (--gpu, all, a list) must be there */
  const int required =
      e->opt.use_gpu == 2 || pol.kind == GPU_POLICY_ALL || pol.kind == GPU_POLICY_LIST;
  char why[256];
  /* the GPU runs the hydrodynamic phase as a whole (solids, damage, XSPH
   * and the continuity equation included) and self-gravity's interactions
   * (the walks stay on the CPU); the gravitational softening tied to h has
   * no GPU implementation yet (the GPU P2P uses one constant eps; the kick has the
   * criterion with eps_i = h_factor h_i), and a
   * gravity-only run none */
  const char *unsupported = !e->hp.enabled ? "hydrodynamics is off"
                            : e->gp.enabled && e->gp.h_factor > 0.0
                                ? "Gravity:softening_h_factor > 0 (softening tied to h) has no GPU "
                                  "implementation yet"
                            : e->nr_planes > 0
                                ? "Boundaries:planes (mirror ghosts) has no GPU implementation yet"
                                : gpu_engine_cpu_only(e);
  if (unsupported) {
    if (required) error_exit("a GPU was required (%s) but %s", asked, unsupported);
    error_log(0, "GPU not used (%s): every task runs on the CPU", unsupported);
    return;
  }
  /* every EOS (tables included), strength, damage and porosity model has
   * a GPU path: the shared inline functions */
  /* several MPI ranks on a node: each its own device, by the node-local rank */
  int local_rank, local_ranks;
  ranks_local(&local_rank, &local_ranks);
  struct gpu *g = gpu_init(local_rank, why, sizeof why);
  if (!g) {
    if (required) error_exit("a GPU was required (%s) but cannot be used: %s", asked, why);
    error_log(0, "no GPU (%s): every task runs on the CPU", why);
    return;
  }
  /* auto: the measured best, the hybrid (BENCHMARKS.md, "Hybrid"), or the
   * serial runner when gravity's walks run on the device (below) */
  int mode = GPU_MODE_HYBRID;
  if (pol.kind == GPU_POLICY_ALL)
    mode = GPU_MODE_SERIAL;
  else if (pol.kind == GPU_POLICY_LIST && !(pol.families & (1u << task_family_gravity)))
    mode = GPU_MODE_CPU_GRAV;
  /* exact summation has no GPU part: it runs on the CPU beside the hydrodynamics */
  if (e->gp.enabled && e->gp.direct) mode = GPU_MODE_CPU_GRAV;
  /* several MPI ranks: gravity's multipoles and walks on the CPU workers
   * (the walks read the other ranks' top-level records there), its
   * interactions on the GPU, before the GPU's hydrodynamics
   * (gpu_engine_grav_ranks), the exchanges on thread 0: the serial order */
  const int ranks = ranks_size() > 1 && !e->opt.one_rank;
  if (e->gp.enabled && ranks && mode == GPU_MODE_HYBRID) mode = GPU_MODE_SERIAL;
  if (!e->gp.enabled) mode = GPU_MODE_SERIAL; /* nothing to run beside the hydrodynamics */
  if (e->hp.wake_density)
    params_error(e->params, "TimeIntegration:limiter_wake",
                 "density runs on the CPU only yet (issue 20): run with --no-gpu (or "
                 "Scheduler:gpu: off), or with limiter_wake: force");
  struct gpu_engine *ge = error_calloc(1, sizeof *ge, "GPU state");
  ge->gpu = g;
  ge->mode = mode;
  e->gpu = ge;
  ge->cells.leaf_size = (int)params_get_int(e->params, "Scheduler:gpu_leaf_size");
  ge->cells.host_lists = params_get_enum(e->params, "Scheduler:gpu_lists") == 1;
  ge->up_on_device = params_get_enum(e->params, "Scheduler:gpu_multipoles") == 1;
  ge->rebuild_on_device = params_get_enum(e->params, "Scheduler:gpu_rebuild") == 0;
  gpu_engine_absent(e);
  ge->reorder = error_calloc((size_t)part_nr_fields, 1, "GPU rebuild fields");
  for (int k = 0; k < part_nr_fields; k++)
    for (int q = 0; q < GPU_REBUILD_NR_KEEP; q++)
      if (!strcmp(part_fields[k].name, gpu_rebuild_keep[q])) ge->reorder[k] = 1;
  ge->walk_on_device = params_get_enum(e->params, "Scheduler:gpu_walks") == 1;
  const int walks_given = params_given(e->params, "Scheduler:gpu_walks");
  const int up_given = params_given(e->params, "Scheduler:gpu_multipoles");
  /* the far-field reuse decides on the shortest M2L/M2P distance, which
   * the CPU's walks measure: there the walks stay on the CPU unless asked
   * for on the device (an error); so do they where the multipoles were
   * asked for on the host */
  const int reuse = e->gp.enabled && e->gp.reuse_steps > 0 && mode != GPU_MODE_CPU_GRAV;
  if (!walks_given && (reuse || (up_given && !ge->up_on_device))) ge->walk_on_device = 0;
  if (ge->walk_on_device && !ge->up_on_device) {
    if (up_given)
      error_exit(
          "%s: Scheduler:gpu_walks: device needs Scheduler:gpu_multipoles: device (the "
          "walks read the multipoles where they are computed)",
          params_filename(e->params));
    ge->up_on_device = 1;
  }
  /* several MPI ranks: the multipoles of walks on the CPU are the CPU's
   * (the copies for gravity reach the host before the walks' stages) */
  if (e->gp.enabled && ranks && !ge->walk_on_device && ge->up_on_device) {
    if (up_given)
      error_exit(
          "%s: Scheduler:gpu_multipoles: device needs Scheduler:gpu_walks: device on %d MPI "
          "ranks (the walks on the CPU read the multipoles of the CPU's stages)",
          params_filename(e->params), ranks_size());
    ge->up_on_device = 0;
  }
  if (ge->walk_on_device && reuse)
    error_exit(
        "%s: Scheduler:gpu_walks: device cannot be combined with Gravity:reuse_steps > 0 "
        "yet (the reuse's tolerance is measured by the CPU's walks)",
        params_filename(e->params));
  /* auto with gravity's walks on the device: the workers have nothing to
   * run beside the GPU, and the hybrid's order measured 0.98 of the serial
   * one's speed (BENCHMARKS.md, "Hybrid against GPU-only"): auto takes the
   * serial runner, as Scheduler:gpu: all does */
  if (pol.kind == GPU_POLICY_AUTO && mode == GPU_MODE_HYBRID && ge->walk_on_device) {
    mode = GPU_MODE_SERIAL;
    ge->mode = mode;
  }
  /* the GPU runs the whole FORCE phase and no CPU worker takes a task of
   * it: the task cells only index the device's neighbour lists, and cells
   * of 1,000 particles made the graph of 1.1e7 particles 1.9M tasks, 0.48 s
   * of a 0.70-s rebuild (BENCHMARKS.md, "The reference impact at 1.1e7 on
   * one GPU"): larger ones unless the user chose (with time bins the task
   * cells are also the unit of activity: they stay) */
  if (mode == GPU_MODE_SERIAL && (!e->gp.enabled || ge->walk_on_device) && !e->individual &&
      !params_given(e->params, "Scheduler:cell_task_size")) {
    e->cell_task_size = GPU_CELL_TASK_SIZE;
    error_log(1,
              "GPU: task cells of at most %d particles (the GPU runs the whole phase; "
              "Scheduler:cell_task_size sets it)",
              e->cell_task_size);
  }
  if (e->gp.enabled && mode != GPU_MODE_CPU_GRAV) {
    ge->grav = gravity_gpu_new(g, ge->up_on_device, ge->walk_on_device,
                               params_get_bool(e->params, "Gravity:gpu_reproducible"));
  }
  /* the host thread driving the GPU then sleeps while it waits: the CPU
   * workers have every core */
  if (mode != GPU_MODE_SERIAL && !gpu_set_blocking_sync(g))
    error_log(1, "GPU: the driver refused blocking waits; the thread driving the GPU spins");
  /* the flaw thresholds never change during a run: on the device once */
  if (e->damage) gpu_set_flaws(g, e->flaw_eps, (size_t)e->nr_flaws);
  const char *grav = "";
  if (e->gp.enabled && mode == GPU_MODE_SERIAL)
    grav = ranks ? "; self-gravity: multipoles and walks on the CPU workers, M2L, L2L, L2P, M2P "
                   "and P2P on the GPU (several MPI ranks, Scheduler:gpu_walks: host: before the "
                   "GPU's hydrodynamics, the ranks' exchanges on thread 0; the far field of the "
                   "other ranks' records on the CPU, added to ga)"
                 : "; self-gravity: multipoles and walks on the CPU, M2L, L2L, L2P, M2P and P2P "
                   "on the GPU (one after the other: the CPU part, the GPU part, then the "
                   "hydrodynamics)";
  else if (mode == GPU_MODE_HYBRID)
    grav =
        "; self-gravity: multipoles and walks on the CPU, M2L, L2L, L2P, M2P and P2P on the GPU "
        "(hybrid: the CPU workers walk while the GPU computes the hydrodynamics; then gravity's "
        "GPU part and the kick)";
  else if (mode == GPU_MODE_CPU_GRAV)
    grav = ranks ? "; self-gravity entirely on the CPU workers (several MPI ranks: before the "
                   "GPU's hydrodynamics, the ranks' exchanges on thread 0); ga goes up for the "
                   "kick"
           : e->gp.direct
               ? "; self-gravity (Gravity:direct, no GPU implementation) on the CPU "
                 "workers while the GPU computes the hydrodynamics; ga goes up for the kick"
               : "; self-gravity entirely on the CPU workers (multipoles, walks, M2L, "
                 "P2P, L2P) while the GPU computes the hydrodynamics; ga goes up for the "
                 "kick";
  if (e->gp.enabled && mode != GPU_MODE_CPU_GRAV && !e->gp.direct && ge->up_on_device)
    grav = ge->walk_on_device && ranks
               ? "; self-gravity on the GPU (Scheduler:gpu_walks: device: multipoles, walks, "
                 "M2L, L2L, L2P, M2P and P2P; several MPI ranks: the walks with the other ranks' "
                 "records on the CPU workers, added to ga), before the hydrodynamics"
           : ge->walk_on_device
               ? "; self-gravity entirely on the GPU (Scheduler:gpu_walks: device: multipoles, "
                 "walks, M2L, L2L, L2P, M2P and P2P), before the hydrodynamics"
           : mode == GPU_MODE_SERIAL
               ? "; self-gravity: multipoles on the GPU (Scheduler:gpu_multipoles: device), "
                 "walks on the CPU, M2L, L2L, L2P, M2P and P2P on the GPU (one after the "
                 "other)"
               : "; self-gravity: multipoles on the GPU (Scheduler:gpu_multipoles: device), "
                 "walks on the CPU, M2L, L2L, L2P, M2P and P2P on the GPU (hybrid: the CPU "
                 "workers walk while the GPU computes the hydrodynamics; then gravity's GPU "
                 "part and the kick)";
  error_log(0,
            "GPU %s (%s): drift, density, ghost, %sforce, %skick2 of every cell run on it, the "
            "particles stay on it between steps%s",
            gpu_name(g), asked, e->hp.solids ? "gradient, extra ghost (plasticity, dS/dt), " : "",
            e->damage ? "damage, " : "", grav);
}

/** Scheduler callback of the gravity pass: the engine's task, with the
 *  calling worker's interactions recorded in its own list; after a
 *  grav_up task, its cell's multipoles go to the upload staging (the
 *  family's gravity_gpu_task). */
static void gpu_engine_grav_task(void *ctx, struct task *t, int thread_id) {
  struct engine *e = ctx;
  gravity_gpu_task(e, e->gpu->grav, t, thread_id);
}

/** Self-gravity of the FORCE phase, in three parts.  Prepare (here): with
 *  on_gpu the family's gravity_gpu_prepare (the tree on the device after a
 *  rebuild, the staging of the multipoles, the workers' lists emptied),
 *  then the gravity tasks of the graph activated (with on_gpu, grav_down,
 *  the GPU's, skipped).  Returns 0 when the step reuses the far field
 *  (Gravity:reuse_steps) or the walks run on the device: the GPU alone
 *  then, nothing on the CPU.  These make CUDA calls: before any thread
 *  drives the GPU beside. */
static int gpu_engine_grav_prepare(struct engine *e, int on_gpu) {
  struct gpu_engine *ge = e->gpu;
  if (on_gpu) {
    ge->grav_evals++;
    if (!gravity_gpu_prepare(e, ge->grav)) return 0;
  }
  engine_activate_phase(e, ENGINE_PHASE_FORCE);
  /* several MPI ranks: the host's L2L and L2P push what the walks with the
   * other ranks' records computed there (gpu_engine_grav_ranks) */
  const int down_on_host = !on_gpu || (e->halo && halo_gravity_by_records(e));
  for (int k = 0; k < e->sched.nr_tasks; k++) {
    struct task *t = scheduler_task(&e->sched, k);
    if (t->subtype != task_subtype_grav || (!down_on_host && t->type == task_type_grav_down) ||
        (on_gpu && ge->up_on_device && t->type == task_type_grav_up))
      t->skip = 1;
  }
  return 1;
}

/** Several MPI ranks: self-gravity with its interactions on the GPU.  The
 *  gravity tasks run on the CPU workers in the stages of several ranks
 *  (engine_run_gravity_stages; the copies for gravity go to the device as
 *  well, halo_device.gravity), their walks recording the interactions for
 *  the device, except those with the other ranks' top-level cells read by
 *  their records (walk_remote), which the host computes, and whose L2L and
 *  L2P the host's grav_down tasks push to ga and pot.  The device part
 *  then computes the rest and copies ga and pot back; the host's part is
 *  added and ga and pot go up for the kick. */
static void gpu_engine_grav_device(struct engine *e);
static void gpu_engine_grav_ranks(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  struct parts *p = &e->parts;
  const size_t n = p->count;
  const int records = halo_gravity_by_records(e);
  const double w0 = error_walltime();
  if (ge->walk_on_device) {
    /* the walks on the device too (skipping the cells of copies only and
     * those read by records, gravity_gpu_prepare); the multipoles back on
     * the host for the records, whose walks the host's long-range tasks
     * make (remote_only), then its grav_down tasks */
    halo_refresh_gravity(e);
    const double w1 = error_walltime();
    if (gpu_engine_grav_prepare(e, 1))
      error_bug("several MPI ranks: gravity's walks not on the GPU");
    const double w2 = error_walltime();
    ge->t_ranks[0] += w1 - w0;
    ge->t_ranks[1] += w2 - w1;
    if (records) {
      halo_gravity_records(e);
      const double w3 = error_walltime();
      ge->t_ranks[2] += w3 - w2;
      memset(p->gax, 0, n * sizeof(double));
      memset(p->gay, 0, n * sizeof(double));
      memset(p->gaz, 0, n * sizeof(double));
      memset(p->pot, 0, n * sizeof(double));
      engine_activate_phase(e, ENGINE_PHASE_FORCE);
      for (int k = 0; k < e->sched.nr_tasks; k++) {
        struct task *t = scheduler_task(&e->sched, k);
        t->skip = t->subtype != task_subtype_grav ||
                  (t->type != task_type_grav_long_range && t->type != task_type_grav_down);
      }
      e->gp.remote_only = 1;
      scheduler_run(&e->sched, engine_run_task, e);
      e->gp.remote_only = 0;
      halo_gravity_after(e);
      ge->t_ranks[3] += error_walltime() - w3;
    }
  } else {
    if (!gpu_engine_grav_prepare(e, 1))
      error_bug("several MPI ranks: gravity's walks not on the CPU");
    engine_run_gravity_stages(e, gpu_engine_grav_task);
  }
  ge->t_grav_walk += error_walltime() - w0;
  if (records) {
    if (n > ge->nr_remote) {
      free(ge->remote);
      ge->nr_remote = n + n / 4 + 1;
      ge->remote = error_malloc(4 * ge->nr_remote * sizeof(double), "GPU gravity, far field");
    }
    memcpy(ge->remote, p->gax, n * sizeof(double));
    memcpy(ge->remote + n, p->gay, n * sizeof(double));
    memcpy(ge->remote + 2 * n, p->gaz, n * sizeof(double));
    memcpy(ge->remote + 3 * n, p->pot, n * sizeof(double));
  }
  gpu_engine_grav_device(e);
  if (records) {
    for (size_t i = 0; i < n; i++) {
      p->gax[i] += ge->remote[i];
      p->gay[i] += ge->remote[n + i];
      p->gaz[i] += ge->remote[2 * n + i];
      p->pot[i] += ge->remote[3 * n + i];
    }
    gpu_upload_gravity(ge->gpu, p);
  }
}

/** The CPU part: the gravity tasks on the CPU workers, the calling thread
 *  as thread 0.  on_gpu: multipoles, and walks that record their
 *  interactions instead of computing them; else the CPU's own gravity
 *  (grav_down included), which leaves ga and pot complete on the host. */
static void gpu_engine_grav_cpu(struct engine *e, int on_gpu) {
  const double w0 = error_walltime();
  scheduler_run(&e->sched, on_gpu ? gpu_engine_grav_task : engine_run_task, e);
  e->gpu->t_grav_walk += error_walltime() - w0;
}

/** The engine's time bins for the GPU's next drift or kick (gpu_set_bins). */
static void gpu_engine_set_bins(struct engine *e) {
  const struct gpu_bins b = {e->individual, e->first_force, e->ti_current, e->ti_next, e->timeline};
  gpu_set_bins(e->gpu->gpu, &b);
}

/** The device part (the family's gravity_gpu_device: gpu_grav_run,
 *  grouping included, or the replay of a step that reuses the far field),
 *  which leaves ga and pot complete on both sides for the kick, on stream 0
 *  after whatever is queued there. */
static void gpu_engine_grav_device(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  const double w0 = error_walltime();
  gravity_gpu_device(e, ge->grav);
  ge->t_grav_gpu += error_walltime() - w0;
}

/** The hydrodynamic phase on the GPU driven by a host thread beside the
 *  CPU's gravity (hybrid modes), or alone (serial). */
struct gpu_hydro_job {
  struct engine *e;        /**< the engine */
  struct gpu_damage dmg;   /**< damage of this phase */
  struct gpu_gravity grav; /**< gravity in the kick */
  double dt_kick;          /**< second half kick */
  int capped;              /**< gpu_cells_force's result */
  pthread_mutex_t mutex;   /**< guards cpu_done */
  pthread_cond_t cond;     /**< signalled when cpu_done is set */
  int cpu_done;            /**< the CPU's gravity tasks have finished */
  int ga_ready;            /**< ga is complete on the device (the hook ran) */
  double t_start, t_hook;  /**< wall clock: the thread started, it reached the hook */
  double t_waited;         /**< seconds the hook waited for the CPU */
};

/** gpu_set_kick_wait's hook in the hybrid modes: wait until the CPU's
 *  gravity tasks are done, then complete ga on the device (gravity's device
 *  part, or the CPU's ga uploaded); at once when already done. */
static void gpu_engine_kick_wait(void *ctx) {
  struct gpu_hydro_job *jb = ctx;
  if (jb->ga_ready) return;
  struct engine *e = jb->e;
  jb->t_hook = error_walltime();
  pthread_mutex_lock(&jb->mutex);
  while (!jb->cpu_done) pthread_cond_wait(&jb->cond, &jb->mutex);
  pthread_mutex_unlock(&jb->mutex);
  jb->t_waited = error_walltime() - jb->t_hook;
  if (e->gpu->mode == GPU_MODE_HYBRID)
    gpu_engine_grav_device(e);
  else
    gpu_upload_gravity(e->gpu->gpu, &e->parts);
  jb->ga_ready = 1;
}

/** Thread body: the hydrodynamic phase (lists, density, ghost, gradient,
 *  force, damage, kick2) on the GPU.  Unpinned from thread 0's core, so
 *  that it and the list build's threads spread over the process's cores. */
static void *gpu_engine_hydro_run(void *arg) {
  struct gpu_hydro_job *jb = arg;
  struct engine *e = jb->e;
  struct gpu_engine *ge = e->gpu;
  runner_unpin_self(&e->sched.pool);
  jb->t_start = error_walltime();
  jb->capped = gpu_cells_force(ge->gpu, &ge->cells, &e->parts, &e->space, e->tcells, e->nr_tcells,
                               e->ct, ge->tc_h_cap, &e->hp, e->mats, &jb->dmg, &jb->grav,
                               jb->dt_kick, 1, e->cell_dt_min, e->individual ? e->cell_kick : NULL);
  return NULL;
}

/** halo_device's functions: the records of several MPI ranks from and to
 *  the resident particles. */
static void gpu_engine_halo_pack(void *ctx, const size_t *idx, size_t n, char *dst,
                                 const unsigned char *sel) {
  struct engine *e = ctx;
  gpu_halo_pack(e->gpu->gpu, &e->parts, idx, n, dst, sel);
}
static void gpu_engine_halo_unpack(void *ctx, const size_t *slot, size_t n, const char *src,
                                   const unsigned char *sel, int64_t q0) {
  struct engine *e = ctx;
  gpu_halo_unpack(e->gpu->gpu, slot, n, src, sel, q0);
}

/** gpu_set_stage_hook's function: the refresh of the copies after stage k
 *  of the phase (the fields it wrote), on thread 0 (MPI_THREAD_FUNNELED). */
static void gpu_engine_stage(void *ctx, int k) {
  struct engine *e = ctx;
  halo_refresh_start(e, k);
  halo_refresh_finish(e);
}

void gpu_engine_force(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  gpu_engine_set_bins(e);
  const double w_phase = error_walltime();
  if (e->halo) {
    /* several MPI ranks: every copy takes its owner's state (the drift and
     * the kick changed it), from device to device through the exchange;
     * then the phase's stages refresh what each wrote (gpu_engine_stage) */
    if (!ge->dev_valid) {
      gpu_upload_all(ge->gpu, &e->parts);
      ge->dev_valid = 1;
    }
    ge->halo = (struct halo_device){e, gpu_engine_halo_pack, gpu_engine_halo_unpack, 0};
    halo_set_device(e, &ge->halo);
    halo_refresh(e);
  }
  if (e->nr_tcells > ge->nr_tc) {
    ge->tc_h_cap = error_realloc(ge->tc_h_cap, e->nr_tcells * sizeof(double), "GPU caps");
    ge->nr_tc = e->nr_tcells;
  }
  /* the caps of the CPU ghost (tasks/ghost/ghost_task.c): a pair is found while
   * H_i + |dx_i| + |dx_j| stays below the reach of the task graph */
  const double H_limit = engine_H_limit(e);
  for (int t = 0; t < e->nr_tcells; t++) {
    double dx_max = 0.0;
    for (int k = 0; k < e->ct[t].nr_ngb; k++)
      if (e->tcells[e->ct[t].ngb[k]]->dx_max > dx_max) dx_max = e->tcells[e->ct[t].ngb[k]]->dx_max;
    ge->tc_h_cap[t] = (H_limit - 2.0 * dx_max) / kernel_gamma;
  }
  ge->cells.nr_threads = e->nr_threads;
  if (!ge->dev_valid) {
    gpu_upload_all(ge->gpu, &e->parts);
    ge->dev_valid = 1;
  }
  ge->host_stale = 1;
  ge->xh_fresh = 0; /* (the phase's h iteration) */
  struct gpu_hydro_job jb;
  memset(&jb, 0, sizeof jb);
  jb.e = e;
  /* (rk2/pc: no kick, the drift's stages put the states; damage grows
   * only at a step's end: tasks/drift/drift_integrate.c) */
  jb.dt_kick = e->first_force || e->scheme != ENGINE_SCHEME_KDK ? 0.0 : 0.5 * e->dt;
  /* no damage before Damage:start_time (damage_task does the same) */
  jb.dmg = (struct gpu_damage){e->damage && !(e->time < e->damage_start),
                               e->first_force || e->stage_eval ? 0.0 : e->dt, e->damage_max_change};
  jb.grav = (struct gpu_gravity){e->gp.enabled, e->gp.eps, e->gp.eta, e->gp.h_factor};
  const int hybrid = e->gp.enabled && ge->mode != GPU_MODE_SERIAL;
  const int on_gpu = ge->mode != GPU_MODE_CPU_GRAV;
  /* serial: gravity's CPU part and device part first */
  if (e->gp.enabled && !hybrid && e->halo) {
    ge->halo.gravity = 1;
    gpu_engine_grav_ranks(e);
    ge->halo.gravity = 0;
  } else {
    if (e->gp.enabled && !hybrid && gpu_engine_grav_prepare(e, 1)) gpu_engine_grav_cpu(e, 1);
    if (e->gp.enabled && !hybrid) gpu_engine_grav_device(e);
  }
  /* hybrid: prepare gravity (CUDA calls) before the hydro thread starts */
  int cpu_work = 0;
  if (hybrid) {
    cpu_work = gpu_engine_grav_prepare(e, on_gpu);
    if (cpu_work && e->halo) {
      /* several MPI ranks: thread 0 makes gravity's exchanges and then
       * drives the GPU, so the CPU's gravity runs whole first (ga and pot
       * complete on the host; the kick's hook uploads them) */
      const double w0 = error_walltime();
      engine_run_gravity_stages(e, engine_run_task);
      const double w = error_walltime() - w0;
      ge->t_grav_walk += w;
      ge->t_cpu_side += w;
      cpu_work = 0;
    }
    pthread_mutex_init(&jb.mutex, NULL);
    pthread_cond_init(&jb.cond, NULL);
    jb.cpu_done = !cpu_work;
    gpu_set_kick_wait(ge->gpu, gpu_engine_kick_wait, &jb);
  }
  /* the hydrodynamics on the GPU, driven by a thread off thread 0's core;
   * with several MPI ranks (no self-gravity: nothing runs beside) by
   * thread 0 itself, the only one that calls MPI */
  pthread_t tid;
  if (e->halo) {
    gpu_set_stage_hook(ge->gpu, gpu_engine_stage, e);
    gpu_engine_hydro_run(&jb);
    runner_repin_self(&e->sched.pool);
    gpu_set_stage_hook(ge->gpu, NULL, NULL);
    halo_set_device(e, NULL);
  } else if (pthread_create(&tid, NULL, gpu_engine_hydro_run, &jb))
    error_exit("cannot start the thread that drives the GPU");
  if (cpu_work) {
    /* the CPU workers, this thread as thread 0, while the GPU works */
    const double w0 = error_walltime();
    gpu_engine_grav_cpu(e, on_gpu);
    ge->t_cpu_side += error_walltime() - w0;
    pthread_mutex_lock(&jb.mutex);
    jb.cpu_done = 1;
    pthread_cond_signal(&jb.cond);
    pthread_mutex_unlock(&jb.mutex);
  }
  if (!e->halo) pthread_join(tid, NULL);
  if (hybrid) {
    gpu_set_kick_wait(ge->gpu, NULL, NULL);
    if (!jb.ga_ready) error_bug("the GPU's kick did not wait for self-gravity");
    pthread_mutex_destroy(&jb.mutex);
    pthread_cond_destroy(&jb.cond);
    ge->t_gpu_side += jb.t_hook - jb.t_start;
    ge->t_waited += jb.t_waited;
    ge->hybrid_phases++;
  }
  ge->t_phase += error_walltime() - w_phase;
  ge->phases++;
  if (jb.capped) e->need_rebuild = 1;
  if (!e->first_force) e->h_resummed += ge->cells.h_resummed; /* (its thread is joined) */
  ge->cells.h_resummed = 0;
}

/** cell_update_bounds of every top-level cell, on the engine's threads
 *  (space_update_bounds: the leaves shared among them). */
static void gpu_engine_bounds(struct engine *e) {
  /* (threads started by thread 0 inherit its core: spread them) */
  if (e->nr_threads > 1) runner_unpin_self(&e->sched.pool);
  space_update_bounds(&e->space, e->nr_threads);
  if (e->nr_threads > 1) runner_repin_self(&e->sched.pool);
}

int gpu_engine_rebuild_begin(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  if (!ge || !ge->dev_valid || !ge->rebuild_on_device || e->nr_planes > 0 ||
      e->restart_h_max > 0.0 || e->halo) {
    if (ge)
      error_log(1, "GPU rebuild %d on the host: %s", e->space.nr_rebuilds + 1,
                !ge->dev_valid           ? "the host holds the current particles"
                : !ge->rebuild_on_device ? "Scheduler:gpu_rebuild: host"
                : e->halo                ? "several MPI ranks (particles move between them)"
                : e->nr_planes > 0       ? "mirror planes"
                                         : "a resumed run's first rebuild");
    gpu_engine_to_host(e);
    gpu_engine_host_modified(e);
    if (ge) ge->rebuilds_host++;
    return 0;
  }
  if (ge->host_stale && !ge->xh_fresh) {
    gpu_copy_some(ge->gpu, &e->parts, gpu_rebuild_down, GPU_REBUILD_NR_DOWN, 0);
    ge->xh_fresh = 1;
  }
  if (space_rebuild_removes(&e->space)) {
    /* particles leave the open box: their budget reads every field */
    error_log(1, "GPU rebuild %d on the host: particles leave the open box",
              e->space.nr_rebuilds + 1);
    gpu_engine_to_host(e);
    gpu_engine_host_modified(e);
    ge->rebuilds_host++;
    return 0;
  }
  e->space.reorder = ge->reorder;
  return 1;
}

void gpu_engine_rebuild_end(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  e->space.reorder = NULL;
  gpu_permute(ge->gpu, space_order(&e->space), e->parts.count);
  if (e->space.periodic) {
    /* the positions the host wrapped into the box */
    static const char *const xyz[3] = {"x", "y", "z"};
    gpu_copy_some(ge->gpu, &e->parts, xyz, 3, 1);
  }
  gpu_copy_some(ge->gpu, &e->parts, gpu_rebuild_after, GPU_REBUILD_NR_AFTER, 0);
  ge->host_stale = 1; /* the host's other fields are in the old order */
  ge->rebuilds_device++;
}

void gpu_engine_drift(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  gpu_engine_set_bins(e);
  if (!ge->dev_valid) {
    gpu_upload_all(ge->gpu, &e->parts);
    ge->dev_valid = 1;
  }
  if (e->stage) /* a stage of rk2 or pc (tasks/drift/drift_integrate.c) */
    e->stage_err[0] = gpu_drift_stage(ge->gpu, &e->parts, e->stage, &e->hp);
  else
    gpu_drift(ge->gpu, &e->parts, 0.5 * e->dt, e->dt, &e->hp, e->mats);
  ge->host_stale = 1;
  ge->xh_fresh = 1; /* (gpu_drift copies x, y, z and h back) */
  /* positions and h are back: the bounds the rebuild test and the lists read */
  const double w0 = error_walltime();
  gpu_engine_bounds(e);
  ge->t_bounds += error_walltime() - w0;
  ge->steps++;
}

/** The device holds the current particles (uploaded if the host changed them). */
static void gpu_engine_resident(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  if (!ge->dev_valid) {
    gpu_upload_all(ge->gpu, &e->parts);
    ge->dev_valid = 1;
  }
}

void gpu_engine_rk_arrays(struct engine *e, int ny, int nr, int nrec, double **y0, double **r) {
  gpu_rk_arrays(e->gpu->gpu, e->parts.count, ny, nr, nrec, y0, r);
}

void gpu_engine_rk_restore(struct engine *e, const double *y0, const double *r1) {
  gpu_engine_resident(e);
  gpu_rk_restore(e->gpu->gpu, y0, r1);
  e->gpu->host_stale = 1;
  e->gpu->xh_fresh = 0;
}

void gpu_engine_watchdog_save(struct engine *e) {
  gpu_engine_resident(e);
  gpu_watchdog_save(e->gpu->gpu);
}

long gpu_engine_watchdog_moved(struct engine *e, double width, double *x0_host) {
  return gpu_watchdog_moved(e->gpu->gpu, width, x0_host);
}

int gpu_engine_watchdog_check(struct engine *e) {
  gpu_engine_resident(e);
  int32_t ids[MATERIAL_MAX];
  int n = 0;
  for (int k = 0; k < e->mats->n && n < MATERIAL_MAX; k++)
    if (e->mats->mats[k].u_floor) ids[n++] = e->mats->mats[k].id;
  return gpu_watchdog_check(e->gpu->gpu, ids, n);
}

void gpu_engine_to_host(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  if (!ge || !ge->host_stale) return;
  gpu_download_all(ge->gpu, &e->parts);
  ge->host_stale = 0;
  ge->xh_fresh = 1;
}

void gpu_engine_host_modified(struct engine *e) {
  if (e->gpu) e->gpu->dev_valid = 0;
}

void gpu_engine_print(const struct engine *e, FILE *f) {
  const struct gpu_engine *ge = e->gpu;
  if (!ge) return;
  gpu_print_timers(ge->gpu, f);
  if (ge->steps) {
    long nb = 0;
    const double dev_ms = ge->cells.dev ? gpu_lists_device_ms(ge->cells.dev, &nb) : 0.0;
    fprintf(f,
            "GPU host side, ms per step: neighbour lists %.3f (built %ld times on the %s, widened "
            "%ld; %d leaves, %d entries; device part %.3f ms per build), cell bounds %.3f\n",
            1e3 * ge->cells.t_build / ge->steps, ge->cells.builds,
            ge->cells.host_lists ? "host" : "device", ge->cells.widenings, ge->cells.n,
            ge->cells.nr_ngb, nb ? dev_ms / nb : 0.0, 1e3 * ge->t_bounds / ge->steps);
  }
  if (ge->rebuilds_device + ge->rebuilds_host)
    fprintf(f,
            "GPU rebuilds: %ld with the particles reordered on the device, %ld with every field "
            "copied back and up again (Scheduler:gpu_rebuild)\n",
            ge->rebuilds_device, ge->rebuilds_host);
  if (ge->phases) {
    static const char *const mode_name[3] = {"serial", "hybrid", "gravity on the CPU"};
    fprintf(f, "GPU runner (%s), ms per FORCE phase: %.3f", mode_name[ge->mode],
            1e3 * ge->t_phase / ge->phases);
    if (ge->hybrid_phases)
      fprintf(f,
              "; at the same time (%ld phases): CPU gravity tasks %.3f, GPU hydrodynamics until "
              "the kick %.3f, the kick waited %.3f for the CPU",
              ge->hybrid_phases, 1e3 * ge->t_cpu_side / ge->hybrid_phases,
              1e3 * ge->t_gpu_side / ge->hybrid_phases, 1e3 * ge->t_waited / ge->hybrid_phases);
    if (e->halo)
      fprintf(f, "; the foreign copies' records gathered and scattered on the device %.3f",
              gpu_halo_ms(ge->gpu) / ge->phases);
    fprintf(f, "\n");
  }
  gravity_gpu_print(ge->grav, f);
  double run = 0.0, total = 0.0;
  gpu_memory_used(ge->gpu, &run, &total);
  fprintf(f, "GPU memory: %.1f MiB held by the run (%.0f bytes per particle) of %.1f GiB\n",
          run / 1048576.0, e->parts.count ? run / (double)e->parts.count : 0.0,
          total / 1073741824.0);
  gpu_memory_by_use(f, (double)e->parts.count);
  if (ge->grav_evals)
    fprintf(f,
            "GPU gravity host side, ms per evaluation: multipoles + walks on the CPU %.3f, "
            "device part (copies included) %.3f\n",
            1e3 * ge->t_grav_walk / ge->grav_evals, 1e3 * ge->t_grav_gpu / ge->grav_evals);
  if (ge->grav_evals && e->halo && ge->walk_on_device)
    fprintf(f,
            "GPU gravity on several ranks, ms per evaluation: the copies' refresh %.3f, the "
            "device's multipoles and walks (copied back) %.3f, the records' exchange %.3f, the "
            "host's walks with the records and their L2L, L2P %.3f\n",
            1e3 * ge->t_ranks[0] / ge->grav_evals, 1e3 * ge->t_ranks[1] / ge->grav_evals,
            1e3 * ge->t_ranks[2] / ge->grav_evals, 1e3 * ge->t_ranks[3] / ge->grav_evals);
}

void gpu_engine_free(struct engine *e) {
  struct gpu_engine *ge = e->gpu;
  if (!ge) return;
  gpu_unpin(ge->gpu);
  gravity_gpu_free(ge->grav);
  gpu_free(ge->gpu);
  gpu_cells_free(&ge->cells);
  free(ge->tc_h_cap);
  free(ge->reorder);
  free(ge->remote);
  free(ge);
  e->gpu = NULL;
}
