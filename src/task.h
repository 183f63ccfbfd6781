/* Tasks: the nodes of the task graph.
 *
 * A task is a piece of work on a cell (ci) or a pair of cells (ci, cj).  Its
 * *type* says its shape (self, pair, ghost, drift, kick, ...) and its
 * *subtype* the physics it runs (density, gradient, force, ...):
 * theory/architecture.md, rule 4.  The scheduler treats ci and cj as opaque
 * pointers; it never looks inside a cell.
 *
 * Two separate mechanisms order the work (theory/scheduler.md):
 *  - dependencies: `wait` counts the unfinished predecessors; at zero the task
 *    is ready and is enqueued;
 *  - conflicts: `locks` are the resources the task writes; a ready task runs
 *    only once it holds all of them (try-locks, never waited on). */
#ifndef BOLIDE_TASK_H
#define BOLIDE_TASK_H

#include "config.h"

#include "tasks/task_families.h"

#include <stdatomic.h>
#include <stdint.h>
#include <time.h>

/* The task types and subtypes: the generic shapes below, and the cell types
 * and subtypes of the task families, from their registry
 * (tasks/task_families.h).  The enums and the name tables (used by the
 * timers, the task dumps and tools/plot_tasks.py through the dumps) are
 * generated from these lists (theory/architecture.md, rule 5). */
/* clang-format off */
#define TASK_TYPES(X)                                                    \
  X(none)     /* unused slot: a task never has it */                     \
  X(self)     /* interactions within one cell */                         \
  X(pair)     /* interactions between two neighbouring cells */          \
  TASK_FAMILY_TYPES /* the families' own per-cell types */               \
  X(implicit) /* no work: only dependencies (fan-in, fan-out) */         \
  X(test)     /* for the tests of the scheduler */

#define TASK_SUBTYPES(X) X(none) TASK_FAMILY_SUBTYPES

/** The shape of a task. */
enum task_type {
#define TASK_ENUM_(name) task_type_##name,
#define TASK_FAMILY_TYPE_X_ TASK_ENUM_
  TASK_TYPES(TASK_ENUM_)
#undef TASK_FAMILY_TYPE_X_
#undef TASK_ENUM_
  task_type_count /**< number of types */
};

/** The physics a task runs. */
enum task_subtype {
#define TASK_ENUM_(name) task_subtype_##name,
#define TASK_FAMILY_SUBTYPE_X_ TASK_ENUM_
  TASK_SUBTYPES(TASK_ENUM_)
#undef TASK_FAMILY_SUBTYPE_X_
#undef TASK_ENUM_
  task_subtype_count /**< number of subtypes */
};
/* clang-format on */

/** Names of the types and subtypes, indexed by the enums. */
extern const char *const task_type_names[task_type_count];
extern const char *const task_subtype_names[task_subtype_count];
/** Names of the task families (tasks/task_families.h), indexed by enum task_family. */
extern const char *const task_family_names[task_family_count];

/** A resource that tasks write (a cell's particles, its multipole...): a
 *  try-lock.  0 free, 1 held. */
struct sched_lock {
  atomic_int held; /**< 1 while a running task owns the resource */
};

/** Make a lock free. */
static inline void sched_lock_init(struct sched_lock *l) {
  atomic_init(&l->held, 0);
}

/** Take the lock if it is free; never waits.  1 on success.  Sequentially
 *  consistent, like sched_lock_release(): the scheduler's wake-up logic
 *  (scheduler_done) relies on lock operations and queue counts having one
 *  total order. */
static inline int sched_lock_try(struct sched_lock *l) {
  int expected = 0;
  return atomic_compare_exchange_strong(&l->held, &expected, 1);
}

/** Give the lock back. */
static inline void sched_lock_release(struct sched_lock *l) {
  atomic_store(&l->held, 0);
}

/** Monotonic wall clock in nanoseconds (task timings). */
static inline int64_t task_now_ns(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (int64_t)t.tv_sec * 1000000000 + t.tv_nsec;
}

/** A node of the task graph.  Created by scheduler_addtask(); its address is
 *  stable until scheduler_clear() or scheduler_free(). */
struct task {
  enum task_type type;         /**< shape of the work */
  enum task_subtype subtype;   /**< physics of the work */
  int skip;                    /**< 1: not active in the next scheduler_run() */
  void *ci, *cj;               /**< the cells (or anything); opaque to the scheduler */
  int cell_index;              /**< index of ci for dumps and plots (-1 if none) */
  struct sched_lock *locks[2]; /**< resources the task writes (NULL: none) */

  int id;                /**< index in the scheduler (creation order) */
  atomic_int wait;       /**< unfinished active predecessors in this run */
  int nr_unlocks;        /**< number of dependants */
  struct task **unlocks; /**< dependants: a slice of the scheduler's CSR array */

  float cost;       /**< seconds: measured in the previous run, else an estimate */
  float weight;     /**< queue priority: cost + longest cost path to the end of the graph */
  int64_t tic, toc; /**< start and end of the last run (task_now_ns()) */
  int rid;          /**< thread that ran it last (-1: never ran) */
  int mark;         /**< the engine's own (several MPI ranks: the task reads foreign copies, or
                         follows one that does within its stage of a FORCE phase) */
#ifdef BOLIDE_DEBUG_CHECKS
  atomic_int nr_runs; /**< times run in this scheduler_run(): must end 1 if active, 0 if not */
#endif
};

/** Take all the task's locks, or none: on a failure the locks already taken
 *  are released.  1 when the task may run. */
int task_lock(struct task *t);

/** Release the task's locks after it ran. */
void task_unlock(struct task *t);

#endif
