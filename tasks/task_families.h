/* The registry of task families: one row per folder tasks/<family>/.
 *
 * Everything the engine, the scheduler and the GPU runner know about a
 * family comes from here (theory/architecture.md, rule 5, "one list, many
 * uses"):
 *
 *  - the task types and subtypes (src/task.h) and so the names of the
 *    timers and of the task dumps (tools/plot_tasks.py);
 *  - the CPU dispatch of the engine (src/engine_runtask.c): the function of
 *    each kind of task, tasks/<family>/<family>_task.c;
 *  - the families Scheduler:gpu can name, and which of them run on the GPU
 *    as one phase (src/gpu/gpu_policy.c);
 *  - the GPU FORCE phase (src/gpu/gpu.cu): its steps, their order, their
 *    timers and the particle fields each step reads and writes;
 *  - the build: tasks/families.am (tools/families_am.sh, run by autogen.sh
 *    and by Makefile.am when this file changes) includes each family's
 *    fragment tasks/<family>/local.am;
 *  - the graph, for a family of shape chain (below): its tasks between the
 *    force and the kick of every task cell (src/engine_graph.c);
 *  - what the engine has a family do outside its tasks, at points of its
 *    start-up and end (TASK_FAMILY_HOOKS, src/engine.c), the other
 *    functions of a family that src/ calls (TASK_FAMILY_ENTRIES), and the
 *    header of what the engine holds of a family, the one header of the
 *    family's folder that src/ may include (TASK_FAMILY_INTERFACES);
 *  - tests/repo/test_layers.py, which fails when a folder of tasks/, a fragment
 *    or a list of family names elsewhere disagrees with this list.
 *
 * A new per-particle family between the force and the kick is its folder
 * (tasks/<name>/: <name>_task.c, local.am), its two rows here and its test;
 * a family with other edges adds them in src/engine_graph.c.  Preprocessor
 * lists only: included by C and by CUDA C++. */
#ifndef BOLIDE_TASK_FAMILIES_H
#define BOLIDE_TASK_FAMILIES_H

/* clang-format off */

/* TASK_FAMILIES(X): X(name, subtype, policy, place, gpu, when, stage, reads, writes)
 *
 *  name     the folder tasks/<name>/, the prefix of its files, and the name
 *           Scheduler:gpu lists (src/io/param_list.h)
 *  subtype  SUB(s): the subtype its tasks carry (task_subtype_s), or NOSUB
 *  policy   HYDRO: on the GPU it runs in the hydrodynamic phase, so a list in
 *           Scheduler:gpu names it with the other HYDRO families; FREE: it
 *           may be named or not; CPU: it has no GPU implementation (not a
 *           name of Scheduler:gpu; a run where it has tasks stays on the CPU)
 *  place    its rank along a step's graph (engine_graph.c): drift first;
 *           self-gravity runs beside the hydrodynamics and joins before the
 *           kick.  The GPU FORCE phase runs its steps in this order.
 *  gpu      its step of the GPU FORCE phase (gpu_kernels.h: an int
 *           fn(struct gpu_phase *)), or NOSTEP: no step there (the drift
 *           has its own phase, gpu_drift)
 *  when     ALWAYS: the step runs in every phase; SOLIDS: only with a
 *           material with strength (hydro_props.solids); BRITTLE: only with
 *           damage
 *  stage    the name of that step's timer (gpu_print_timers)
 *  reads    the particle fields that step reads, (field, ...): copied to the
 *           device before the phase when the particles are not resident
 *  writes   the fields it writes, copied back after the phase
 *
 * The fields of a family whose step does not run in a phase (column when)
 * are not copied.  The solid
 * state (stress, strain, plastic work) is listed under gradient, the family
 * that solids add: the force and the kick read it only with solids. */
