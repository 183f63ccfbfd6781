/* The engine: the time-step loop.  Each step: kick and drift the cells,
 * rebuild the cells and the task graph when particles have moved too far,
 * run the density -> ghost [-> gradient -> extra_ghost] -> force ->
 * kick/time-step graph (the bracket only with solids), write
 * statistics and snapshots. */
#ifndef BOLIDE_ENGINE_H
#define BOLIDE_ENGINE_H

#include <stdio.h>

#include "src/cell.h"
#include "tasks/gravity/gravity_props.h"
#include "tasks/hydro/hydro_props.h"
#include "src/part.h"
#include "src/scheduler.h"
#include "src/space.h"
#include "src/timeline.h"
#include "src/io/restart.h"
#include "src/io/units.h"

struct params;
struct material_table;
struct gpu_engine;

/** Command-line choices that shape the run. */
struct engine_options {
  int nr_threads; /**< CPU workers (0: every allowed core) */
  long max_steps; /**< stop after this many steps (-1: no limit) */
  int use_gpu;    /**< 0 never, 1 when present, 2 required */
  int check_only; /**< validate and exit */
  int restart;    /**< resume from a restart file */
  int one_rank;   /**< 1: this process's engine alone, whatever the MPI ranks (bolide --partition
                       on rank 0): no multi-rank run */
};

/** Tasks of one task cell (engine_graph.c: the graph is built on these). */
struct engine_cell_tasks {
  struct task *drift;       /**< kick1 + drift of the cell */
  struct task *ghost;       /**< h iteration and equation of state */
  struct task *extra_ghost; /**< end of the gradient loop (solids only, else NULL) */
  struct task *kick2;       /**< second half kick and new time step */
  struct task
      *force_done; /**< what the force tasks unlock: the first chain task (damage), else kick2 */
  int nr_ngb;      /**< number of neighbouring task cells (itself included) */
  int ngb_cap;     /**< allocated length of ngb and ngb_shift */
  int *ngb;        /**< their numbers in engine.tcells */
  double (*ngb_shift)[3]; /**< periodic shift to add to the neighbour's positions */
};

/** Pair tasks join task cells closer than this many times the largest kernel
 *  support at the rebuild: the margin for h to grow and particles to move
 *  before the next rebuild. */
#define ENGINE_REACH_FACTOR 1.5

/** TimeIntegration:scheme (tasks/drift/drift_integrate.c, theory/integrators.md). */
enum engine_scheme { ENGINE_SCHEME_KDK = 0, ENGINE_SCHEME_RK2 = 1, ENGINE_SCHEME_PC = 2 };

struct drift_stage;
struct drift_integrator;

/** Phases of a step: which tasks a scheduler_run activates. */
enum engine_phase { ENGINE_PHASE_DRIFT = 0, ENGINE_PHASE_FORCE = 1 };

/** The whole state of a run. */
struct engine {
  const struct params *params; /**< the run's parameters */
  struct engine_options opt;   /**< command-line choices */
  struct unit_system us;       /**< internal units */
  struct hydro_props hp;       /**< SPH settings */
  struct material_table *mats; /**< materials by id */
  struct parts parts;          /**< the particles */
  struct space space;          /**< cells */
  struct scheduler sched;      /**< tasks and workers */
  int nr_threads;              /**< workers in use */

