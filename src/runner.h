/* CPU worker threads: persistent pthreads, one per scheduler thread beyond
 * the caller's, pinned with hwloc to cores of the process's CPU set.
 *
 * Between runs a worker sleeps on the pool's run_cond; runner_launch()
 * wakes the workers into the pool's work function (the scheduler's
 * scheduler_work, given to runner_start() as a callback: the runner does not
 * know the scheduler), runner_wait() returns when every one has left it. */
#ifndef BOLIDE_RUNNER_H
#define BOLIDE_RUNNER_H

#include <pthread.h>

struct runner_pool;

/** One worker thread. */
struct runner {
  int id;                   /**< thread number (1 .. nr_threads-1) */
  pthread_t thread;         /**< its pthread */
  struct runner_pool *pool; /**< the pool it belongs to */
};

/** The persistent worker threads of a scheduler. */
struct runner_pool {
  int nr_threads;            /**< threads, the caller (thread 0) included */
  void (*work)(void *, int); /**< what a worker does in a run: work(ctx, thread) */
  void *ctx;                 /**< its context */
  struct runner *runners;    /**< threads 1 .. nr_threads-1 */
  void *pinning;             /**< hwloc state of runner.c (NULL: threads not pinned) */
  pthread_mutex_t run_mutex; /**< protects run_gen, nr_finished, shutdown */
  pthread_cond_t run_cond;   /**< workers wait here between runs */
  pthread_cond_t done_cond;  /**< the caller waits here for the workers to finish a run */
  int run_gen;               /**< incremented to start a run */
  int nr_finished;           /**< workers done with the current run */
  int shutdown;              /**< 1: workers exit */
};

/** Pin the calling thread as thread 0 and start threads 1 .. nr_threads-1,
 *  each calling work(ctx, thread) in every run.  Threads are pinned one per
 *  core (or per hardware thread when there are more threads than cores) of
 *  the CPU set the process may use; with more threads than hardware
 *  threads, or if hwloc fails (a warning, once), they are left to the
 *  operating system. */
/** Several processes of one run on this node (MPI ranks): this one is
 *  local_rank of local_ranks.  When the CPUs each may use hold a core for
 *  every thread of all of them (mpirun --bind-to none), the threads of
 *  local rank r take the cores after those of ranks 0 .. r - 1; when they
 *  do not (each rank bound to its own cores), every process pins within its
 *  own set as a single one does.  Call before runner_start(). */
void runner_share_node(int local_rank, int local_ranks);

void runner_start(struct runner_pool *pool, int nr_threads, void (*work)(void *, int), void *ctx);

/** Stop and join the workers; restore the calling thread's CPU binding. */
void runner_stop(struct runner_pool *pool);

/** Start a run: every worker calls the work function once. */
void runner_launch(struct runner_pool *pool);

/** Wait until every worker has finished the current run. */
void runner_wait(struct runner_pool *pool);

/** Bind the calling thread to the CPU set the process had before
 *  runner_start() pinned thread 0 (nothing when the threads are not
 *  pinned).  For a helper thread started by thread 0, which inherits its
 *  one core: it, and the threads it starts, then spread over the
 *  process's cores. */
void runner_unpin_self(const struct runner_pool *pool);

/** Bind the calling thread (thread 0) to its core again after
 *  runner_unpin_self (no-op when the pool does not pin). */
void runner_repin_self(const struct runner_pool *pool);

#endif