#define TASK_FAMILIES(X)                                                                          \
  X(drift, NOSUB, HYDRO, 0, NOSTEP, ALWAYS, "drift",                                              \
    (),                                                                                           \
    ())                                                                                           \
  X(density, SUB(density), HYDRO, 1, STEP(density_gpu_phase), ALWAYS, "density",                  \
    ("x", "y", "z", "vpx", "vpy", "vpz", "m", "h", "flags"),                                      \
    ("rho", "rho_dh", "wcount", "wcount_dh", "div_v", "curl_vx", "curl_vy", "curl_vz"))           \
  X(ghost, NOSUB, FREE, 2, STEP(ghost_gpu_phase), ALWAYS, "ghost",                                \
    ("up", "mat", "u", "rho_full", "rho_fp", "alpha", "alpha_p"),                                 \
    ("h", "P", "cs", "cl", "balsara", "f_gradh", "flags", "h_lo", "h_hi", "rho_full", "rho_fp"))  \
  X(gradient, SUB(gradient), HYDRO, 3, STEP(gradient_gpu_phase), SOLIDS,                          \
    "gradient(+extra ghost)",                                                                     \
    ("Sxx", "Sxy", "Sxz", "Syy", "Syz", "Szz", "Spxx", "Spxy", "Spxz", "Spyy", "Spyz", "Spzz",    \
     "eps_p", "dmg", "dmg_shear", "w_plastic"),                                                   \
    ("gmxx", "gmxy", "gmxz", "gmyy", "gmyz", "gmzz", "gvxx", "gvxy", "gvxz", "gvyx", "gvyy",      \
     "gvyz", "gvzx", "gvzy", "gvzz", "Sxx", "Sxy", "Sxz", "Syy", "Syz", "Szz", "Spxx", "Spxy",    \
     "Spxz", "Spyy", "Spyz", "Spzz", "dSxx", "dSxy", "dSxz", "dSyy", "dSyz", "dSzz", "Rxx",       \
     "Rxy", "Rxz", "Ryy", "Ryz", "Rzz", "eps_p", "dmg_shear", "w_plastic", "wvol"))               \
  X(force, SUB(force), HYDRO, 4, STEP(force_gpu_phase), ALWAYS, "force",                          \
    ("vx", "vy", "vz"),                                                                           \
    ("ax", "ay", "az", "du_dt", "drho_dt", "v_sig", "xsphx", "xsphy", "xsphz"))                   \
  X(damage, SUB(damage), HYDRO, 5, STEP(damage_gpu_phase), BRITTLE, "damage",                     \
    ("dmg", "dcbrt", "n_act", "n_flaws", "flaw_first"),                                           \
    ("dmg", "dcbrt", "n_act", "dmg_rate"))                                                        \
  X(kick, NOSUB, HYDRO, 7, STEP(kick_gpu_phase), ALWAYS, "kick2",                                 \
    ("e_clamp"),                                                                                  \
    ("vx", "vy", "vz", "u", "vpx", "vpy", "vpz", "up", "alpha", "alpha_p", "dalpha_dt",           \
     "e_clamp"))                                                                                  \
  X(gravity, SUB(grav), FREE, 6, STEP(gravity_gpu_phase), ALWAYS,                                 \
    "gravity(hybrid: wait + device part)",                                                        \
    (),                                                                                           \
    ())

/* TASK_FAMILY_TASKS(X): X(family, shape, type, subtype, cpu): the kinds of
 * task each family adds to the graph, and the CPU function that runs one
 * (void cpu(struct engine *, struct task *), in tasks/<family>/<family>_task.c).
 *
 *  shape    self (one cell), pair (two cells), cell (a task type of its
 *           own: one cell's bookkeeping, no neighbours), or chain(active):
 *           a cell type of its own that the engine places itself, one task
 *           per task cell between its force tasks and its kick (in registry
 *           order), in the runs where int active(const struct engine *) is
 *           1 (engine_graph.c); its edges then need no code of their own
 *  type     the task type (task_type_<type>): self, pair, or the cell type
 *  subtype  the task subtype (task_subtype_<subtype>), none for a cell type
 *           of a family without a subtype */
