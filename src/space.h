/* The space: the simulation box, its top-level grid of cells and the octree
 * below each top-level cell, over particles sorted so that every cell owns
 * one contiguous index range (theory/architecture.md, "Data layout").
 *
 * space_rebuild() wraps (periodic box) or removes (open box) particles,
 * chooses the top-level grid so that every interacting pair of particles is
 * in the same or in neighbouring top-level cells, sorts the particles by
 * top-level cell and then by octant down to split_size particles per leaf,
 * and fills each cell's range, h_max and bounding box.  space_top_pairs()
 * lists the pairs of top-level cells that can interact, with the periodic
 * shift of each: the engine makes one pair task per entry and one self task
 * per non-empty top-level cell.
 *
 * Interactions: particles i and j interact when r_ij < H_i (gather form) or
 * r_ij < max(H_i, H_j) (symmetric form), with H = kernel_gamma * h and, in a
 * periodic box, r_ij the minimum-image distance (unique: the box must be at
 * least 2 H_max wide in every periodic direction). */
#ifndef BOLIDE_SPACE_H
#define BOLIDE_SPACE_H

#include <stddef.h>

#include "src/budget.h"
#include "src/cell.h"
#include "src/timeline.h"

struct parts;

/** Default deepest octree level below a top-level cell (a leaf may hold more
 *  than split_size particles only if they are this close together). */
#define SPACE_MAX_DEPTH 30

/** When a rebuild of the kick-drift-kick step removes particles: how long
 *  ago each was last evaluated, so that what it takes with it is its state
 *  of now (space.c, space_count_removed). */
struct space_clock {
  int set;           /**< 0: count the particles' fields as they are */
  double since_eval; /**< the global step: its dt (every particle was evaluated at its start) */
  const struct timeline *tl; /**< time bins: the run's time line (NULL: the global step) */
  integertime_t ti;          /**< time bins: now on it */
};

/** The box, its cells and the particles they index. */
struct space {
  double dim[3];             /**< box size; the box is [0, dim) in every direction */
  int periodic;              /**< 1: periodic box (positions wrapped); 0: open box */
  int cdim[3];               /**< top-level grid: number of cells per direction */
  double width[3];           /**< edge lengths of a top-level cell, dim / cdim */
  double iwidth[3];          /**< 1 / width */
  struct cell *cells;        /**< all cells: top-level ones first (grid order), then octree cells */
  int *progeny_index;        /**< 8 per cell: index in cells of each octant, -1 where empty */
  int nr_top;                /**< number of top-level cells, cdim[0] * cdim[1] * cdim[2] */
  int nr_cells;              /**< number of cells in use (top-level and octree) */
  int cells_capacity;        /**< allocated length of cells (and of progeny_index / 8) */
  struct parts *parts;       /**< the particles (owned by the caller) */
  int split_size;            /**< a cell with more particles than this is split */
  int max_top_level_cells;   /**< at most this many top-level cells per direction */
  int max_depth;             /**< deepest octree level (SPACE_MAX_DEPTH) */
  double cell_stretch;       /**< top-level width >= cell_stretch * kernel_gamma * h_max at rebuild,
                                  the margin for h to grow before the next rebuild (1.1) */
  double max_drift_fraction; /**< rebuild when a particle drifted more than this fraction of a
                                  top-level cell width (0.25) */
  double h_max;              /**< largest smoothing length at the last rebuild */
  size_t nr_removed;         /**< particles removed from an open box since space_init */
  struct budget_removed removed; /**< what they took with them (the engine sets it on restart) */
  struct space_clock clock;      /**< for them, set by the step around its rebuilds */
  double *gone;                  /**< the particles the last rebuild removed: x, y, z, m, h each
                                      (for the potential energy of their pairs, which their
                                      m pot counts twice; engine.c) */
  size_t nr_gone, gone_cap;      /**< their number and the room for them */
  int nr_rebuilds;               /**< number of calls of space_rebuild */
  int nr_timed;                  /**< calls of space_rebuild after the first (t_parts) */
  double t_parts[4];             /**< their wall seconds: sort by top-level cell, octrees, reorder,
                                      boxes (the first, which sorts a file's order, left out) */
  size_t *sort_index;            /**< work array of the rebuild (capacity sort_capacity) */
  size_t sort_capacity;          /**< allocated length of sort_index */
  unsigned char *sort_oct;       /**< the octrees' work array of octants (space.c) */
  size_t oct_capacity;           /**< allocated length of sort_oct */
  int nr_threads;                /**< threads of the rebuild's reordering of the fields (1) */
  const unsigned char *reorder;  /**< [part_nr_fields]: the fields the rebuild reorders (NULL:
                                      every field; the others are left in the old order, e.g.
                                      while the GPU holds them and reorders its own copies) */
  double restore_h_max;          /**< > 0: space_choose_grid takes this h_max (space_restore) */
  double h_max_floor;            /**< space_choose_grid takes at least this h_max: the largest h
                                      of every rank's particles (src/mpi/halo.c), so that all ranks
                                      choose the grid that one rank holding them all would */
};

