/* The engine's side of the GPU runner: the scheduling policy
 * (Scheduler:gpu, --gpu/--no-gpu), the leaf cells and their neighbour lists
 * built from the space for each FORCE phase, and the phase itself. */
#ifndef BOLIDE_GPU_ENGINE_H
#define BOLIDE_GPU_ENGINE_H

/** Scheduler:cell_task_size when the GPU runs the whole FORCE phase (the
 *  serial runner with gravity's walks on the device, or no gravity) and
 *  the parameter file does not set it. */
#define GPU_CELL_TASK_SIZE 8000

#include "src/engine.h"
#include "src/gpu/gpu.h"

struct gpu_cells_job;
struct gpu_list_box;

/** Host-side leaf cells and neighbour lists, grown and reused between steps. */
struct gpu_cells {
  int n, cap;                    /**< leaves and allocated length */
  size_t *offset;                /**< first particle of each leaf */
  int *count;                    /**< particles of each leaf */
  int *top;                      /**< task cell of each leaf */
  double *h_cap;                 /**< the cells' cap on h of each leaf (its task cell's) */
  double *h_list_cap;            /**< largest h the lists cover */
  int *ngb_start;                /**< n + 1 */
  int nr_ngb, ngb_cap;           /**< list entries and allocated length */
  int *ngb_leaf;                 /**< neighbouring leaf of each entry */
  double *ngb_shift;             /**< 3 per entry */
  int *leaf_of_cell;             /**< leaf number of each cell of the space (-1: not a leaf) */
  int cells_cap;                 /**< allocated length of leaf_of_cell */
  double growth;                 /**< lists cover h up to growth * the leaf's h_max */
  double t_build;                /**< host seconds spent in gpu_cells_build */
  int nr_threads;                /**< host threads building the lists (0: 1) */
  int min_parallel;              /**< fewer particles: the host's part on one thread (0: 50,000) */
  struct gpu_cells_job *jobs;    /**< workers of the list build, kept between calls */
  int nr_jobs;                   /**< their number */
  long widenings;                /**< times h outgrew the lists (phase run again) */
  long long h_resummed;          /**< particles whose density sums the h iteration redid */
  long builds;                   /**< times the lists were built */
  const struct cell **leaf_cell; /**< the cell of each leaf */
  double *dx_allow;              /**< drift of each leaf up to which the lists hold */
  int built_rebuild;             /**< space.nr_rebuilds when the lists were built */
  struct cell *const *built_tcells; /**< the task cells they were built on */
  int built_nr;                     /**< their number */
  int leaf_size;                    /**< lists on cells of at most this many particles
                                         (Scheduler:gpu_leaf_size; 0: the tree's leaves) */
  int host_lists;                   /**< 1: build the lists on the host (gpu_cells_build,
                                         Scheduler:gpu_lists: host), 0: on the device */
  struct gpu_lists *dev;            /**< the device lists and their build (gpu_lists.h) */
  int *leaf_node;                   /**< node of each leaf (device build) */
  int nr_nodes;                     /**< nodes of the last device build */
  int *tc_node, *tc_ngb_start;      /**< by task cell + 1: first node, first neighbour */
  int tc_cap;                       /**< their allocated length */
  int *tc_ngb;                      /**< neighbouring task cells, all in one array */
  double *tc_ngb_shift;             /**< 3 per entry */
  int tc_ngb_cap;                   /**< allocated entries */
  struct gpu_list_box *box;         /**< bounds of each cell (host build) */
  int box_cap;                      /**< their allocated length */
};

/** Build the leaves below the task cells tcells[0..nr) (the engine's, or the
 *  top-level cells) and, for each leaf, the leaves of the neighbouring task
 *  cells ct[t] (numbers in tcells, with their shifts) whose bounding boxes
 *  come within growth * kernel_gamma * max(h_max) plus both drifts.
 *  tc_h_cap[t]: the largest h task cell t allows.  nr_threads host threads
 *  walk the trees (a dual walk per pair of task cells). */
void gpu_cells_build(struct gpu_cells *gc, const struct space *s, struct cell *const *tcells,
                     int nr, const struct engine_cell_tasks *ct, const double *tc_h_cap,
                     double growth, int nr_threads);
