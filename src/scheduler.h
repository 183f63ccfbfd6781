/* The scheduler: builds the task graph and runs it on worker threads.
 *
 * Building (once per rebuild):
 *   scheduler_addtask()   a node;  scheduler_addunlock(before, after)  an edge;
 *   scheduler_finalize()  packs the edges, orders the graph, rejects cycles.
 * Running (every step):
 *   set each task's `skip`, then scheduler_run(s, fn, ctx): every task not
 *   skipped runs exactly once, after all its non-skipped predecessors, never at
 *   the same time as another task holding one of its locks.  A skipped task's
 *   dependants do not wait for it (theory/scheduler.md).
 *
 * Threads: scheduler_init() starts nr_threads - 1 persistent workers
 * (runner.c); the thread calling scheduler_run() works as thread 0, so
 * `--threads N` means N threads computing.  Between runs the workers sleep.
 *
 * Tasks live in chunks of SCHEDULER_CHUNK: a `struct task *` stays valid
 * until scheduler_clear() or scheduler_free(), however many tasks are added
 * after it.  The scheduler knows nothing of cells or SPH: ci, cj and the
 * locks are chosen by the caller. */
#ifndef BOLIDE_SCHEDULER_H
#define BOLIDE_SCHEDULER_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>

#include "src/queue.h"
#include "src/runner.h"
#include "src/task.h"

/** Tasks per storage chunk. */
#define SCHEDULER_CHUNK 1024

/** The work of one task: called by thread `thread_id` (0 .. nr_threads-1). */
typedef void (*scheduler_run_fn)(void *ctx, struct task *t, int thread_id);

/** Accumulated time of one kind of task on one thread. */
struct scheduler_timer {
  int64_t ns;    /**< total wall time, nanoseconds */
  int64_t count; /**< tasks run */
};

/** An edge before -> after, kept until scheduler_finalize(). */
struct scheduler_edge {
  int before; /**< id of the task that must finish first */
  int after;  /**< id of the task that waits for it (ids, not pointers: scheduler_finalize's
                   passes over the edges then read no task) */
};

/** The task graph, its queues and its worker threads. */
struct scheduler {
  int nr_threads;  /**< threads computing, the caller of scheduler_run() included */
  int fixed_costs; /**< 1: never replace the task costs by measured times, so that with one
                        thread the task order (and every sum) repeats from run to run */

  /* -- the graph */
  struct task **chunks;         /**< task storage: chunks of SCHEDULER_CHUNK tasks */
  int nr_chunks;                /**< chunks allocated */
  int nr_tasks;                 /**< tasks added since the last scheduler_clear() */
  struct scheduler_edge *edges; /**< unlocks added since the last scheduler_clear() */
  int nr_edges, size_edges;     /**< edges used and allocated */
  struct task **unlocks;        /**< CSR array of dependants, sliced by task->unlocks */
  struct task **order;          /**< the tasks in a topological order */
  int finalized;                /**< 1 when unlocks and order match the tasks and edges */

  /* -- one run */
  struct queue *queues;     /**< one queue of ready tasks per thread */
  scheduler_run_fn fn;      /**< the work function of the current run */
  void *ctx;                /**< its context */
  int nr_active;            /**< tasks not skipped in the current run */
  atomic_int nr_remaining;  /**< active tasks not finished yet */
  int64_t run_tic, run_toc; /**< start and end of the last run (task_now_ns()) */
  void (*poll)(void *);     /**< NULL, or called by thread 0 (the caller of scheduler_run) after
                                 each task it ran: several MPI ranks progress their exchanges
                                 there while the workers compute (src/mpi/halo.c) */
  void *poll_ctx;           /**< its argument */

  /* -- idle workers sleep here until work appears (no long busy-waiting) */
  pthread_mutex_t sleep_mutex; /**< protects the wait on sleep_cond */
  pthread_cond_t sleep_cond;   /**< signalled on new ready tasks, released locks, the end */
  atomic_int nr_sleeping;      /**< workers waiting on sleep_cond */
  atomic_uint epoch;           /**< bumped on every event that may give a worker work */

  /* -- the persistent worker threads (runner.c) */
  struct runner_pool pool; /**< they run scheduler_work() */

  /* -- timers, accumulated over runs until scheduler_reset_timers() */
  struct scheduler_timer *timers; /**< [thread][type][subtype] */
  int64_t *busy_ns;               /**< per thread: time spent inside tasks */
  int64_t wall_ns;                /**< total wall time of the runs */
  int nr_runs;                    /**< runs timed */

  double deadlock_seconds;    /**< debug checks: no task finished for this long = deadlock */
  atomic_llong last_progress; /**< debug checks: task_now_ns() of the last finished task */
};

/** Set up an empty graph and start nr_threads - 1 worker threads, pinned to
 *  cores of the process's CPU set when there are enough (runner.c). */
void scheduler_init(struct scheduler *s, int nr_threads);

/** Stop the workers and free everything. */
void scheduler_free(struct scheduler *s);

/** Add a task; cell_index is set to -1, no locks, cost to a small estimate.
 *  The caller may set locks, cell_index, cost and skip on the result. */
struct task *scheduler_addtask(struct scheduler *s, enum task_type type, enum task_subtype subtype,
                               void *ci, void *cj);

/** Add the dependency before -> after: `after` starts once `before` ended. */
void scheduler_addunlock(struct scheduler *s, struct task *before, struct task *after);

/** Pack the dependencies of every task (CSR) and order the graph; a cycle is
 *  a bug (error_bug naming a task on or behind it).  Needed after adding
 *  tasks or unlocks, before scheduler_run(). */
void scheduler_finalize(struct scheduler *s);

/** Run every task whose skip flag is 0, each once, honouring dependencies
 *  and locks, with fn(ctx, task, thread) doing the work.  Returns when all
 *  are done.  Measures each task's time: it becomes its cost, and so its
 *  priority, in the next run. */
void scheduler_run(struct scheduler *s, scheduler_run_fn fn, void *ctx);

/** Drop every task and unlock, keeping the storage, for a new graph. */
void scheduler_clear(struct scheduler *s);

/** Task number i (0 <= i < s->nr_tasks), in creation order. */
static inline struct task *scheduler_task(const struct scheduler *s, int i) {
  return &s->chunks[i / SCHEDULER_CHUNK][i % SCHEDULER_CHUNK];
}

/** Print the time per task type/subtype (total, count, mean) and per thread
 *  (busy time, idle fraction), accumulated since the last reset. */
void scheduler_print_timers(const struct scheduler *s, FILE *f);

/** Zero the accumulated timers. */
void scheduler_reset_timers(struct scheduler *s);

/** Write one line per task run in the last scheduler_run(): thread, start
 *  and end in seconds from the start of the run, type, subtype, cell index.
 *  tools/plot_tasks.py draws it.  Returns 0, or -1 on a write error. */
int scheduler_dump_tasks(const struct scheduler *s, FILE *f);

/** The work loop of thread `tid` during a run: the work function of the
 *  runner pool (threads 1 ..), and scheduler_run()'s as thread 0. */
void scheduler_work(struct scheduler *s, int tid);

#endif
