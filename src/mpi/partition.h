/* Domain decomposition: the top-level cells over ranks (issue 22,
 * theory/mpi.md).
 *
 * The graph: one vertex per top-level cell, weighted by its work (the
 * measured times of the tasks of its cells once the scheduler has run them,
 * before that an estimate from particle counts and the pairs the loops
 * test); one edge per pair of top-level cells that a pair task joins,
 * weighted by the particles such a task would need from the other rank,
 * plus a light edge between face neighbours of the grid, so that the graph
 * is connected and empty cells join a neighbour's rank.  METIS
 * (METIS_PartGraphKway) cuts it into parts of equal work with the least
 * communication; two naive splits, slabs of equal volume along x and Morton
 * ranges of equal work, are there to compare with and for builds without
 * METIS.
 *
 * Nothing here needs MPI: the serial build partitions and reports, so that
 * the decomposition is tested without mpirun (tests/unit/test_partition.c,
 * tests/program/test_partition.sh). */
#ifndef BOLIDE_PARTITION_H
#define BOLIDE_PARTITION_H

#include <stddef.h>
#include <stdio.h>

struct space;
struct scheduler;

/** How the cells are split. */
enum partition_method {
  partition_method_metis,  /**< METIS_PartGraphKway on the weighted cell graph */
  partition_method_morton, /**< contiguous ranges of the Morton order, equal work */
  partition_method_slabs,  /**< slabs of equal width along x (the naive split) */
};

/** The weighted graph of the top-level cells (CSR, both directions). */
struct partition_graph {
  int nr_cells;       /**< vertices: the top-level cells, in space.cells order */
  int cdim[3];        /**< the top-level grid */
  double *cost;       /**< [nr_cells] work of each cell (seconds if measured, else pair tests;
                           particles for the estimate without a task graph) */
  size_t *count;      /**< [nr_cells] particles of each cell */
  int *xadj;          /**< [nr_cells + 1] start of each vertex's edges in adj */
  int *adj;           /**< [xadj[nr_cells]] neighbouring cells */
  double *comm;       /**< [xadj[nr_cells]] particles exchanged per step if cut (0: grid edge) */
  int measured;       /**< 1: costs are measured task times; 0: the estimate */
  int nr_space_cells; /**< cells of the space (top-level and octree) */
  size_t *cell_count; /**< [nr_space_cells] particles of every cell */
  int nr_links;       /**< pairs of cells on two top-level cells that a pair task joins */
  int *link_cell;     /**< [2 nr_links] their cells (space.cells indices) */
  int *link_top;      /**< [2 nr_links] their top-level cells */
  double total_cost;
  double total_comm; /**< sum of comm over the edges, each edge once */
  int *ijk;          /**< [3 nr_cells] grid coordinates of the vertices when the graph lists only
                          some cells of the grid (partition_graph_counts); NULL: every cell, in
                          space.cells order */
};

/** A partition and what it costs. */
struct partition {
  int nr_ranks;
  enum partition_method method;
  int *rank;          /**< [nr_cells] rank of each top-level cell */
  double *rank_cost;  /**< [nr_ranks] work of each rank */
  size_t *rank_parts; /**< [nr_ranks] particles of each rank */
  int *rank_cells;    /**< [nr_ranks] top-level cells of each rank (empty ones included) */
  double *rank_halo;  /**< [nr_ranks] particles the rank receives per step (cut comm) */
  int *rank_pieces;   /**< [nr_ranks] connected pieces of the rank's non-empty cells */
  double imbalance;   /**< max rank cost / mean rank cost */
  double edge_cut;    /**< comm of the edges between ranks, each edge once */
  int max_pieces;     /**< largest rank_pieces */
  int unassigned;     /**< cells without a valid rank (must be 0) */
  int fallback;       /**< METIS: 1 when the Morton ranges were taken, 5% better balanced */
};

/** The graph of the top-level cells of s from the tasks of sched (their
 *  cells are struct cell *, NULL for tasks without a cell): a task's cost
 *  goes to the top-level cell of its first cell, half to each for a pair
 *  across two top-level cells, which also adds the particles of both its
 *  cells to their edge.  measured: 1 takes the tasks' measured times
 *  (task.cost after a scheduler_run), 0 the estimate, in the pair tests of
 *  the loops (tasks/iact_loop.h): a self task on n particles n (n - 1) / 2,
 *  a hydro pair task n_i + n_j (every particle against the other cell's
 *  box) plus the product of the particles of each cell within a kernel
 *  support of the other's box, a gravity pair task n_i n_j, a task on one
 *  cell PARTITION_PER_PARTICLE per particle (calibrated on hydro only).
 *  sched NULL: the estimate from the top-level cells alone, their
 *  particles (each costs about the same; the edges are those of a pair
 *  task per pair of neighbouring non-empty cells). */
