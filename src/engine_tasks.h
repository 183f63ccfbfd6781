/* Functions of the engine shared between its files (not a public API). */
#ifndef BOLIDE_ENGINE_TASKS_H
#define BOLIDE_ENGINE_TASKS_H

#include "src/engine.h"

/* engine_graph.c */
void engine_make_graph(struct engine *e);
void engine_activate_phase(struct engine *e, int phase);
void engine_graph_clean(struct engine *e);
/** The reach of an interaction until the next rebuild on the cells of s. */
double engine_reach(const struct space *s);

/* engine.c */
void engine_rebuild(struct engine *e);
int engine_should_rebuild(const struct engine *e);
double engine_next_dt(struct engine *e);
void engine_run_phase(struct engine *e, int phase);
/** Several MPI ranks with a GPU: the gravity tasks that are active (the
 *  others skipped) run on the workers through fn (engine_run_task, or the
 *  GPU runner's that records the walks' interactions) in the CPU's stages
 *  2 and 3, thread 0 (the caller) making the exchanges: the copies'
 *  gravity fields first, the top-level records between the two. */
void engine_run_gravity_stages(struct engine *e, scheduler_run_fn fn);
/** The watchdog around a drift (the positions before it; every moved
 *  particle checked after it). */
void engine_watchdog_before_drift(struct engine *e);
void engine_watchdog_after_drift(struct engine *e);

/* engine_runtask.c: the scheduler's callback */
double engine_H_limit(const struct engine *e);
void engine_run_task(void *ctx, struct task *t, int thread_id);

/* engine_io.c */
void engine_stats_open(struct engine *e);
void engine_stats_write(struct engine *e);
void engine_stats_maybe(struct engine *e);
/** At the start of a run (not a resumed one): the budget's start, and the
 *  first line when Statistics:time_first is not later. */
void engine_stats_first(struct engine *e);
/** At the end: the closing line, unless this step has one already. */
void engine_stats_close(struct engine *e);
/** One line of the timesteps file (wall_step: wall-clock seconds of the step). */
void engine_timesteps_write(struct engine *e, double wall_step);
void engine_budget_summary(struct engine *e);
void engine_snapshot(struct engine *e);
/** Write the particles to the snapshot file path (no index counted). */
void engine_snapshot_to(struct engine *e, const char *path);
/** Write this process's particles as they are (several MPI ranks: the
 *  rank's own and its foreign copies, no gather; a crash snapshot of one
 *  rank). */
void engine_snapshot_rank(struct engine *e, const char *path);
void engine_dump_tasks(struct engine *e);

#endif
