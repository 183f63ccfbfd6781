/* The scheduler: see scheduler.h and theory/scheduler.md. */
#include "src/scheduler.h"

#include <sched.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "src/error.h"

/** Failed attempts to find a task before a worker goes to sleep. */
#define SCHEDULER_SPIN 64

/** Cost estimate (seconds) of a task that never ran: small, so that at first
 *  the priority is the number of tasks on the longest path behind a task. */
#define SCHEDULER_DEFAULT_COST 1e-6f

/** Index into the timer array. */
static inline size_t scheduler_timer_index(int tid, enum task_type type,
                                           enum task_subtype subtype) {
  return ((size_t)tid * task_type_count + type) * task_subtype_count + subtype;
}

/** The work function of the runner pool: scheduler_work() of thread tid. */
static void scheduler_work_cb(void *s, int tid) {
  scheduler_work(s, tid);
}

void scheduler_init(struct scheduler *s, int nr_threads) {
  if (nr_threads < 1) error_exit("the number of threads must be at least 1 (got %d)", nr_threads);
  memset(s, 0, sizeof *s);
  s->nr_threads = nr_threads;
  s->queues = error_malloc(nr_threads * sizeof(struct queue), "task queues");
  for (int i = 0; i < nr_threads; i++) queue_init(&s->queues[i]);
  pthread_mutex_init(&s->sleep_mutex, NULL);
  pthread_condattr_t attr; /* timed waits on the monotonic clock: immune to clock changes */
  pthread_condattr_init(&attr);
  pthread_condattr_setclock(&attr, CLOCK_MONOTONIC);
  pthread_cond_init(&s->sleep_cond, &attr);
  pthread_condattr_destroy(&attr);
  atomic_init(&s->nr_sleeping, 0);
  atomic_init(&s->epoch, 0);
  atomic_init(&s->nr_remaining, 0);
  s->timers = error_calloc((size_t)nr_threads * task_type_count * task_subtype_count,
                           sizeof(struct scheduler_timer), "task timers");
  s->busy_ns = error_calloc(nr_threads, sizeof(int64_t), "thread timers");
  s->deadlock_seconds = 60;
  runner_start(&s->pool, nr_threads, scheduler_work_cb, s);
}

void scheduler_free(struct scheduler *s) {
  runner_stop(&s->pool);
  for (int i = 0; i < s->nr_threads; i++) queue_free(&s->queues[i]);
  free(s->queues);
  for (int i = 0; i < s->nr_chunks; i++) free(s->chunks[i]);
  free(s->chunks);
  free(s->edges);
  free(s->unlocks);
  free(s->order);
  free(s->timers);
  free(s->busy_ns);
  pthread_cond_destroy(&s->sleep_cond);
  pthread_mutex_destroy(&s->sleep_mutex);
  memset(s, 0, sizeof *s);
}

/* ------------------------------------------------------------ building */

struct task *scheduler_addtask(struct scheduler *s, enum task_type type, enum task_subtype subtype,
                               void *ci, void *cj) {
  if (s->nr_tasks == s->nr_chunks * SCHEDULER_CHUNK) {
    s->chunks = error_realloc(s->chunks, (s->nr_chunks + 1) * sizeof(struct task *), "tasks");
    s->chunks[s->nr_chunks++] = error_malloc(SCHEDULER_CHUNK * sizeof(struct task), "tasks");
  }
  struct task *t = scheduler_task(s, s->nr_tasks);
  memset(t, 0, sizeof *t);
  t->type = type;
  t->subtype = subtype;
  t->ci = ci;
  t->cj = cj;
  t->cell_index = -1;
  t->id = s->nr_tasks++;
  t->cost = SCHEDULER_DEFAULT_COST;
  t->rid = -1;
  atomic_init(&t->wait, 0);
#ifdef BOLIDE_DEBUG_CHECKS
  atomic_init(&t->nr_runs, 0);
#endif
  s->finalized = 0;
  return t;
}