#define TASK_FAMILY_TASKS(X)                                                  \
  X(drift,    cell, drift,           none,     drift_task)                    \
  X(density,  self, self,            density,  density_self_task)             \
  X(density,  pair, pair,            density,  density_pair_task)             \
  X(ghost,    cell, ghost,           none,     ghost_task)                    \
  X(gradient, self, self,            gradient, gradient_self_task)            \
  X(gradient, pair, pair,            gradient, gradient_pair_task)            \
  X(gradient, cell, extra_ghost,     none,     extra_ghost_task)              \
  X(force,    self, self,            force,    force_self_task)               \
  X(force,    pair, pair,            force,    force_pair_task)               \
  X(damage,   chain(damage_active), damage, damage, damage_task)              \
  X(kick,     cell, kick2,           none,     kick2_task)                    \
  X(gravity,  cell, grav_up,         grav,     gravity_up_task)               \
  X(gravity,  self, self,            grav,     gravity_self_task)             \
  X(gravity,  pair, pair,            grav,     gravity_pair_task)             \
  X(gravity,  cell, grav_long_range, grav,     gravity_long_range_task)       \
  X(gravity,  cell, grav_down,       grav,     gravity_down_task)

/* TASK_FAMILY_HOOKS(X): X(family, when, fn): what a family does for the
 * engine outside its tasks: void fn(struct engine *), in
 * tasks/<family>/<family>_task.c (or <family>_engine.c), called by the
 * engine at point when (in this order, engine.c: engine_family_hooks), so
 * that src/ needs none of the family's headers for it.
 *
 *  when  init: at the start of engine_init, once the units and the SPH
 *          settings are read: the family reads its settings and makes its
 *          state (gravity: e->gp, e->grav)
 *        ic: after the initial conditions are read (not on a restart)
 *        start: after the particles are read, from the initial conditions
 *          or a restart file (e->restarted), and their smoothing lengths
 *          guessed; e->input_file names that file
 *        first_force: at the start of the first force computation
 *        rebuild_start, rebuild: before and after the space's rebuild (the
 *          cells and particles of the rebuild; not on a restart's)
 *        force: before every force computation (FORCE phase), after the
 *          drift and the rebuild
 *        clean: engine_clean, after the task graph is freed: the family
 *          frees its state */
#define TASK_FAMILY_HOOKS(X)                  \
  X(gravity, init,        gravity_engine_init)  \
  X(drift,   init,        drift_mirror_init)    \
  X(drift,   ic,          drift_sync_ic)        \
  X(damage,  start,       damage_init_flaws)    \
  X(drift,   rebuild_start, drift_mirror_strip) \
  X(drift,   rebuild,     drift_mirror_make)    \
  X(density, first_force, density_reset_all)    \
  X(drift,   force,       drift_mirror_refresh) \
  X(gravity, clean,       gravity_engine_clean) \
  X(drift,   clean,       drift_mirror_clean)