  struct cell **tcells;         /**< the task cells (engine_graph.c) */
  int nr_tcells;                /**< their number */
  int cell_task_size;           /**< Scheduler:cell_task_size */
  int grav_task_size;           /**< Scheduler:gravity_task_size */
  double reach;                 /**< task cells closer than this have pair tasks */
  int damage;                   /**< 1 when a material is brittle (tasks/damage) */
  double *flaw_eps;             /**< every particle's flaw thresholds, one flat array */
  int64_t nr_flaws;             /**< their number */
  const char *flaws_from;       /**< where they came from (log), NULL: Damage:seed */
  double damage_max_change;     /**< Damage:max_change */
  double damage_start;          /**< Damage:start_time: no damage before it */
  int porous;                   /**< 1 when a material has a porosity model */
  struct gravity_props gp;      /**< self-gravity settings (gp.enabled) */
  struct gravity_state *grav;   /**< self-gravity's state: the cells' multipoles and
                                     expansions, the interaction lists, the far field
                                     that steps reuse (tasks/gravity, through the
                                     registry's hooks and entry points) */
  struct sched_lock *glocks;    /**< per top-level cell: taken by gravity tasks writing it */
  struct sched_lock *gsublocks; /**< by cell index: taken by the split self-gravity tasks */
  struct task **grav_down;      /**< per top-level cell: its gravity_down task (or NULL) */
  int *tcell_top;               /**< top-level cell of each task cell */
  struct engine_cell_tasks *ct; /**< per task cell */
  int nr_ct;                    /**< number of entries of ct */
  struct task **phase_tasks[2]; /**< tasks of each phase */
  int phase_count[2];           /**< their numbers */
  struct space_pair *pairs;     /**< pairs of task cells (numbers in tcells, periodic shift) */
  int nr_pairs;                 /**< their number */
  int *task_pair;               /**< pair number of each pair task, by task id */
  double *cell_dt_min;          /**< smallest new time step per task cell */
  struct timeline timeline;     /**< integer time line of the run (src/timeline.h) */
  int64_t *cell_bins;           /**< per task cell, TIMELINE_NR_BINS + 1 counts of its particles by
                                     the time bin of their own limit (CPU kick; issue 20) */
  int64_t bins[TIMELINE_NR_BINS + 1]; /**< the sum of cell_bins after the last step */
  double bin_updates;       /**< sum over the CPU steps of this process of the particle updates
                                 that time bins would have done (timeline_active_fraction) */
  double bin_all;           /**< and of the particle updates done */
  int individual;           /**< TimeIntegration:global_step false: individual time steps in
                                 time bins (drift_cell_bins_cpu, kick2_cell_bins_cpu) */
  integertime_t ti_current; /**< with individual steps: the time on the time line */
  integertime_t ti_next;    /**< and the end of the step being taken (the drift's target) */
  struct timeline_sums *cell_kick; /**< per task cell, what its kick with bins left */
  int64_t nr_active;               /**< particles kicked at the end of the last step */
  int need_rebuild;                /**< set by tasks (atomic): h outgrew the cells */
  int first_force;                 /**< 1 while computing the initial forces */
  int scheme;                      /**< TimeIntegration:scheme (enum engine_scheme) */
  int stage_eval; /**< 1 while evaluating a stage of an rk2/pc step that is not its end: the
                       damage does not grow (it grows once, over the step, at its end) */
  const struct drift_stage *stage; /**< the stage the drift tasks put (rk2/pc), NULL: kdk */
  double *stage_err;           /**< per task cell, the largest error estimate of its drift (rk2) */
  struct drift_integrator *rk; /**< the rk2/pc integrator's state (tasks/drift/drift_integrate.c) */
  double t_eval;            /**< wall seconds of the steps' FORCE phases (derivative evaluations) */
  long nr_eval;             /**< their number */
  long long h_resummed;     /**< particles whose density sums the h iteration redid in the
                                 steps' evaluations (CPU ghosts, atomic; the GPU's phases add
                                 their count), the initial forces not counted */
  double t_rebuild;         /**< wall seconds of the rebuilds (cells, sort, task graph) */
  double t_rebuild_part[3]; /**< of which: particles back from the GPU, space_rebuild, task graph */
  double
      t_rebuild_first[4]; /**< the first rebuild (the file's order sorted): its total and parts */
  long nr_rebuild;        /**< rebuilds, the first one included */

  double time;           /**< current simulation time */
  double time_end;       /**< end of the run */
  double dt;             /**< current global time step */
  double dt_min, dt_max; /**< limits */
  long step;             /**< steps done */
  long long updates;     /**< particle updates so far */
  long long nr_removed;  /**< particles that left an open box */

  char outdir[1024];       /**< folder of snapshots and statistics */
  char snap_basename[256]; /**< snapshot prefix */
  double *out_times;       /**< snapshot times */
  int nr_out, next_out;    /**< their count and the next to write */
  int snap_index;          /**< index of the next snapshot file */
  int write_acc;           /**< Snapshots:accelerations */
  int snap_enabled;        /**< Snapshots:enabled */
  int compression;         /**< gzip level */
  char *params_text;       /**< the parameters in use, for snapshots */