void partition_graph_make(struct partition_graph *g, const struct space *s,
                          const struct scheduler *sched, int measured);

/** Free the graph's arrays. */
void partition_graph_free(struct partition_graph *g);

/** Pair tests that one particle's work in a task on one cell (drift, ghost,
 *  kick, multipoles) is counted as in the estimate: on the reference impact
 *  (2026-12-03, BENCHMARKS.md) the drift, ghost and kick of a particle took
 *  69, 292 and 35 times a self loop's pair test, 130 on average. */
#define PARTITION_PER_PARTICLE 130.0

/** The particles of a run's top-level cells without the particles
 *  (tools/bench/impact_counts.py writes them; theory/mpi.md, "Scaling on
 *  paper"): each non-empty cell's count, which neighbours its pair tasks
 *  join, and per particle the neighbours within the kernel support, as
 *  counts of (cell, mask of 26 neighbour bits). */
struct partition_counts {
  int cdim[3];
  double support;     /**< kernel support H */
  int loops;          /**< pair loops per pair of cells (density, force: 2) */
  int cell_tasks;     /**< tasks on one cell counted PARTITION_PER_PARTICLE each */
  size_t particles;   /**< total, as the file says */
  int nr_cells;       /**< non-empty cells listed */
  int *ijk;           /**< [3 nr_cells] */
  size_t *count;      /**< [nr_cells] */
  int *pairmask;      /**< [nr_cells] bit d: a pair with neighbour d (d = 9(oi+1)+3(oj+1)+ok+1) */
  int *nbr;           /**< [27 nr_cells] vertex of neighbour d, -1: none or no pair */
  size_t nr_masks;    /**< rows of (cell, mask, count) */
  int *mask_cell;     /**< [nr_masks] */
  int *mask_bits;     /**< [nr_masks] neighbours within the support of these particles */
  size_t *mask_count; /**< [nr_masks] */
  double *near;       /**< [27 nr_cells] particles of the cell within the support of neighbour d */
};

/** Read a counts file; exits with one line naming the file on an error. */
void partition_counts_read(struct partition_counts *pc, const char *file);
void partition_counts_free(struct partition_counts *pc);

/** The graph of the listed cells with the estimated costs of
 *  partition_graph_make's task loop, every top-level cell taken as one task
 *  cell: loops * (n(n-1)/2 + the halves of its pairs' n_i + n_j + b_i b_j)
 *  + cell_tasks * PARTITION_PER_PARTICLE * n. */
void partition_graph_counts(struct partition_graph *g, const struct partition_counts *pc);

/** What each rank receives per exchange: `layer[r]`, the particles of other
 *  ranks' cells within the support of one of r's cells (each particle once
 *  per rank; the halo of partition_stats counts whole cells), `sent[r]`
 *  the particles r sends (once per receiving rank), `peers[r]` the ranks r
 *  shares a pair task with. */
void partition_exchange(const struct partition *p, const struct partition_counts *pc, double *layer,
                        double *sent, int *peers);

/** 1 if this build can partition with METIS (configure found libmetis). */
int partition_have_metis(void);

/** Split g over nr_ranks with method (METIS in a build without it stops
 *  with a one-line error) and fill the statistics of p. */
void partition_make(struct partition *p, const struct partition_graph *g, int nr_ranks,
                    enum partition_method method);

/** Fill the statistics of p from p->rank (after changing it by hand). */
void partition_stats(struct partition *p, const struct partition_graph *g);

/** Free the partition's arrays. */
void partition_free(struct partition *p);

/** Name of a method ("metis", "morton", "slabs"); and back (-1: unknown). */
const char *partition_method_name(enum partition_method m);
int partition_method_parse(const char *name);

/** Print one line of totals for p: method, ranks, imbalance, edge cut,
 *  pieces; with per_rank one line per rank too. */
void partition_print(const struct partition *p, const struct partition_graph *g, int per_rank,
                     FILE *f);

#endif
