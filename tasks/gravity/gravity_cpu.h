/* Self-gravity on the CPU: the cell-level routines that gravity tasks call.
 *
 * The fast multipole method of tasks/gravity/gravity_iact.h over the cell
 * octrees of src/space.h (theory/gravity.md):
 *
 *   gravity_up          per top-level cell: P2M at the leaves, M2M up     (grav_up)
 *   gravity_interact_cells  per top-level self (ci == cj) and per near pair:
 *                       symmetric dual-tree walk, M2L where the opening
 *                       criterion accepts, P2P between leaves            (self/pair, grav)
 *   gravity_long_range  per top-level cell: one-way walk against every
 *                       top-level cell that is not its near pair         (grav_long_range)
 *   gravity_down        per top-level cell: L2L down, L2P to particles   (grav_down)
 *
 * Dependencies: up(every cell) -> interact, long_range -> down(cell).
 * Conflicts: a self task and a long-range task write ci only (its field
 * tensors and its particles' ax, ay, az, pot); a pair task writes ci and cj.
 * Every task only reads the positions, masses and multipoles of other cells.
 *
 * Which top-level pairs are "near" (pair tasks) is gravity_top_pair_is_near,
 * a geometric test on the cells' boxes meant for building the graph once per
 * rebuild; any choice is correct (a long-range task walks into a far cell
 * when the opening criterion refuses it), it only moves work between tasks.
 *
 * Gravity data (multipoles, field tensors) are cold data kept apart from
 * struct cell, in an array of struct gravity_cell indexed by cell->index
 * (the cell's position in struct space.cells); struct cell is unchanged.
 *
 * Particle fields: gravity owns pot and the accumulators gax, gay, gaz
 * (src/part.h): gravity_up zeroes them for its cell, the interactions add
 * to them, gravity_down completes them; the engine's kick adds ga to the
 * hydrodynamic acceleration ax, ay, az (gravity and hydro tasks then never
 * write the same field and need no common lock).  |ga| stays until the next
 * gravity_up: the scale of the adaptive criterion.  Gravity in a periodic box
 * (Ewald sums) is not implemented: gravity_check_space refuses it. */
#ifndef BOLIDE_GRAVITY_CPU_H
#define BOLIDE_GRAVITY_CPU_H

#include <stddef.h>

#include "tasks/gravity/gravity_iact.h"
#include "tasks/gravity/gravity_props.h"
#include "tasks/task_families.h"

struct cell;
struct parts;

/** One particle-level interaction of a walk: what a step that reuses the
 *  far field recomputes (gravity_replay). */
struct gravity_iitem {
  const struct cell *a, *b; /**< leaves (P2P; b == NULL: within a), or leaf a and cell b (M2P) */
  int kind;                 /**< 0: P2P, 1: M2P of b's multipole to a's particles */
  int symmetric;            /**< P2P: b's particles receive too */
};

/** The particle-level interactions of one gravity task, recorded by a full
 *  evaluation (gravity_record_begin ... end) and replayed by the steps that
 *  reuse the far field: those steps keep every cell's local expansion (the
 *  M2L and P2L of the full step) and every multipole, recompute the P2P
 *  pairs and the M2P of the list at the particles' current positions, and
 *  evaluate the kept local expansions at the current positions (L2P).  The
 *  error is that of sources that moved since the full evaluation: of order
 *  displacement / distance of the far-field interactions (theory/gravity.md;
 *  measured in tests/unit/test_gravity_reuse). */
struct gravity_ilist {
  struct gravity_iitem *item; /**< the interactions */
  int count, capacity;        /**< their number and the allocated length */
  double d_min; /**< shortest centre distance of an M2L or M2P of the walk (HUGE_VAL: none) */
};