void scheduler_addunlock(struct scheduler *s, struct task *before, struct task *after) {
  if (s->nr_edges == s->size_edges) {
    s->size_edges = s->size_edges ? 2 * s->size_edges : 1024;
    s->edges = error_realloc(s->edges, s->size_edges * sizeof(struct scheduler_edge), "unlocks");
  }
  s->edges[s->nr_edges].before = before->id;
  s->edges[s->nr_edges].after = after->id;
  s->nr_edges++;
  s->finalized = 0;
}

void scheduler_finalize(struct scheduler *s) {
  const int n = s->nr_tasks;
  /* CSR: count the dependants of each task, prefix sum, fill */
  int *offset = error_calloc(n + 1, sizeof(int), "unlock offsets");
  int *indeg = error_calloc(n + 1, sizeof(int), "in-degrees");
  for (int e = 0; e < s->nr_edges; e++) {
    offset[s->edges[e].before + 1]++;
    indeg[s->edges[e].after]++;
  }
  for (int i = 0; i < n; i++) offset[i + 1] += offset[i];
  free(s->unlocks);
  s->unlocks = error_malloc((s->nr_edges + 1) * sizeof(struct task *), "unlocks");
  for (int i = 0; i < n; i++) {
    struct task *t = scheduler_task(s, i);
    t->unlocks = s->unlocks + offset[i];
    t->nr_unlocks = offset[i + 1] - offset[i];
  }
  /* (offset[i] moves along task i's slice as it is filled) */
  for (int e = 0; e < s->nr_edges; e++)
    s->unlocks[offset[s->edges[e].before]++] = scheduler_task(s, s->edges[e].after);

  /* topological order (Kahn): needed for the priorities, and finds cycles */
  free(s->order);
  s->order = error_malloc((n + 1) * sizeof(struct task *), "task order");
  int head = 0, tail = 0;
  for (int i = 0; i < n; i++)
    if (indeg[i] == 0) s->order[tail++] = scheduler_task(s, i);
  while (head < tail) {
    struct task *t = s->order[head++];
    for (int k = 0; k < t->nr_unlocks; k++)
      if (--indeg[t->unlocks[k]->id] == 0) s->order[tail++] = t->unlocks[k];
  }
  if (tail < n) {
    int i = 0;
    while (indeg[i] == 0) i++;
    struct task *t = scheduler_task(s, i);
    error_bug("the task graph has a cycle: %d of %d tasks never become ready, e.g. task %d (%s/%s)",
              n - tail, n, i, task_type_names[t->type], task_subtype_names[t->subtype]);
  }
  free(indeg);
  free(offset);
  s->finalized = 1;
}

void scheduler_clear(struct scheduler *s) {
  s->nr_tasks = 0;
  s->nr_edges = 0;
  s->finalized = 0;
}

/* ------------------------------------------------------------ running */

/** Wake sleeping workers: one (a new ready task) or all (a lock released,
 *  the run over). */
static void scheduler_wake(struct scheduler *s, int all) {
  atomic_fetch_add(&s->epoch, 1);
  if (atomic_load(&s->nr_sleeping) == 0) return;
  pthread_mutex_lock(&s->sleep_mutex);
  if (all)
    pthread_cond_broadcast(&s->sleep_cond);
  else
    pthread_cond_signal(&s->sleep_cond);
  pthread_mutex_unlock(&s->sleep_mutex);
}

/** Put a ready task in a queue: that of the thread that ran it last (its
 *  data may still be in that core's cache), else one chosen by its cell. */
static void scheduler_enqueue(struct scheduler *s, struct task *t) {
  unsigned q;
  if (t->rid >= 0)
    q = (unsigned)t->rid % s->nr_threads;
  else {
    /* Fibonacci hashing: neighbouring addresses land in different queues */
    const uint64_t key = t->ci ? (uint64_t)(uintptr_t)t->ci : (uint64_t)t->id;
    q = (unsigned)((key * 0x9E3779B97F4A7C15ull) >> 40) % (unsigned)s->nr_threads;
  }
  queue_insert(&s->queues[q], t);
  scheduler_wake(s, 0);
}