/* TASK_FAMILY_ENTRIES(X): X(family, ret, fn, params): the other functions of
 * a family that src/ calls by name, each with its own signature
 * (ret fn params, declared below from this list), so that src/ reaches them
 * through this header and none of the family's own:
 *
 *  drift_integrate_*   TimeIntegration:scheme rk2 and pc, whose stages are
 *                      drifts (tasks/drift/drift_integrate.c): _init reads
 *                      the scheme and checks what it runs with, _step takes
 *                      one step (0: none to take), _log the run's closing
 *                      line, _free its arrays
 *  kick_dt_culprit     which particle and which criterion of the kick's time
 *                      step (tasks/kick/timestep.h) set the smallest step,
 *                      written into why: the message of a step below
 *                      TimeIntegration:dt_min (engine.c)
 *  flaws_check_values  the damage family's check of the flaw thresholds of
 *                      a restart file (struct restart_expect, flaws_check),
 *                      tasks/damage/flaws.c
 *  gravity_*           self-gravity's part of the engine's rebuild, restart
 *                      and step loop, on its state e->grav
 *                      (tasks/gravity/gravity_engine.c):
 *    gravity_cell_doubles      doubles of one cell's gravity data in a
 *                              restart file (struct restart_expect)
 *    gravity_restart_read      keep the far field that restart_read found
 *                              (moved out of *g) until gravity_restart_restore
 *    gravity_restart_save      the far field the coming steps may reuse, for
 *                              the restart file (restart_gravity_free it)
 *    gravity_restart_restore   after the first rebuild of a resumed run: the
 *                              restart file's far field back in place
 *    gravity_active_decide     before a FORCE phase (time bins, CPU): whether
 *                              only the cells with particles that end their
 *                              step receive gravity (sets e->gp.active; all
 *                              when an output follows)
 *    gravity_reuse_decide      before a FORCE phase: whether it reuses the
 *                              far field of the last full evaluation (sets
 *                              e->gp.replay; not after a rebuild)
 *    gravity_reuse_remember    after a FORCE phase that evaluated in full:
 *                              the positions and distances the next decide
 *                              compares with
 *    gravity_estimate_first    before the first FORCE phase: the adaptive
 *                              criterion's scale (gravity_estimate); 1 if it
 *                              changed the particles' ga and pot
 *    gravity_graph_made        the gravity tasks are the graph's first
 *                              nr_tasks: the per-cell data grown to the new
 *                              cells, one interaction list per task (reuse)
 *    gravity_graph_free        the task graph is freed: the lists too
 *    gravity_top_pair_is_near  whether two top-level cells get a pair task
 *                              (tasks/gravity/gravity_cpu.c)
 *    gravity_potential_energy  1/2 sum_i m_i pot_i (the statistics)
 *    gravity_pairs_energy      the potential energy of the pairs among n
 *                              particles (x, y, z, m, h each), directly:
 *                              particles removed at one rebuild, whose
 *                              m pot counts each of their pairs twice
 *    gravity_log_end           the run's closing line on the far-field reuse
 *    gravity_top_record_*, gravity_top_records_use, gravity_top_needed,
 *    gravity_remote_misses     several MPI ranks (src/mpi/halo.c): a
 *                              top-level cell's record of this step (its
 *                              multipole, a_min, support, box, count,
 *                              split) packed for the other ranks; the other
 *                              ranks' records put where the walks read them
 *                              (gp.remote); the cells of other ranks whose
 *                              particles this rank's walks may need until
 *                              the next rebuild, from the records of the
 *                              last step with a margin; the walks' misses
 *                              (a needed cell without its particles)
 *  gravity_gpu_*       self-gravity's part of the GPU runner's FORCE phase,
 *                      on its device state (tasks/gravity/gpu_gravity_runner.c,
 *                      CUDA builds only; src/gpu/gpu_engine.c):
 *    gravity_gpu_new      the device state on g (Scheduler:gpu_multipoles,
 *                         Scheduler:gpu_walks: device: up_on_device,
 *                         walk_on_device)
 *    gravity_gpu_prepare  the tree, the multipoles' staging and the workers'
 *                         lists for a device evaluation; 0 when the CPU has
 *                         nothing to do (a step that reuses the far field,
 *                         or the walks on the device)
 *    gravity_gpu_task     run a gravity task on a CPU worker, its walks
 *                         recording their interactions for the device
 *    gravity_gpu_device   the device part: ga and pot complete on both sides
 *    gravity_gpu_print, gravity_gpu_free */