/** Gravity data of one cell (cold: only gravity tasks read them). */
struct gravity_cell {
  struct gravity_multipole mp; /**< multipole about the centre of mass (gravity_up) */
  struct gravity_field field;  /**< local expansion about mp.com (interactions, gravity_down) */
  double a_min;     /**< smallest |ga| of the cell's particles at the previous pass (0: unknown) */
  double h_support; /**< largest kernel support 3 h_factor h_i of the cell's particles (gravity_up;
                         0 unless Gravity:softening_h_factor > 0) */
};

/** An upward pass made elsewhere (the GPU's, copied back to its staging),
 *  by cell index: what gravity_up would leave in a gravity_cell. */
struct gravity_back {
  const struct gravity_multipole *mp;
  const double *a_min, *h_support;
};

/** gc[k] from b (multipole, a_min, h_support; the field zeroed). */
BOLIDE_INLINE void gravity_back_fill_cell(const struct gravity_back *b, int k,
                                          struct gravity_cell *gc) {
  gc[k].mp = b->mp[k];
  gc[k].a_min = b->a_min[k];
  gc[k].h_support = b->h_support[k];
  gravity_field_zero(&gc[k].field);
}

/** gravity_back_fill_cell for c and every cell below it. */
void gravity_back_fill(const struct gravity_back *b, const struct cell *c, struct gravity_cell *gc);

/** Record the particle-level interactions of the walks this thread runs
 *  until gravity_record_end into il (emptied first; NULL: record nothing). */
void gravity_record_begin(struct gravity_ilist *il);
void gravity_record_end(void);

/** Redo the particle-level interactions of il at the current positions
 *  (a step with gp->replay set; gravity_up and gravity_down then keep the
 *  multipoles and local expansions of the last full evaluation). */
void gravity_replay(struct parts *p, const struct gravity_ilist *il, struct gravity_cell *gc,
                    const struct gravity_props *gp);

/** Free the interactions of il. */
void gravity_ilist_free(struct gravity_ilist *il);

/** Stop with a one-line error if gravity cannot run in this box (periodic). */
void gravity_check_space(const struct gravity_props *gp, int periodic);

/** Grow the per-cell gravity array to at least n cells (after a rebuild:
 *  n = space.cells_capacity).  Returns the (possibly moved) array. */
struct gravity_cell *gravity_cells_reserve(struct gravity_cell *gc, int *capacity, int n);

/** P2M at the leaves of c's octree and M2M up to c; also zeroes the field
 *  tensors of c's octree (a new step's expansions start from 0), records
 *  each cell's a_min from |ga| and zeroes ga and pot of c's particles.
 *  Writes c's particles' ga and pot only. */
void gravity_up(struct parts *p, const struct cell *c, struct gravity_cell *gc,
                const struct gravity_props *gp);

/** Interactions within ci (ci == cj) or between ci and cj (a near pair):
 *  symmetric dual-tree walk; writes both cells. */
void gravity_interact_cells(struct parts *p, const struct cell *ci, const struct cell *cj,
                            struct gravity_cell *gc, const struct gravity_props *gp);

/** The near pair of top-level cells ci and cj walked one way: the same
 *  interactions as gravity_interact_cells (its decisions are symmetric in
 *  the two cells), received by ci only; writes ci only.  Several MPI
 *  ranks: the pair of an owned cell and a cell of copies, whose other
 *  half the copies' owner walks (src/mpi/halo.h). */
void gravity_interact_pair_one_way(struct parts *p, const struct cell *ci, const struct cell *cj,
                                   struct gravity_cell *gc, const struct gravity_props *gp);

/** A top-level cell of another MPI rank as the walks of this rank read
 *  it (gp->remote): its owner's multipole, a_min, h_support, bounding box,
 *  particle count and split flag of this step (src/mpi/halo.c sends them
 *  each step, gravity_top_record_pack).  Its particles are here only where
 *  this rank may have to open it (complete); the far field of the others
 *  comes from the record alone (theory/mpi.md, "Self-gravity on several
 *  ranks"). */
struct gravity_remote {
  struct gravity_multipole mp;
  double a_min, h_support;
  double bmin[3], bmax[3];
  long long count;
  int split;
  int complete; /**< 1: every particle of the cell is on this rank (a copy) */
};