#ifdef BOLIDE_DEBUG_CHECKS
/** No task finished for s->deadlock_seconds: name the stuck tasks, stop. */
static void scheduler_report_deadlock(struct scheduler *s) {
  int shown = 0;
  for (int i = 0; i < s->nr_tasks && shown < 10; i++) {
    struct task *t = scheduler_task(s, i);
    if (t->skip || atomic_load(&t->nr_runs) > 0) continue;
    fprintf(stderr, "%s: stuck task %d (%s/%s) cell %d: wait %d, locks %s\n", error_progname, t->id,
            task_type_names[t->type], task_subtype_names[t->subtype], t->cell_index,
            atomic_load(&t->wait),
            (t->locks[0] && atomic_load(&t->locks[0]->held)) ||
                    (t->locks[1] && atomic_load(&t->locks[1]->held))
                ? "held by others"
                : "free");
    shown++;
  }
  error_bug("deadlock: no task finished for %g s, %d of %d active tasks remain",
            s->deadlock_seconds, atomic_load(&s->nr_remaining), s->nr_active);
}
#endif

/** Next task for thread tid, its locks taken: its own queue first, then
 *  the others from a random one on (stealing).  Spins a little, then sleeps
 *  until something changes.  NULL when the run is over. */
static struct task *scheduler_gettask(struct scheduler *s, int tid, unsigned *seed) {
  const int nq = s->nr_threads;
  for (int spin = 0;; spin++) {
    const unsigned epoch = atomic_load(&s->epoch);
    struct task *t = queue_gettask(&s->queues[tid]);
    if (!t && nq > 1) {
      /* xorshift: a random victim spreads thieves over the queues */
      *seed ^= *seed << 13, *seed ^= *seed >> 17, *seed ^= *seed << 5;
      const int start = (int)(*seed % (unsigned)nq);
      for (int k = 0; k < nq && !t; k++) {
        const int q = (start + k) % nq;
        if (q != tid) t = queue_gettask(&s->queues[q]);
      }
    }
    if (t) return t;
    if (atomic_load(&s->nr_remaining) <= 0) return NULL;
    if (spin < SCHEDULER_SPIN) {
      sched_yield();
      continue;
    }
    /* sleep until the epoch moves: any enqueue or lock release after the
     * scan above bumps it, so no wake-up is missed (scheduler_wake) */
    atomic_fetch_add(&s->nr_sleeping, 1);
    pthread_mutex_lock(&s->sleep_mutex);
    while (atomic_load(&s->epoch) == epoch && atomic_load(&s->nr_remaining) > 0) {
      struct timespec until;
      clock_gettime(CLOCK_MONOTONIC, &until);
      until.tv_nsec += 100000000; /* wake every 0.1 s anyway: robust, and the deadlock check */
      if (until.tv_nsec >= 1000000000) until.tv_sec++, until.tv_nsec -= 1000000000;
      pthread_cond_timedwait(&s->sleep_cond, &s->sleep_mutex, &until);
#ifdef BOLIDE_DEBUG_CHECKS
      if (task_now_ns() - atomic_load(&s->last_progress) > (int64_t)(s->deadlock_seconds * 1e9))
        scheduler_report_deadlock(s);
#endif
    }
    pthread_mutex_unlock(&s->sleep_mutex);
    atomic_fetch_sub(&s->nr_sleeping, 1);
    spin = 0;
  }
}