#define TASK_FAMILY_ENTRIES(X)                                                              \
  X(drift,   void, drift_integrate_init, (struct engine *e))                                 \
  X(drift,   int,  drift_integrate_step, (struct engine *e))                                 \
  X(drift,   void, drift_integrate_log, (const struct engine *e))                            \
  X(drift,   void, drift_integrate_free, (struct engine *e))                                 \
  X(kick,    void, kick_dt_culprit, (const struct engine *e, char *why, size_t len))         \
  X(damage,  int,  flaws_check_values,                                                       \
    (size_t n, const int64_t *offset, const double *eps, char *msg, size_t len))             \
  X(gravity, int64_t, gravity_cell_doubles, (void))                                          \
  X(gravity, void, gravity_restart_read, (struct engine *e, struct restart_gravity *g))      \
  X(gravity, void, gravity_restart_save, (const struct engine *e, struct restart_gravity *g)) \
  X(gravity, void, gravity_restart_restore, (struct engine *e))                              \
  X(gravity, void, gravity_active_decide, (struct engine *e, int full))                      \
  X(gravity, void, gravity_reuse_decide, (struct engine *e, int rebuilt))                    \
  X(gravity, void, gravity_reuse_remember, (struct engine *e))                               \
  X(gravity, int,  gravity_estimate_first, (struct engine *e))                               \
  X(gravity, void, gravity_graph_made, (struct engine *e, int nr_tasks))                     \
  X(gravity, void, gravity_graph_free, (struct engine *e))                                   \
  X(gravity, int,  gravity_top_pair_is_near,                                                 \
    (const struct cell *ci, const struct cell *cj, const struct gravity_props *gp))          \
  X(gravity, double, gravity_potential_energy, (const struct parts *p))                      \
  X(gravity, double, gravity_pairs_energy,                                                   \
    (const double *xmh, size_t n, const struct gravity_props *gp))                           \
  X(gravity, void, gravity_log_end, (const struct engine *e))                                \
  X(gravity, int,  gravity_top_record_doubles, (void))                                       \
  X(gravity, void, gravity_top_record_pack, (const struct engine *e, int c, double *out))    \
  X(gravity, void, gravity_top_records_use,                                                  \
    (struct engine *e, const double *recs, const int *row, const unsigned char *use,         \
     const unsigned char *complete))                                                         \
  X(gravity, void, gravity_top_needed,                                                       \
    (const struct engine *e, const double *recs, const int *row,                             \
     const unsigned char *mine, const long long *count, const double *box, double drift,     \
     unsigned char *need))                                                                   \
  X(gravity, long, gravity_remote_misses, (int reset))                                       \
  X(gravity, struct gravity_gpu *, gravity_gpu_new,                                          \
    (struct gpu *g, int up_on_device, int walk_on_device, int reproducible))                 \
  X(gravity, int,  gravity_gpu_prepare, (struct engine *e, struct gravity_gpu *gg))          \
  X(gravity, void, gravity_gpu_task,                                                         \
    (struct engine *e, struct gravity_gpu *gg, struct task *t, int thread_id))               \
  X(gravity, void, gravity_gpu_device, (struct engine *e, struct gravity_gpu *gg))           \
  X(gravity, void, gravity_gpu_print, (const struct gravity_gpu *gg, FILE *f))               \
  X(gravity, void, gravity_gpu_free, (struct gravity_gpu *gg))

/* TASK_FAMILY_INTERFACES(X): X(family, header): the header of a family that
 * src/ may include besides this one: what the engine holds of the family by
 * value (gravity: its settings, struct gravity_props, and its state behind
 * a pointer).  Such a header includes nothing of tasks/ but this registry
 * and tasks/hydro/ (tests/repo/test_layers.py checks both). */
#define TASK_FAMILY_INTERFACES(X) \
  X(gravity, "tasks/gravity/gravity_props.h")

/* ------------------------------------------------------------ expansions */

/** (a, b, c) -> a, b, c: the field lists. */
#define TASK_UNPAREN(...) __VA_ARGS__

/** The task types the families add: TASK_FAMILY_TYPE_X_(type) for every row
 *  of shape cell, in registry order, and the subtypes they define:
 *  TASK_FAMILY_SUBTYPE_X_(s) for every SUB(s) (src/task.h defines both hooks
 *  before each expansion). */
#define TASK_FAMILY_CELL_TYPE_cell(type) TASK_FAMILY_TYPE_X_(type)
#define TASK_FAMILY_CELL_TYPE_chain(active) TASK_FAMILY_CELL_TYPE_cell
#define TASK_FAMILY_CELL_TYPE_self(type)
#define TASK_FAMILY_CELL_TYPE_pair(type)
#define TASK_FAMILY_TYPES_ROW_(family, shape, type, subtype, cpu) \
  TASK_FAMILY_CELL_TYPE_##shape(type)
#define TASK_FAMILY_TYPES TASK_FAMILY_TASKS(TASK_FAMILY_TYPES_ROW_)

#define TASK_FAMILY_SUBTYPE_SUB(s) TASK_FAMILY_SUBTYPE_X_(s)
#define TASK_FAMILY_SUBTYPE_NOSUB
#define TASK_FAMILY_SUBTYPES_ROW_(name, subtype, policy, place, gpu, when, stage, reads, writes) \
  TASK_FAMILY_SUBTYPE_##subtype