/** Long-range interactions of top-level cell ci: every non-empty cell of
 *  tops[0..nr_top) other than ci that is not near ci acts on ci (one-way
 *  walk: M2L at the top when the criterion accepts).  Writes ci only.
 *  Several MPI ranks (gp->remote_idx): a cell of another rank acts through
 *  its record (struct gravity_remote) wherever the walk does not open it;
 *  where it must be opened, through its particles if they are here, else
 *  through its multipole all the same, counted as a miss
 *  (gravity_remote_misses). */
void gravity_long_range(struct parts *p, const struct cell *ci, const struct cell *tops, int nr_top,
                        struct gravity_cell *gc, const struct gravity_props *gp);

/** Whether gravity_long_range with gp->remote_only walks anything for ci
 *  (an other rank's cell whose particles are not all here, not near ci):
 *  where it does not, ci's field tensors stay zero and its grav_down has
 *  nothing to push. */
int gravity_remote_reads(const struct cell *ci, const struct gravity_props *gp);

/** L2L down c's octree and L2P to its particles (into ga and pot), then
 *  the particles' ga and pot. */
void gravity_down(struct parts *p, const struct cell *c, struct gravity_cell *gc,
                  const struct gravity_props *gp);

/* gravity_top_pair_is_near: 1 if top-level cells ci and cj should interact in a pair task: their
 *  boxes fail the opening criterion (radius: half-diagonal of the particles'
 *  bounding box at the rebuild; distance between box centres).  It must give
 *  the same answer from one rebuild to the next: the pair tasks are made
 *  with it when the graph is built and the long-range tasks skip, with it,
 *  the pairs that have one.  (It once grew the boxes by dx_max, which grows
 *  between rebuilds: pairs that turned "near" after the rebuild then had no
 *  pair task and were skipped by the long-range task, so that collapsing
 *  bodies lost part of their gravity and energy drifted by ~1% in the
 *  Evrard test.)  The walks stay exact for any classification: they apply
 *  the acceptance criterion to the current multipoles at every level.
 *  Declared by the registry (TASK_FAMILY_ENTRIES): the engine builds the
 *  graph with it. */

/** The whole tree method without tasks, in the order the task graph runs
 *  it: gravity_estimate (when needed), up for every top-level cell, self
 *  and near pairs, long range, down.  For tests and a serial fallback. */
void gravity_tree_all(struct parts *p, const struct cell *tops, int nr_top, struct gravity_cell *gc,
                      const struct gravity_props *gp);

/** Opening angle and highest expansion order of gravity_estimate's pass. */
#define GRAVITY_ESTIMATE_THETA 0.8
#define GRAVITY_ESTIMATE_ORDER 2
/** Particles above which a cell of gravity_estimate's walks is shared among
 *  the threads as its octants (targets of at most this many). */
#define GRAVITY_ESTIMATE_UNIT 20000

/** 1 if the adaptive criterion (epsilon_fmm > 0, tree, full evaluation)
 *  lacks its scale: some particle has ga = 0 (a run's first step). */
int gravity_estimate_needed(const struct parts *p, const struct gravity_props *gp);

/** A run's first evaluation gives the adaptive criterion the scale it
 *  lacks (theory/gravity.md, "The first evaluation"): when
 *  gravity_estimate_needed, one cheaper pass (the geometric criterion at
 *  GRAVITY_ESTIMATE_THETA, order at most GRAVITY_ESTIMATE_ORDER, every top-level
 *  cell, or its octants down to GRAVITY_ESTIMATE_UNIT particles, gathering
 *  its interactions one way, over nthreads POSIX threads)
 *  sets every particle's ga and pot, whose |ga| the following full
 *  evaluation's gravity_up reads as a_min.  Returns 1 if it ran.
 *  gravity_tree_all calls it first (one thread); the engine before its
 *  first FORCE phase. */