/** The same leaves and caps as gpu_cells_build, and the same lists built on
 *  the device g (gpu_lists.h), where they stay: gc->ngb_start, ngb_leaf
 *  and ngb_shift are not set (gpu_lists_download copies them back). */
void gpu_cells_build_dev(struct gpu *g, struct gpu_cells *gc, const struct space *s,
                         struct cell *const *tcells, int nr, const struct engine_cell_tasks *ct,
                         const double *tc_h_cap, double growth);
/** Free the arrays of gc. */
void gpu_cells_free(struct gpu_cells *gc);

/** Run one FORCE phase on the GPU g over the task cells tcells[0..nr) of s
 *  (neighbours ct): build the lists, run, and when some h outgrows them
 *  rebuild them wider and run again.  dmg: damage, grav: gravity in the
 *  kick (NULL or !enabled: none).  tc_dt_min[t]: the smallest new time
 *  step of task cell t; with time bins (gpu_set_bins) tc_sums[t] the
 *  earliest end of a step and the particles kicked (NULL: not wanted).  resident: as
 * gpu_force_phase.  Returns 1 if a smoothing length was capped by the cells (the space must be
 * rebuilt), else 0. */
int gpu_cells_force(struct gpu *g, struct gpu_cells *gc, struct parts *p, struct space *s,
                    struct cell *const *tcells, int nr, const struct engine_cell_tasks *ct,
                    const double *tc_h_cap, const struct hydro_props *hp,
                    const struct material_table *mats, const struct gpu_damage *dmg,
                    const struct gpu_gravity *grav, double dt_kick, int resident, double *tc_dt_min,
                    struct timeline_sums *tc_sums);

/** Choose where tasks run from Scheduler:gpu and --gpu/--no-gpu, set
 *  e->gpu when the FORCE phase goes to a device, and say so in one line. */
void gpu_engine_init(struct engine *e);
/** Before the CPU workers start (scheduler_init): where the run may use a
 *  GPU, tell the runner the node's GPUs (runner_near_devices), so that
 *  each rank's threads go to the cores nearest its own. */
void gpu_engine_near(const struct engine *e);
/** The FORCE phase of the engine on its GPU. */
void gpu_engine_force(struct engine *e);
/** The DRIFT phase on the GPU: kick1 and drift of the resident particles;
 *  positions and h come back, the cells' bounds are updated. */
void gpu_engine_drift(struct engine *e);
/** TimeIntegration:scheme rk2 and pc on the GPU (tasks/drift/drift_integrate.c):
 *  the device arrays of the step's start and records (gpu_rk_arrays: ny
 *  and nrec x nr doubles per particle) into *y0 and r[]; the step's start
 *  put back into the resident particles (drift_rk_restore). */
void gpu_engine_rk_arrays(struct engine *e, int ny, int nr, int nrec, double **y0, double **r);
void gpu_engine_rk_restore(struct engine *e, const double *y0, const double *r1);
/** The watchdog's checks on the device (engine.c; gpu_watchdog_*): keep
 *  the positions before the drift; after it, the first particle that moved
 *  more than width (-1: none; else the saved positions are copied into
 *  x0_host as x, y, z arrays); after the step, 1 if a field is Inf or NaN,
 *  a density negative or u negative where the material forbids it. */
void gpu_engine_watchdog_save(struct engine *e);
long gpu_engine_watchdog_moved(struct engine *e, double width, double *x0_host);
int gpu_engine_watchdog_check(struct engine *e);
/** Copy the particles back when the device has changed them (before
 *  statistics, snapshots, restart files and rebuilds). */
void gpu_engine_to_host(struct engine *e);
/** Before a rebuild: 1 if the particles stay on the device, which reorders
 *  them after space_rebuild (gpu_engine_rebuild_end; the host then reorders
 *  only the few fields it reads, Scheduler:gpu_rebuild); 0 if every field
 *  came back to the host (which uploads them again before the next phase). */
int gpu_engine_rebuild_begin(struct engine *e);
/** After space_rebuild when gpu_engine_rebuild_begin said 1. */
void gpu_engine_rebuild_end(struct engine *e);
/** The host changed the particles (rebuild, restart): upload before the next phase. */
void gpu_engine_host_modified(struct engine *e);
/** Print the GPU's timers. */
void gpu_engine_print(const struct engine *e, FILE *f);
/** Free the GPU state of the engine. */
void gpu_engine_free(struct engine *e);

#endif
