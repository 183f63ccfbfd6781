/* CPU worker threads: persistent pthreads, one per scheduler thread beyond
 * the caller's, pinned with hwloc to cores of the process's CPU set.
 *
 * Between runs a worker sleeps on the scheduler's run_cond; runner_launch()
 * wakes the workers into scheduler_work(), runner_wait() returns when every
 * one has left it. */
#ifndef BOLIDE_RUNNER_H
#define BOLIDE_RUNNER_H

#include <pthread.h>

struct scheduler;

/** One worker thread. */
struct runner {
  int id;              /**< scheduler thread number (1 .. nr_threads-1) */
  pthread_t thread;    /**< its pthread */
  struct scheduler *s; /**< the scheduler it works for */
};

/** Pin the calling thread as thread 0 and start threads 1 .. nr_threads-1.
 *  Threads are pinned one per core (or per hardware thread when there are
 *  more threads than cores) of the CPU set the process may use; with more
 *  threads than hardware threads, or if hwloc fails (a warning, once), they
 *  are left to the operating system. */
void runner_start(struct scheduler *s);

/** Stop and join the workers; restore the calling thread's CPU binding. */
void runner_stop(struct scheduler *s);

/** Start a run: every worker enters scheduler_work(). */
void runner_launch(struct scheduler *s);

/** Wait until every worker has finished the current run. */
void runner_wait(struct scheduler *s);

/** Bind the calling thread to the CPU set the process had before
 *  runner_start() pinned thread 0 (nothing when the threads are not
 *  pinned).  For a helper thread started by thread 0, which inherits its
 *  one core: it, and the threads it starts, then spread over the
 *  process's cores. */
void runner_unpin_self(const struct scheduler *s);

#endif
