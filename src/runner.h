/* CPU worker threads: persistent pthreads, one per scheduler thread beyond
 * the caller's, pinned with hwloc to cores of the process's CPU set.
 *
 * Between runs a worker sleeps on the pool's run_cond; runner_launch()
 * wakes the workers into the pool's work function (the scheduler's
 * scheduler_work, given to runner_start() as a callback: the runner does not
 * know the scheduler), runner_wait() returns when every one has left it. */
#ifndef BOLIDE_RUNNER_H
#define BOLIDE_RUNNER_H

#include <hwloc.h>
#include <pthread.h>
#include <stddef.h>

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

/** Several processes of one run on this node (MPI ranks): this one is
 *  local_rank of local_ranks.  When the CPUs each may use hold a core for
 *  every thread of all of them (mpirun --bind-to none), the threads of
 *  local rank r take the cores after those of ranks 0 .. r - 1; when they
 *  do not (each rank bound to its own cores), every process pins within its
 *  own set as a single one does.  Call before runner_start(). */
void runner_share_node(int local_rank, int local_ranks);

/** The longest PCI bus id of runner_near_devices ("0000:3b:00.0" and the
 *  terminating 0, with room). */
#define RUNNER_BUS_ID_LEN 32

/** The node's GPUs, by CUDA device number: bus_id[d] is device d's PCI bus
 *  id; local rank r of runner_share_node uses device r % nr_devices (as
 *  gpu_init chooses).  runner_start then pins each rank's threads to the
 *  cores nearest its GPU (runner_near_place) where they all fit, and as
 *  without GPUs otherwise.  Call before runner_start(); nr_devices 0:
 *  none. */
void runner_near_devices(const char (*bus_id)[RUNNER_BUS_ID_LEN], int nr_devices);

/** Where the threads go near the GPUs, in topo (loaded with its PCI
 *  devices, restricted to the CPUs the process may use): for every local
 *  rank the CPUs of the first ancestor of its GPU's PCI device that is not
 *  an I/O object (its package or NUMA node); the ranks whose GPUs lie near
 *  the same CPUs share out their cores in the order of their local ranks,
 *  nr_threads each.  On success returns 1 with the CPUs of local_rank's
 *  GPU in set and the number of its thread 0's core among those of set in
 *  *first; returns 0 with the reason in why when hwloc does not see a GPU,
 *  a GPU is near every CPU (nothing to choose), or some rank's threads do
 *  not fit the cores near its GPU (then no rank pins near its GPU, since
 *  every rank decides the same; hardware threads of one core are not
 *  shared, which costs the compute-bound loops more than the distance). */
int runner_near_place(hwloc_topology_t topo, const char (*bus_id)[RUNNER_BUS_ID_LEN],
                      int nr_devices, int local_rank, int local_ranks, int nr_threads,
                      hwloc_bitmap_t set, int *first, char *why, size_t len);

/** Pin the calling thread as thread 0 and start threads 1 .. nr_threads-1,
 *  each calling work(ctx, thread) in every run.  Threads are pinned one per
 *  core (or per hardware thread when there are more threads than cores) of
 *  the CPU set the process may use (near its GPU: runner_near_devices);
 *  with more threads than hardware threads, or if hwloc fails (a warning,
 *  once), they are left to the operating system. */
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