#define TASK_FAMILY_SUBTYPES TASK_FAMILIES(TASK_FAMILY_SUBTYPES_ROW_)

/** The families, by registry row (task_family_names in src/task.c). */
enum task_family {
#define TASK_FAMILY_ENUM_(name, subtype, policy, place, gpu, when, stage, reads, writes) \
  task_family_##name,
  TASK_FAMILIES(TASK_FAMILY_ENUM_)
#undef TASK_FAMILY_ENUM_
  task_family_count /**< number of families */
};

/** The points of TASK_FAMILY_HOOKS (column when). */
enum task_family_when {
  task_family_at_init,        /**< the units and SPH settings are read (engine_init) */
  task_family_at_ic,          /**< the initial conditions are read */
  task_family_at_start,       /**< the particles are read (ICs or restart file) */
  task_family_at_first_force, /**< the first force computation starts */
  task_family_at_rebuild_start, /**< the space is about to be rebuilt */
  task_family_at_rebuild,       /**< the space was rebuilt */
  task_family_at_force,         /**< a FORCE phase is about to run */
  task_family_at_clean,       /**< the engine is freed (engine_clean) */
};

/** The bit (1u << family) of every HYDRO family (column policy). */
#define TASK_FAMILY_POLICY_HYDRO(name) | (1u << task_family_##name)
#define TASK_FAMILY_POLICY_FREE(name)
#define TASK_FAMILY_POLICY_CPU(name)
#define TASK_FAMILY_HYDRO_ROW_(name, subtype, policy, place, gpu, when, stage, reads, writes) \
  TASK_FAMILY_POLICY_##policy(name)
#define TASK_FAMILIES_HYDRO (0u TASK_FAMILIES(TASK_FAMILY_HYDRO_ROW_))

/** The bit of every family with a GPU implementation (policy HYDRO or FREE):
 *  the names Scheduler:gpu knows. */
#define TASK_FAMILY_ON_GPU_HYDRO(name) | (1u << task_family_##name)
#define TASK_FAMILY_ON_GPU_FREE(name) | (1u << task_family_##name)
#define TASK_FAMILY_ON_GPU_CPU(name)
#define TASK_FAMILY_GPU_ROW_(name, subtype, policy, place, gpu, when, stage, reads, writes) \
  TASK_FAMILY_ON_GPU_##policy(name)
#define TASK_FAMILIES_GPU (0u TASK_FAMILIES(TASK_FAMILY_GPU_ROW_))

/* clang-format on */

#ifndef __cplusplus
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

struct engine;
struct task;
struct cell;
struct parts;
struct gpu;
struct gravity_props;
struct gravity_gpu;
struct restart_gravity;
/* The CPU function of every kind of task, and the predicate of every chain
 * (tasks/<family>/<family>_task.c). */
#define TASK_FAMILY_ACTIVE_DECL_chain(active) int active(const struct engine *e);
#define TASK_FAMILY_ACTIVE_DECL_cell
#define TASK_FAMILY_ACTIVE_DECL_self
#define TASK_FAMILY_ACTIVE_DECL_pair
#define TASK_FAMILY_CPU_DECL_(family, shape, type, subtype, cpu) \
  void cpu(struct engine *e, struct task *t);                    \
  TASK_FAMILY_ACTIVE_DECL_##shape
TASK_FAMILY_TASKS(TASK_FAMILY_CPU_DECL_)
#undef TASK_FAMILY_CPU_DECL_
/* The hooks of TASK_FAMILY_HOOKS. */
#define TASK_FAMILY_HOOK_DECL_(family, when, fn) void fn(struct engine *e);
TASK_FAMILY_HOOKS(TASK_FAMILY_HOOK_DECL_)
#undef TASK_FAMILY_HOOK_DECL_
/* The entry points of TASK_FAMILY_ENTRIES. */
#define TASK_FAMILY_ENTRY_DECL_(family, ret, fn, params) ret fn params;
TASK_FAMILY_ENTRIES(TASK_FAMILY_ENTRY_DECL_)
#undef TASK_FAMILY_ENTRY_DECL_
#endif

#endif
