/* Cells: the top-level grid and its octrees.
 *
 * Every cell owns one contiguous range [offset, offset + count) of the
 * particle arrays, sorted at rebuild (space_rebuild): a cell's progeny split
 * its range into consecutive sub-ranges, so a batch of cells is a set of
 * ranges (cheap packing for the GPU, MPI and SIMD).
 *
 * Geometry: loc/width is the cell's box in the grid; bmin/bmax the bounding
 * box of its particles' positions at the last rebuild (x0); a particle is at
 * most dx_max from its rebuild position, so its current position lies in the
 * bounding box grown by dx_max.  The interaction loops (tasks/iact_loop.h)
 * prune sub-cell pairs with bmin/bmax, dx_max and h_max; the tasks that move
 * particles or change h keep dx_max and h_max up to date (cell_update_bounds).
 *
 * All cells live in one array (struct space.cells): the top-level cells
 * first, in grid order, then the octree cells. */
#ifndef BOLIDE_CELL_H
#define BOLIDE_CELL_H

#include <stddef.h>

#include "src/inline.h"
#include "src/task.h"

struct parts;

/** Number of pointer-sized slots a cell keeps for the engine's tasks. */
#define CELL_TASK_SLOTS 16

/** One cell of the top-level grid or of an octree below it. */
struct cell {
  double loc[3];           /**< lower corner of the cell's box */
  double width[3];         /**< edge lengths of the cell's box */
  double bmin[3];          /**< bounding box of the particles at rebuild (x0): lower corner */
  double bmax[3];          /**< bounding box of the particles at rebuild (x0): upper corner */
  double h_max;            /**< largest smoothing length of the cell's particles */
  double dx_max;           /**< largest displacement of a particle since the rebuild */
  size_t offset;           /**< index of the first particle in the sorted arrays */
  size_t count;            /**< number of particles, the range [offset, offset + count) */
  int depth;               /**< 0 for a top-level cell, parent's depth + 1 below */
  int split;               /**< 1 if the cell has progeny (then every particle is in one of them) */
  struct cell *progeny[8]; /**< octants (x, y, z bits 4, 2, 1), NULL where empty */
  struct cell *parent;     /**< NULL for a top-level cell */
  int index;               /**< position of this cell in struct space.cells */
  int top;                 /**< index of the top-level cell this cell descends from */
  int active;              /**< set by the engine: the cell has active particles this step */
  int copies;              /**< several MPI ranks (src/mpi/halo.c): 1 if the cell holds a foreign
                                copy (its tasks wait for the refresh of the copies) */
  int foreign;             /**< several MPI ranks (src/mpi/halo.c): 1 if every particle of the cell
                                is a foreign copy, 0 otherwise */
  struct sched_lock lock;  /**< taken by the tasks that write the cell's particles */
  void *tasks[CELL_TASK_SLOTS]; /**< tasks of this cell, filled by the engine */
};

/** The CPU hydro loops treat a cell of at most this many particles as a
 *  leaf even where the octree splits it further (Scheduler:cpu_leaf_size,
 *  set by the engine; 0: only the tree's leaves). */
extern int cell_loop_leaf_max;

/** Recompute h_max and dx_max of c and its progeny from the particles (leaves)
 *  and the progeny (split cells): call after a drift or a change of h.  The
 *  bounding boxes stay those of the rebuild, dx_max accounting for motion. */
void cell_update_bounds(const struct parts *p, struct cell *c);

/** h_max and dx_max of the leaf c from its particles. */
void cell_leaf_bounds(const struct parts *p, struct cell *c);

/** h_max and dx_max of c and its split progeny from their leaves', which
 *  are left as they are (cell_leaf_bounds: space_update_bounds does the
 *  leaves of every tree on several threads first). */
void cell_gather_bounds(struct cell *c);

/** Recompute only h_max of c and its progeny (the ghost, after changing h:
 *  positions, and so dx_max, do not change while other tasks read them). */
void cell_update_h_max(const struct parts *p, struct cell *c);

/** Squared distance between the bounding box of ci and that of cj shifted by
 *  shift (0 where they overlap): the positions at rebuild. */
BOLIDE_INLINE double cell_bbox_dist2(const struct cell *ci, const struct cell *cj,
                                     const double shift[3]) {
  double d2 = 0.0;
  for (int k = 0; k < 3; k++) {
    const double a = cj->bmin[k] + shift[k] - ci->bmax[k];
    const double b = ci->bmin[k] - cj->bmax[k] - shift[k];
    const double g = a > b ? a : b;
    if (g > 0.0) d2 += g * g;
  }
  return d2;
}

/** Squared distance from the point x to the bounding box of c shifted by
 *  shift (0 inside). */
BOLIDE_INLINE double cell_point_dist2(const struct cell *c, const double x[3],
                                      const double shift[3]) {
  double d2 = 0.0;
  for (int k = 0; k < 3; k++) {
    const double a = c->bmin[k] + shift[k] - x[k];
    const double b = x[k] - c->bmax[k] - shift[k];
    const double g = a > b ? a : b;
    if (g > 0.0) d2 += g * g;
  }
  return d2;
}

#endif