int gravity_estimate(struct parts *p, const struct cell *tops, int nr_top, struct gravity_cell *gc,
                     const struct gravity_props *gp, int nthreads);

/** Exact O(N^2) summation over all pairs (Gravity:direct, and the reference
 *  of the tests): sets ga and pot.  nthreads > 1
 *  splits the work over POSIX threads (gather form). */
void gravity_direct(struct parts *p, double G, double eps, int softening, int nthreads);

/** gravity_direct with the softening tied to h when h_factor > 0 (pair
 *  softening gravity_pair_softening; spline kernel). */
void gravity_direct_h(struct parts *p, double G, double eps, int softening, double h_factor,
                      int nthreads);

/** Interactions of one kind recorded by the walks for the GPU
 *  (gravity_gpu_record): entry k acts on cell target[k] from source[k],
 *  both cell indices (struct cell.index); a negative source -1 - s names
 *  cell s as the other kind of source (below). */
struct gravity_rec_list {
  size_t n, cap; /**< entries recorded and allocated */
  int *target;   /**< receiving cell */
  int *source;   /**< acting cell (>= 0) or -1 - cell (< 0) */
};

/** What a walk records instead of computing, for the GPU
 *  (gpu_grav_run): everything but P2M, M2M (gravity_up) and the L2L and
 *  L2P of gravity_down.
 *    part:  the target is a leaf whose particles receive: source >= 0, the
 *           particles of leaf `source` (P2P; a leaf with itself: target ==
 *           source, a particle skips itself); source < 0, the multipole of
 *           cell -1 - source (M2P, gravity_m2p_p2l without P2L).
 *    field: the target is a cell whose local expansion receives: source
 *           >= 0, the multipole of cell `source` (M2L, one way: a
 *           symmetric M2L is recorded once in each direction); source < 0,
 *           the particles of leaf -1 - source (P2L of gravity_m2p_p2l).
 *  A mutual interaction (a symmetric walk's P2P of two leaves, or M2L of
 *  two cells) is recorded once, in part_sym or field_sym, and stands for
 *  (target, source) and (source, target): half the memory traffic.
 *  gpu_grav_group expands them. */
struct gravity_gpu_rec {
  struct gravity_rec_list part;      /**< interactions received by particles */
  struct gravity_rec_list field;     /**< interactions received by local expansions */
  struct gravity_rec_list part_sym;  /**< P2P of two distinct leaves, both receiving */
  struct gravity_rec_list field_sym; /**< M2L of two cells, both receiving */
};
/** The tree of the cells [0, nr_cells) (cells[k].index == k) as the
 *  walk of gravity_walk.h reads it: 8 progeny indices per cell (-1: none),
 *  particle counts, split flags. */
void gravity_walk_tree_arrays(const struct cell *cells, int nr_cells, int *progeny, int *count,
                              unsigned char *split);
/** From now on the calling thread's walks record their interactions in r
 *  (appending) instead of computing them; NULL: compute them again. */
void gravity_gpu_record(struct gravity_gpu_rec *r);
/** Free the arrays of r and zero it. */
void gravity_gpu_rec_free(struct gravity_gpu_rec *r);

/** Work counters of the tree walks (diagnostics), kept per thread. */
struct gravity_counters {
  unsigned long long mac; /**< cell pairs tested by the acceptance criterion */
  unsigned long long m2l; /**< accepted cell pairs (M2L) */
  unsigned long long p2p; /**< particle pairs summed directly (each pair once) */
  unsigned long long m2p; /**< particle-cell interactions (M2P/P2L of large leaves) */
};

/** Copy the calling thread's counters since its last reset into *out;
 *  reset them if reset. */
void gravity_counters_get(struct gravity_counters *out, int reset);

/* double gravity_potential_energy(const struct parts *p): potential energy
 * 1/2 sum_i m_i pot_i (pot from a complete gravity pass), declared by the
 * registry (TASK_FAMILY_ENTRIES). */

#endif