/** One pair of top-level cells that can interact: the particles of cj are
 *  seen from ci at x_j + shift (the periodic image; 0 in an open box). */
struct space_pair {
  int ci, cj;      /**< indices of the two top-level cells in space.cells */
  double shift[3]; /**< added to the positions of cj's particles */
};

/** Set up a space over the particles parts (not yet sorted: call
 *  space_rebuild).  box: the box size; periodic: 1 or 0; split_size: most
 *  particles in a leaf; max_top_level_cells: most top-level cells per
 *  direction.  Bad values stop with a one-line error. */
void space_init(struct space *s, struct parts *parts, const double box[3], int periodic,
                int split_size, int max_top_level_cells);

/** Free the cells and work arrays (not the particles). */
void space_free(struct space *s);

/** Rebuild: wrap positions into the periodic box or remove the particles
 *  outside the open box (each id logged, never silently lost), choose the
 *  top-level grid, sort the particles (every cell one contiguous range),
 *  build the octrees, store x0 = x and compute every cell's h_max and
 *  bounding box.  Returns the number of particles removed by this call.
 *  A non-finite position or smoothing length, or (periodic box) a kernel
 *  support larger than half the box, stops with a one-line error naming the
 *  particle. */
size_t space_rebuild(struct space *s);

/** The first half of space_rebuild without cells: wrap or remove the
 *  particles outside the box and choose the top-level grid (s->h_max,
 *  cdim, width), so that the reach of the next rebuild is known; the
 *  particles are not sorted and the cells are those of the last rebuild
 *  (several MPI ranks: the rebuild that follows with the foreign copies
 *  makes them).  Returns the number of particles removed. */
size_t space_prepare(struct space *s);

/** 1 if the next space_rebuild would remove a particle (outside the open
 *  box) or stop on a non-finite position or smoothing length: it reads x,
 *  y, z and h only. */
int space_rebuild_removes(const struct space *s);

/** cell_update_bounds of every top-level cell (h_max and dx_max of every
 *  cell from the particles), on up to nr_threads threads sharing the
 *  leaves; the same values as one thread. */
void space_update_bounds(struct space *s, int nr_threads);

/** The permutation of the last space_rebuild: element i of every field is
 *  now the old element order[i] (parts.count entries; valid until the next
 *  rebuild). */
const size_t *space_order(const struct space *s);

/** Rebuild the cells of the last rebuild of a run resumed from a restart
 *  file (issue 18): the particles are in the order of that rebuild and x0
 *  holds their positions then, h_max is the space's h_max then, and cell_h /
 *  cell_dx (nr_cells values, NULL: recompute) the cells' h_max and dx_max at
 *  the end of the step the file was written after.  The top-level grid, the
 *  octrees and the order are those of the uninterrupted run (the counting
 *  sorts are stable: the permutation is the identity), so that the resumed
 *  run takes the same steps.  A cell count other than nr_cells stops with
 *  one line (file: the restart file's name). */
void space_restore(struct space *s, double h_max, const double *cell_h, const double *cell_dx,
                   int nr_cells, const char *file);

/** 1 if the cells no longer hold every interaction among neighbours or are
 *  too stale: some particle moved more than max_drift_fraction of a cell
 *  width since the rebuild, or kernel_gamma * h_max + 2 * (largest drift)
 *  exceeds a top-level cell width (or half a periodic box); else 0. */
int space_should_rebuild(const struct space *s);

/** The top-level cell (index in s->cells) of the position (x, y, z) inside
 *  the box, as space_rebuild sorts it (wrapped already where periodic). */
int space_top_cell_of(const struct space *s, double x, double y, double z);
/** The same criterion for the largest drift dmax since the rebuild and the
 *  largest smoothing length h_max of the particles (of every rank). */
int space_should_rebuild_at(const struct space *s, double dmax, double h_max);

/** Index in s->cells of top-level cell (i, j, k). */
static inline int space_top_index(const struct space *s, int i, int j, int k) {
  return (i * s->cdim[1] + j) * s->cdim[2] + k;
}

/** The pairs of non-empty top-level cells that can interact (neighbours
 *  within one cell, periodic images included), each once, with the shift
 *  of cj.  *pairs is allocated here (free() it); returns their number. */
size_t space_top_pairs(const struct space *s, struct space_pair **pairs);

#endif
