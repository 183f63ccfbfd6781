/* The gravity family's state in a run: what struct engine holds behind its
 * pointer e->grav (tasks/gravity/gravity_props.h declares it opaque).  The
 * family's tasks (gravity_task.c), its part of the engine's rebuild,
 * restart and step loop (gravity_engine.c) and its part of the GPU runner
 * (gpu_gravity_runner.c) read it; src/ does not. */
#ifndef BOLIDE_GRAVITY_STATE_H
#define BOLIDE_GRAVITY_STATE_H

#include "src/io/restart.h"
#include "tasks/gravity/gravity_cpu.h"

/** Self-gravity's data of a run. */
struct gravity_state {
  struct gravity_cell *cells;     /**< gravity data of every cell, by cell index */
  int cells_cap;                  /**< its allocated length */
  unsigned char *active;          /**< per cell, whether it receives on a step of active
                                       particles only (gravity_active_decide; cells_cap long) */
  long active_steps;              /**< steps of the run that computed gravity only for the
                                       particles that end their step */
  struct gravity_ilist *lists;    /**< interaction list of each gravity task, by task id
                                       (Gravity:reuse_steps > 0; else NULL) */
  int nr_lists;                   /**< their number */
  double *x0;                     /**< positions at the last full gravity evaluation (reuse) */
  double d_min;                   /**< shortest far-field distance of that evaluation */
  int reused;                     /**< steps since it that reused its far field */
  long replays;                   /**< steps of the run that reused the far field */
  struct restart_gravity restart; /**< the far field read from the restart file, restored
                                       after the first rebuild (restart.present 0: none) */
  struct gravity_remote *remote;  /**< several MPI ranks: the other ranks' top-level cells
                                       (gravity_top_records_use; gp.remote) */
  int *remote_idx;                /**< per top-level cell, its entry of remote or -1 */
  int *remote_partial;            /**< the top-level cells of remote whose particles are not
                                       all here, in increasing order (gp.remote_partial) */
  struct gravity_back back;       /**< several MPI ranks with the walks on the GPU: the device's
                                       upward pass of every cell (only the top-level cells are in
                                       cells); a long-range task with gp.remote_only fills its
                                       cell's tree from it where it walks (back.mp NULL: none) */
  int *tops_used;                 /**< gp.tops_used (gravity_tops_used_update) */
  int tops_used_cap;              /**< its allocated length */
  int remote_cap, remote_idx_cap; /**< their allocated lengths (remote_partial: remote_cap) */
};

#endif