/** After task t ran: free its resources, resolve its dependants. */
static void scheduler_done(struct scheduler *s, struct task *t) {
  const int had_locks = t->locks[0] || t->locks[1];
  task_unlock(t);
  for (int k = 0; k < t->nr_unlocks; k++) {
    struct task *u = t->unlocks[k];
    if (u->skip) continue;
    const int w = atomic_fetch_sub(&u->wait, 1) - 1;
#ifdef BOLIDE_DEBUG_CHECKS
    if (w < 0)
      error_bug("task %d (%s/%s) has a negative wait counter", u->id, task_type_names[u->type],
                task_subtype_names[u->subtype]);
#endif
    if (w == 0) scheduler_enqueue(s, u);
  }
#ifdef BOLIDE_DEBUG_CHECKS
  atomic_store(&s->last_progress, task_now_ns());
#endif
  const int left = atomic_fetch_sub(&s->nr_remaining, 1) - 1;
  /* The end frees everyone.  A released lock may unblock a queued task in
   * any queue; if every queue is empty there is nothing to unblock.  That
   * test is safe because lock operations and queue counts are sequentially
   * consistent: a worker that failed to lock a queued task before our
   * release saw a count we see too (theory/scheduler.md). */
  if (left <= 0)
    scheduler_wake(s, 1);
  else if (had_locks) {
    int queued = 0;
    for (int q = 0; q < s->nr_threads && !queued; q++) queued = atomic_load(&s->queues[q].count);
    if (queued) scheduler_wake(s, 1);
  }
}

void scheduler_work(struct scheduler *s, int tid) {
  unsigned seed = 2463534242u + 7919u * (unsigned)tid;
  int64_t busy = 0;
  struct task *t;
  while ((t = scheduler_gettask(s, tid, &seed))) {
#ifdef BOLIDE_DEBUG_CHECKS
    if (atomic_fetch_add(&t->nr_runs, 1) != 0)
      error_bug("task %d (%s/%s) run twice", t->id, task_type_names[t->type],
                task_subtype_names[t->subtype]);
#endif
    t->tic = task_now_ns();
    s->fn(s->ctx, t, tid);
    t->toc = task_now_ns();
    t->rid = tid;
    if (!s->fixed_costs) t->cost = (float)((t->toc - t->tic) * 1e-9);
    struct scheduler_timer *timer = &s->timers[scheduler_timer_index(tid, t->type, t->subtype)];
    timer->ns += t->toc - t->tic;
    timer->count++;
    busy += t->toc - t->tic;
    scheduler_done(s, t);
    if (tid == 0 && s->poll) s->poll(s->poll_ctx);
  }
  s->busy_ns[tid] += busy;
}

/** Activate the tasks not skipped: wait counters from active predecessors,
 *  priorities from the costs.  Returns the number of active tasks. */
static int scheduler_activate(struct scheduler *s) {
  int nr_active = 0;
  for (int i = 0; i < s->nr_tasks; i++) {
    struct task *t = scheduler_task(s, i);
    atomic_store_explicit(&t->wait, 0, memory_order_relaxed);
#ifdef BOLIDE_DEBUG_CHECKS
    atomic_store_explicit(&t->nr_runs, 0, memory_order_relaxed);
#endif
    if (!t->skip) nr_active++;
  }
  for (int i = 0; i < s->nr_tasks; i++) {
    struct task *t = scheduler_task(s, i);
    if (t->skip) continue;
    for (int k = 0; k < t->nr_unlocks; k++)
      if (!t->unlocks[k]->skip)
        atomic_fetch_add_explicit(&t->unlocks[k]->wait, 1, memory_order_relaxed);
  }
  /* weight = cost + heaviest path behind: the critical path goes first */
  for (int i = s->nr_tasks - 1; i >= 0; i--) {
    struct task *t = s->order[i];
    float behind = 0;
    for (int k = 0; k < t->nr_unlocks; k++)
      if (!t->unlocks[k]->skip && t->unlocks[k]->weight > behind) behind = t->unlocks[k]->weight;
    t->weight = t->cost + behind;
  }
  return nr_active;
}

