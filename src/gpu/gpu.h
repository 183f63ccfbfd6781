/* The GPU runner: one CUDA device holding the particle arrays and running
 * the FORCE phase of a step (density -> ghost -> force -> kick2/time step)
 * as batched kernels over every leaf cell (theory/architecture.md, "CPU and
 * GPU").
 *
 * The interface is C; the implementation (src/gpu/gpu.cu and the kernels
 * in tasks/<name>/<name>_gpu.cu) is CUDA C++ calling the same inline pair
 * functions and material models as the CPU loops.  Device memory is
 * allocated once and grown, never per step; every CUDA call is checked
 * (gpu_check.h).  Built only when configure finds nvcc (HAVE_CUDA). */
#ifndef BOLIDE_GPU_H
#define BOLIDE_GPU_H

#include <stddef.h>
#include <stdio.h>

#include "tasks/gravity/gravity_cpu.h"
#include "tasks/hydro/hydro_props.h"
#include "src/part.h"

#ifdef __cplusplus
extern "C" {
#endif

struct material_table;
struct gpu_lists;
/** A device with its streams, buffers and timers (opaque). */
struct gpu;

/** The batch of one FORCE phase, as host arrays: the leaf cells (each one
 *  contiguous particle range) and, for each leaf, the leaves (with periodic
 *  shifts) that its particles can interact with. */
struct gpu_leaves {
  int n;                    /**< number of leaves */
  const size_t *offset;     /**< first particle of each leaf */
  const int *count;         /**< particles of each leaf */
  const double *h_cap;      /**< largest h the top-level cells allow (capped: rebuild) */
  const double *h_list_cap; /**< largest h the neighbour lists below cover */
  const int
      *ngb_start;      /**< n + 1 entries: leaf L's neighbours are [ngb_start[L], ngb_start[L+1]) */
  const int *ngb_leaf; /**< neighbouring leaf of each entry (the leaf itself included) */
  const double *ngb_shift;       /**< 3 per entry: added to the neighbour's positions */
  int nr_ngb;                    /**< number of entries */
  const struct gpu_lists *lists; /**< non-NULL: the lists were built on the device
                                      (gpu_lists.h); ngb_start, ngb_leaf and ngb_shift
                                      above are then unused */
};

/** Damage in a FORCE phase (brittle materials, tasks/damage). */
struct gpu_damage {
  int enabled;       /**< run the damage task after the forces (flaws: gpu_set_flaws) */
  double dt;         /**< step over which damage grows (0 at the first force computation) */
  double max_change; /**< Damage:max_change, the time-step limit */
};

/** Self-gravity in a FORCE phase: the gravitational accelerations (gax,
 *  gay, gaz, complete on the device: gpu_grav_run) join the
 *  hydrodynamic ones in the kick, and their time-step criterion joins. */
struct gpu_gravity {
  int enabled;     /**< add ga in the kick */
  double eps;      /**< softening (time step criterion when > 0) */
  double eta;      /**< Gravity:eta */
  double h_factor; /**< Gravity:softening_h_factor (time step criterion with eps_i = h_factor h_i
                      when > 0) */
};

/** What a FORCE phase reports besides the particle fields. */
struct gpu_force_out {
  int capped;     /**< some h hit the top-level cells' cap: rebuild */
  int overflow;   /**< some h outgrew h_list_cap: rebuild the lists and call again
                       (h was copied back, everything else is unchanged) */
  int iterations; /**< rounds of the h iteration */
};

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

/** Find a CUDA device (cudaGetDeviceCount) and set it up; NULL when there
 *  is none, with the reason in why. */
struct gpu *gpu_init(char *why, size_t len);
/** "NVIDIA H100 80GB HBM3 (132 SMs, 79.1 GiB)" */
const char *gpu_name(const struct gpu *g);
/** Copy the flat array of Weibull flaw thresholds (n of them, indexed by the
 *  particles' flaw_first) to the device, where the damage kernel reads it;
 *  again whenever the array changes. */
void gpu_set_flaws(struct gpu *g, const double *eps, size_t n);
/** Run the FORCE phase on the particles p: density, h iteration (repeating
 *  the density sums of unconverged particles), equation of state, with
 *  solids (hp->solids) the gradient loop and the extra ghost (plasticity,
 *  dS/dt), forces, with dmg->enabled the damage update, second half kick by
 *  dt_kick (with grav->enabled adding the gravitational acceleration already
 *  on the device) and new time steps.  resident = 0: copy what
 *  the loops read to the device first and the results back after;
 *  resident = 1: the device arrays are current (gpu_upload_all), nothing
 *  but the leaf time steps comes back.  leaf_dt_min[L]: smallest new time
 *  step of leaf L.  A particle whose h does not converge in
 *  hp->max_iterations stops the run with an error. */
void gpu_force_phase(struct gpu *g, struct parts *p, const struct gpu_leaves *lv,
                     const struct hydro_props *hp, const struct material_table *mats,
                     const struct gpu_damage *dmg, const struct gpu_gravity *grav, double dt_kick,
                     double *leaf_dt_min, int resident, struct gpu_force_out *out);
/** Have gpu_force_phase call fn(ctx) before its kick reads ga, and before
 *  it writes the host's h when the lists overflow (fn NULL: nothing).  The
 *  hybrid runner's hook: it waits there for the self-gravity computed
 *  beside the phase (CPU tasks), then completes ga on the device (the
 *  device part of gravity on stream 0, or gpu_upload_gravity). */
void gpu_set_kick_wait(struct gpu *g, void (*fn)(void *), void *ctx);
/** Copy gax, gay, gaz and pot of the resident particles from the host to
 *  the device on stream 0 (self-gravity computed on the CPU). */
void gpu_upload_gravity(struct gpu *g, struct parts *p);
/** Let host threads waiting for the device sleep instead of spinning (the
 *  hybrid runner: the CPU workers need the cores).  Returns 0 when the
 *  driver refuses (the waits then keep spinning). */
int gpu_set_blocking_sync(struct gpu *g);
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
 *  order: as struct gravity_props. */
void gpu_grav_walk(struct gpu_grav *gg, const double *lo_hi, int nr_top, double theta,
                   double h_support, double G, double epsilon_fmm, double h_factor, int order);
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
/** Print the accumulated times of the gravity kernels. */
void gpu_grav_print(const struct gpu_grav *gg, FILE *f);
/** Copy every particle field to the device (after a rebuild or a restart). */
void gpu_upload_all(struct gpu *g, const struct parts *p);
/** Copy every particle field back to the host (outputs, rebuilds). */
void gpu_download_all(struct gpu *g, struct parts *p);
/** First half kick by dt_kick and drift by dt of the resident particles;
 *  copy back the positions and smoothing lengths (what the CPU needs to
 *  decide on a rebuild and to build the neighbour lists). */
void gpu_drift(struct gpu *g, struct parts *p, double dt_kick, double dt, double xsph, double h_max,
               int h_continuity);
/** The watchdog (engine.c) on the resident particles.  gpu_watchdog_save:
 *  keep the positions before the drift on the device (a device copy, queued
 *  before the drift).  gpu_watchdog_moved: after the drift, the first
 *  particle that moved more than width since (or whose displacement is
 *  not a number), -1 if none; when there is one, the saved positions are
 *  copied into x0_host (x of every particle, then y, then z).
 *  gpu_watchdog_check: 1 if a double field of a particle is Inf or NaN, a
 *  density is negative, or u is negative for a material whose id is one of
 *  u_floor_ids[0..n_ids) (the host then copies the particles back and names
 *  it).  Each check is one pass over the device arrays and a read of a few
 *  words. */
void gpu_watchdog_save(struct gpu *g);
long gpu_watchdog_moved(struct gpu *g, double width, double *x0_host);
int gpu_watchdog_check(struct gpu *g, const int32_t *u_floor_ids, int n_ids);
/** Unregister the pinned particle arrays (before they are freed). */
void gpu_unpin(struct gpu *g);
/** Print the accumulated time of each stage. */
void gpu_print_timers(const struct gpu *g, FILE *f);
/** Bytes copied host -> device and device -> host so far. */
void gpu_bytes_moved(const struct gpu *g, double *h2d, double *d2h);
/** Device memory the run holds now (in use minus what the context took at
 *  gpu_init) and the device's total, in bytes. */
void gpu_memory_used(const struct gpu *g, double *run, double *total);
/** Free everything. */
void gpu_free(struct gpu *g);

#ifdef __cplusplus
}
#endif

#endif