  int restarts;             /**< Restarts:enable */
  double restart_dt_wall;   /**< seconds of wall time between restart files */
  double restart_last_wall; /**< wall time of the last restart file */
  char restart_dir[1024];   /**< Restarts:subdir */
  char restart_stem[1300];  /**< Restarts:subdir/Restarts:basename: the files are STEM.bin,
                                 STEM.prev.bin (restart.h) */
  long restart_stop_steps;  /**< Restarts:stop_steps: steps between looks for the stop file */
  int restarted;            /**< 1 when this run resumed from a restart file */
  char restart_base[1300];  /**< Restarts:subdir/Restarts:basename, without a rank's suffix */
  int restart_regrouped;    /**< resumed from the files of a run on another number of ranks
                                 (restart_read_ranks): the cells, the decomposition and the
                                 exchange lists are made anew */
  int restart_layout_done;  /**< the files of other layouts removed after the first restart
                                 file this run wrote (restart_remove_layouts) */
  double restart_dt_next;   /**< smallest particle time step saved in the restart file */
  double
      restart_h_max; /**< > 0: the first rebuild restores the cells of the file (space_restore) */
  struct restart_cells restart_cells; /**< the cells' h_max and dx_max from the file */
  char restart_file[4096];            /**< the restart file this run resumed from */
  char input_file[4096]; /**< the file the particles were read from: the initial conditions, or
                              the restart file this run resumed from */
  double *wd_x;          /**< watchdog: positions before the drift of the step (3 per particle) */
  double t_watchdog;     /**< wall seconds of the watchdog's checks */
  long wd_inject_step;   /**< BOLIDE_TEST_INJECT: step whose end gets a bad value (0: none) */
  char wd_inject_field[32];  /**< its particle field */
  double wd_inject_value;    /**< its value */
  long restart_delta_steps;  /**< Restarts:delta_steps */
  double restart_max_wall;   /**< Restarts:max_run_time in seconds (0: none) */
  long restart_stats_offset; /**< length of the statistics file when the restart file was written */

  struct budget_start budget0; /**< totals at the start of the run (engine_io.c) */
  FILE *stats;                 /**< statistics file */
  long stats_last_step;        /**< step of its last line (-1: none yet) */
  FILE *timesteps;             /**< timesteps file: one line per step */
  double stats_dt, next_stats; /**< its interval */
  long dump_tasks;             /**< dump a task timeline every this many steps */
  double wall_start;           /**< wall time at the first step */
  struct gpu_engine *gpu;      /**< the GPU runner (src/gpu/gpu_engine.h), NULL: CPU only */
  int nr_planes;          /**< mirror planes of Boundaries:planes (tasks/drift/drift_mirror.c) */
  double planes[8][6];    /**< each: a point and the unit normal into the domain */
  int mirror_no_slip;     /**< Boundaries:slip: no_slip */
  size_t nr_mirror;       /**< mirror ghosts among the particles (PART_MIRROR) */
  struct halo *halo;      /**< MPI: the domain and the foreign copies (src/mpi/halo.c); NULL with
                               one rank */
  size_t nr_foreign;      /**< foreign copies among the particles (PART_FOREIGN) */
  long long nr_owned_all; /**< particles owned by every rank together (the count the run reports) */
};

/** Read everything (units, materials, initial conditions), build the cells,
 *  write used_parameters.yml.  Stops with an error on bad input. */
void engine_init(struct engine *e, const struct params *params, const struct engine_options *opt);
/** Run to TimeIntegration:time_end or the step limit. */
void engine_run(struct engine *e);
/** Free everything. */
void engine_clean(struct engine *e);

/** With individual time steps, whether the tasks of a cell have nothing to
 *  do in this step's FORCE phase: none of its particles ends its step
 *  (c->active, counted by the drift, engine_count_active_cells after a
 *  rebuild).  Never with the global step nor at the first force
 *  computation. */
#define ENGINE_CELL_IDLE(e, c) \
  ((e)->individual && !(e)->first_force && !((const struct cell *)(c))->active)

/** ENGINE_CELL_IDLE, or (several MPI ranks, src/mpi/halo.c) a cell of
 *  foreign copies only: no copy needs its own sums, forces, drift or kick,
 *  it takes its owner's state before every FORCE phase and between its
 *  stages.  A pair task runs unless both its cells are skipped. */
#define ENGINE_CELL_SKIP(e, c) (ENGINE_CELL_IDLE(e, c) || ((const struct cell *)(c))->foreign)

#endif