void scheduler_run(struct scheduler *s, scheduler_run_fn fn, void *ctx) {
  if (!s->finalized) error_bug("scheduler_run() before scheduler_finalize()");
  s->fn = fn;
  s->ctx = ctx;
  s->nr_active = scheduler_activate(s);
  s->run_tic = task_now_ns();
  atomic_store(&s->last_progress, s->run_tic);
  atomic_store(&s->nr_remaining, s->nr_active);
  if (s->nr_active > 0) {
    for (int i = 0; i < s->nr_tasks; i++) {
      struct task *t = scheduler_task(s, i);
      if (!t->skip && atomic_load_explicit(&t->wait, memory_order_relaxed) == 0)
        scheduler_enqueue(s, t);
    }
    runner_launch(&s->pool);
    scheduler_work(s, 0);
    runner_wait(&s->pool);
  }
  s->run_toc = task_now_ns();
  s->wall_ns += s->run_toc - s->run_tic;
  s->nr_runs++;
#ifdef BOLIDE_DEBUG_CHECKS
  for (int i = 0; i < s->nr_tasks; i++) {
    struct task *t = scheduler_task(s, i);
    const int runs = atomic_load(&t->nr_runs);
    if (runs != !t->skip)
      error_bug("task %d (%s/%s, skip %d) ran %d times", t->id, task_type_names[t->type],
                task_subtype_names[t->subtype], t->skip, runs);
  }
#endif
}

/* ------------------------------------------------------------ timers */

void scheduler_reset_timers(struct scheduler *s) {
  memset(s->timers, 0,
         (size_t)s->nr_threads * task_type_count * task_subtype_count *
             sizeof(struct scheduler_timer));
  memset(s->busy_ns, 0, s->nr_threads * sizeof(int64_t));
  s->wall_ns = 0;
  s->nr_runs = 0;
}

void scheduler_print_timers(const struct scheduler *s, FILE *f) {
  fprintf(f, "# task timers: %d runs, %.6f s wall, %d threads\n", s->nr_runs, s->wall_ns * 1e-9,
          s->nr_threads);
  fprintf(f, "# %-16s %-10s %10s %12s %12s\n", "type", "subtype", "count", "total[s]", "mean[ms]");
  for (int ty = 0; ty < task_type_count; ty++)
    for (int st = 0; st < task_subtype_count; st++) {
      int64_t ns = 0, count = 0;
      for (int tid = 0; tid < s->nr_threads; tid++) {
        const struct scheduler_timer *timer = &s->timers[scheduler_timer_index(tid, ty, st)];
        ns += timer->ns;
        count += timer->count;
      }
      if (count == 0) continue;
      fprintf(f, "  %-16s %-10s %10lld %12.6f %12.6f\n", task_type_names[ty],
              task_subtype_names[st], (long long)count, ns * 1e-9, ns * 1e-6 / count);
    }
  fprintf(f, "# %-8s %12s %10s\n", "thread", "busy[s]", "idle");
  for (int tid = 0; tid < s->nr_threads; tid++)
    fprintf(f, "  %-8d %12.6f %10.4f\n", tid, s->busy_ns[tid] * 1e-9,
            s->wall_ns > 0 ? 1.0 - (double)s->busy_ns[tid] / s->wall_ns : 0.0);
}

int scheduler_dump_tasks(const struct scheduler *s, FILE *f) {
  fprintf(f, "# thread start[s] end[s] type subtype cell  (tasks of the last run, %d threads)\n",
          s->nr_threads);
  for (int i = 0; i < s->nr_tasks; i++) {
    const struct task *t = scheduler_task(s, i);
    if (t->skip || t->rid < 0 || t->tic < s->run_tic || t->toc > s->run_toc) continue;
    fprintf(f, "%d %.9f %.9f %s %s %d\n", t->rid, (t->tic - s->run_tic) * 1e-9,
            (t->toc - s->run_tic) * 1e-9, task_type_names[t->type], task_subtype_names[t->subtype],
            t->cell_index);
  }
  return ferror(f) ? -1 : 0;
}
