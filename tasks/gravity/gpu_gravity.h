/* Self-gravity on the GPU, the C interface of the gravity family's device
 * code: its device state and the sequence of its kernels
 * (tasks/gravity/gpu_gravity.cu) and its host side
 * (tasks/gravity/gpu_gravity_host.c: the cell tree as index arrays, the
 * multipoles packed for the upload, a whole evaluation in sequence).  The
 * GPU runner (src/gpu/gpu_engine.c) runs it in its FORCE phase through the
 * registry's entry points gravity_gpu_* (gpu_gravity_runner.c), without
 * this header.  Built only when configure finds nvcc (HAVE_CUDA). */
#ifndef BOLIDE_GPU_GRAVITY_H
#define BOLIDE_GPU_GRAVITY_H

#include <stddef.h>
#include <stdio.h>

#include "src/gpu/gpu.h"
#include "src/part.h"
#include "tasks/gravity/gravity_cpu.h"

#ifdef __cplusplus
extern "C" {
#endif

struct cell;
struct space;

/** The cell tree of self-gravity on the GPU as index arrays (cells by
 *  struct cell.index): set again after each rebuild (gpu_grav_set_tree). */
struct gpu_grav_tree {
  int nr_cells;               /**< cells 0 .. nr_cells - 1 */
  const size_t *offset;       /**< first particle of each cell */
  const int *count;           /**< its particles */
  int nr_l2l;                 /**< parent-child pairs of non-empty cells, level after level */
  const int *l2l_child;       /**< child of each pair */
  const int *l2l_parent;      /**< parent of each pair */
  int nr_levels;              /**< tree levels below the top-level cells */
  const int *level_start;     /**< nr_levels + 1: level L's pairs are [level_start[L], [L+1]) */
  int nr_leaves;              /**< non-empty leaves */
  const int *leaf;            /**< their cell indices */
  const double *centre;       /**< 3 per cell: the centre of its box */
  const int *progeny;         /**< 8 per cell: child cell or -1 (gravity_walk_tree_arrays) */
  const unsigned char *split; /**< 1 per cell: it has progeny */
};

/** Self-gravity's device state (buffers of the tree, the multipoles, the
 *  local expansions and the grouped interactions; opaque). */
struct gpu_grav;

/** Self-gravity's device state on g (freed by gpu_grav_free, before gpu_free). */
struct gpu_grav *gpu_grav_new(struct gpu *g);
void gpu_grav_free(struct gpu_grav *gg);
/** Upload the cell tree (after each rebuild). */
void gpu_grav_set_tree(struct gpu_grav *gg, const struct gpu_grav_tree *t);
/** Pinned host array of at least nr_cells multipoles (kept while large
 *  enough): the caller writes each cell's multipole (gravity_up's) at its
 *  index before gpu_grav_run. */
struct gravity_multipole *gpu_grav_multipoles(struct gpu_grav *gg, int nr_cells);
/** The upward pass on the device (P2M, M2M; gravity_up_leaf and
 *  gravity_up_node of gravity_iact.h, as the CPU's gravity_up): every
 *  cell's multipole, a_min (from the device's gax, gay, gaz of the last
 *  evaluation) and h_support, left on the device for the next
 *  gpu_grav_run (which then uploads no multipoles) and copied back for the
 *  CPU's walks: *mp, *a_min, *h_support point to pinned host arrays by
 *  cell index, valid until the next call (mp NULL: nothing comes back,
 *  the walks being on the device too).  resident = 0: upload x, y, z, m,
 *  h, gax, gay, gaz first. */
void gpu_grav_up(struct gpu_grav *gg, struct parts *p, int order, double h_factor, int resident,
                 const struct gravity_multipole **mp, const double **a_min,
                 const double **h_support);
/** The walks on the device (gravity_walk.h, the CPU's decisions) from
 *  every pair of the nr_top top-level cells (cells 0 .. nr_top - 1, boxes
 *  lo_hi: 6 doubles each, as now on the host), on the multipoles of this
 *  evaluation's gpu_grav_up (required before): the interactions stay on
 *  the device for the next gpu_grav_run, which then uploads no records.
 *  theta, h_support (the constant support), G, epsilon_fmm, h_factor,
 *  order: as struct gravity_props.  top (host, nr_top entries; NULL:
 *  cells 0 .. nr_top - 1): the cell of each box, the non-empty top-level
 *  cells only; skip (host, nr_top entries; NULL: none): the top-level cells
 *  of copies only and those read by their records on several MPI ranks
 *  (gravity_walk_root). */
void gpu_grav_walk(struct gpu_grav *gg, const double *lo_hi, int nr_top, double theta,
                   double h_support, double G, double epsilon_fmm, double h_factor, int order,
                   const unsigned char *skip, const int *top);
/** One gravity evaluation on the device, ending with p's pot, gax, gay, gaz
 *  complete on the device and on the host.  replay = 0: the multipoles
 *  (gpu_grav_multipoles) and the interactions that the walks recorded in
 *  rec[0..nr_rec) (one struct per worker) go up; the device groups the
 *  interactions by receiving cell (counting sort with atomic cursors: the
 *  order within a cell varies from run to run, like the CPU's task order),
 *  zeroes the fields and runs M2L and P2L, L2L level by level, P2P and M2P,
 *  L2P.  replay = 1 (Gravity:reuse_steps): the multipoles, local
 *  expansions and grouped interactions of the last full evaluation stay;
 *  only P2P, M2P and L2P run, at the current positions (rec unused).
 *  resident = 0: upload x, y, z and m first.  G, eps, softening, eps2
 *  (softening^2 in the expansions), order: as struct gravity_props. */
void gpu_grav_run(struct gpu_grav *gg, struct parts *p, const struct gravity_gpu_rec *rec,
                  int nr_rec, double G, double eps, int softening, double eps2, int order,
                  int resident, int replay);
/** Whether the coming evaluation is a step of active particles only
 *  (gravity_props.active_step; time bins): gpu_grav_up marks the cells
 *  that hold a particle that ends its step (PART_INACTIVE not set),
 *  gpu_grav_walk records the interactions that such cells receive only
 *  (gravity_walk_run's rules), gpu_grav_run zeroes and completes the ga and
 *  pot of their leaves only.  Needs the walks on the device; on == 0 (the
 *  default): every cell. */
void gpu_grav_set_active(struct gpu_grav *gg, int on);
/** on = 1 (Gravity:gpu_reproducible): sort each cell's grouped
 *  interactions, whose order the atomics of the walks and of the grouping
 *  change from run to run, so that the sums, and a run, are the same bit
 *  for bit each time (at a cost: BENCHMARKS.md); 0 (the default): not. */
void gpu_grav_set_reproducible(struct gpu_grav *gg, int on);
/** Print the accumulated times of the gravity kernels. */
void gpu_grav_print(const struct gpu_grav *gg, FILE *f);

/** Host side of self-gravity on the GPU, grown and reused between steps:
 *  the cell tree as index arrays (gpu_grav_tree_build, at each rebuild). */
struct gpu_grav_host {
  struct gpu_grav_tree tree;      /**< the tree, as gpu_grav_set_tree reads it */
  size_t *offset;                 /**< storage of the tree: by cell */
  int *count, cells_cap;          /**< by cell; allocated cells */
  double *centre;                 /**< by cell: its box centre (3 doubles) */
  int *progeny;                   /**< by cell: 8 children or -1 (walks) */
  unsigned char *split;           /**< by cell: split flag (walks) */
  double *lo_hi;                  /**< by non-empty top-level cell: its box (6 doubles, walks) */
  int *top;                       /**< the cell of each box */
  unsigned char *top_skip;        /**< the walks' skip of each (several MPI ranks) */
  int lo_hi_cap;                  /**< top-level cells they hold */
  int *l2l_tmp;                   /**< (child, parent, level) while building */
  int *l2l_child, *l2l_parent;    /**< pairs by level */
  int nr_l2l, l2l_cap;            /**< pairs and allocated length */
  int *level_start;               /**< levels + 1 */
  int *leaf, nr_leaf, leaf_cap;   /**< non-empty leaves */
  int built_rebuild;              /**< space.nr_rebuilds of the tree */
  const struct cell *built_cells; /**< space.cells of the tree */
};
/** The tree of s (its top-level cells' octrees) as index arrays into h->tree. */
void gpu_grav_tree_build(struct gpu_grav_host *h, const struct space *s);
/** Copy the multipoles of c's octree from gc into dst (by cell index). */
void gpu_grav_pack_multipoles(struct gravity_multipole *dst, const struct cell *c,
                              const struct gravity_cell *gc);
/** Free the arrays of h and zero it. */
void gpu_grav_host_free(struct gpu_grav_host *h);
/** The upward pass of every cell of s on the device (gpu_grav_up), copied
 *  into gc (multipole, a_min, h_support; the field zeroed) for the CPU's
 *  walks, as gravity_up of every top-level cell would leave it (host ga
 *  and pot are not zeroed: the device's evaluation overwrites them); gc
 *  NULL: nothing copied back (the walks on the device too).  Only the
 *  first nr_fill cells are copied into gc (-1: every cell; the top-level
 *  cells come first); back (NULL: not wanted) receives the pinned staging
 *  of every cell, valid until the next upward pass, for
 *  gravity_back_fill. */
void gpu_grav_up_cells(struct gpu_grav *gg, struct parts *p, const struct space *s,
                       struct gravity_cell *gc, const struct gravity_props *gp, int resident,
                       int nr_fill, struct gravity_back *back);
/** The walks of every top-level cell of s on the device (gpu_grav_walk,
 *  after gpu_grav_up_cells), with the cells' boxes as they are now; skip
 *  as gpu_grav_walk's. */
void gpu_grav_walk_cells(struct gpu_grav *gg, struct gpu_grav_host *h, const struct space *s,
                         const struct gravity_props *gp, const unsigned char *skip);
/** The whole tree method with the far field on the GPU, without tasks, in
 *  the order of gravity_tree_all: gravity_up of every top-level cell on
 *  the CPU, the walks recorded (gravity_gpu_record) into rec (emptied
 *  first; the caller keeps it, e.g. to count the interactions) and run on
 *  the device (gpu_grav_run; resident as there).  Sets p's ga and pot.
 *  up_on_device: the upward pass on the device instead (gpu_grav_up_cells);
 *  walk_on_device (with up_on_device): the walks too (gpu_grav_walk_cells;
 *  rec then stays empty).  resident = 0: gravity_estimate on the host
 *  first where needed (a first evaluation), as gravity_tree_all.  For
 *  tests; h->built_rebuild must start at -1. */
void gpu_grav_tree_all(struct gpu_grav *gg, struct gpu_grav_host *h, struct gravity_gpu_rec *rec,
                       struct parts *p, const struct space *s, struct gravity_cell *gc,
                       const struct gravity_props *gp, int resident, int up_on_device,
                       int walk_on_device);

#ifdef __cplusplus
}
#endif

#endif
