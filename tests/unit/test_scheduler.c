/* Stress test of the scheduler on random task graphs.
 *
 * Random DAGs (edges from lower to higher node number, nodes created in a
 * shuffled order), random conflicts (each task takes 0-2 locks of a small
 * pool), random skip flags, 1 to 16 threads.  Every run checks that
 *  - each active task ran exactly once, each skipped task never;
 *  - every dependency between active tasks was honoured: the end of A has a
 *    smaller global sequence number than the start of B for every A -> B;
 *  - no two tasks holding the same lock overlapped (holder counters <= 1);
 *  - the thread ids passed to the work function are in range;
 * and a cycle is rejected by scheduler_finalize().  A watchdog alarm turns a
 * deadlock into a failure.
 *
 * With --dump FILE: run a small SPH-shaped graph on 2 threads, print the
 * timers and write the task dump to FILE (used by test_plot_tasks.sh). */
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "src/error.h"
#include "src/scheduler.h"

/** Largest lock pool. */
#define MAX_LOCKS 8

/** What the work function records, shared by all threads. */
struct test_ctx {
  atomic_int seq;                /**< global sequence of task starts and ends */
  int *start, *end;              /**< per node: sequence numbers of its start and end */
  atomic_int *runs;              /**< per node: times run */
  struct sched_lock *pool;       /**< the locks tasks take */
  atomic_int holders[MAX_LOCKS]; /**< tasks inside each lock right now */
  atomic_int max_holders;        /**< largest number of simultaneous holders seen */
  atomic_int bad_thread;         /**< thread ids out of range */
  int nr_threads;                /**< threads of the scheduler */
};

static int test_failures = 0;

/** Report a failed check (the test goes on to report others, then fails). */
#define CHECK(cond, ...)                                     \
  do {                                                       \
    if (!(cond)) {                                           \
      if (test_failures++ < 20) {                            \
        fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__); \
        fprintf(stderr, __VA_ARGS__);                        \
        fputc('\n', stderr);                                 \
      }                                                      \
    }                                                        \
  } while (0)

/** xorshift32 random numbers: reproducible, independent of libc. */
static unsigned test_rand(unsigned *state) {
  unsigned x = *state;
  x ^= x << 13, x ^= x >> 17, x ^= x << 5;
  return *state = x;
}

/** The work: record the sequence numbers, count lock holders, spin a bit. */
static void test_work(void *vctx, struct task *t, int thread_id) {
  struct test_ctx *c = vctx;
  const int node = t->cell_index;
  if (thread_id < 0 || thread_id >= c->nr_threads) atomic_fetch_add(&c->bad_thread, 1);
  atomic_fetch_add(&c->runs[node], 1);
  c->start[node] = atomic_fetch_add(&c->seq, 1);
  int idx[2], n = 0;
  for (int k = 0; k < 2; k++)
    if (t->locks[k] && !(k == 1 && t->locks[1] == t->locks[0]))
      idx[n++] = (int)(t->locks[k] - c->pool);
  for (int k = 0; k < n; k++) {
    const int h = atomic_fetch_add(&c->holders[idx[k]], 1) + 1;
    int m = atomic_load(&c->max_holders);
    while (h > m && !atomic_compare_exchange_weak(&c->max_holders, &m, h)) {
    }
  }
  /* a little work, so that tasks overlap; sometimes yield inside a lock */
  volatile double x = 0;
  for (int i = 0; i < (node % 7) * 40; i++) x += i * 0.5;
  if (node % 5 == 0) sched_yield();
  for (int k = 0; k < n; k++) atomic_fetch_sub(&c->holders[idx[k]], 1);
  c->end[node] = atomic_fetch_add(&c->seq, 1);
}

/** One random graph of n nodes on scheduler s, run `nr_runs` times with
 *  fresh random skip flags each time (the first run: skip with probability
 *  pskip0 percent).  Returns the number of runs. */
static int test_random_graph(struct scheduler *s, int n, unsigned *rng, int nr_runs, int pskip0) {
  struct test_ctx c;
  memset(&c, 0, sizeof c);
  c.nr_threads = s->nr_threads;
  c.start = error_malloc(n * sizeof(int), "test");
  c.end = error_malloc(n * sizeof(int), "test");
  c.runs = error_malloc(n * sizeof(atomic_int), "test");
  struct sched_lock pool[MAX_LOCKS];
  for (int i = 0; i < MAX_LOCKS; i++) sched_lock_init(&pool[i]);
  c.pool = pool;
  const int nr_locks = 1 + test_rand(rng) % MAX_LOCKS;

  /* create the nodes in a shuffled order: creation order is no topological order */
  int *perm = error_malloc(n * sizeof(int), "test");
  for (int i = 0; i < n; i++) perm[i] = i;
  for (int i = n - 1; i > 0; i--) {
    int j = test_rand(rng) % (i + 1), tmp = perm[i];
    perm[i] = perm[j], perm[j] = tmp;
  }
  struct task **node = error_malloc(n * sizeof(struct task *), "test");
  for (int i = 0; i < n; i++) {
    struct task *t = scheduler_addtask(s, task_type_test, task_subtype_none, NULL, NULL);
    t->cell_index = perm[i];
    node[perm[i]] = t;
  }
  for (int i = 0; i < n; i++) {
    const int nl = test_rand(rng) % 3; /* 0, 1 or 2 locks, maybe the same one twice */
    for (int k = 0; k < nl; k++) node[i]->locks[k] = &pool[test_rand(rng) % nr_locks];
  }
  /* edges lower -> higher node number: acyclic; mostly near, sometimes far */
  int nr_edges = 0, size_edges = 4 * n + 1;
  int(*edge)[2] = error_malloc(size_edges * sizeof *edge, "test");
  for (int b = 1; b < n; b++) {
    const int ne = test_rand(rng) % 4;
    for (int k = 0; k < ne; k++) {
      const int span = (test_rand(rng) % 4 == 0) ? b : (b < 8 ? b : 8);
      const int a = b - 1 - (int)(test_rand(rng) % span);
      scheduler_addunlock(s, node[a], node[b]);
      edge[nr_edges][0] = a, edge[nr_edges][1] = b, nr_edges++;
    }
  }
  scheduler_finalize(s);
  CHECK(s->nr_tasks == n, "%d tasks stored, %d added", s->nr_tasks, n);

  for (int run = 0; run < nr_runs; run++) {
    const int pskip = run == 0 ? pskip0 : (int)(test_rand(rng) % 60);
    for (int i = 0; i < n; i++) {
      node[i]->skip = (int)(test_rand(rng) % 100) < pskip;
      atomic_init(&c.runs[i], 0);
      c.start[i] = c.end[i] = -1;
    }
    atomic_store(&c.seq, 0);
    atomic_store(&c.max_holders, 0);
    scheduler_run(s, test_work, &c);
    for (int i = 0; i < n; i++)
      CHECK(atomic_load(&c.runs[i]) == !node[i]->skip, "node %d (skip %d) ran %d times", i,
            node[i]->skip, atomic_load(&c.runs[i]));
    for (int e = 0; e < nr_edges; e++) {
      const int a = edge[e][0], b = edge[e][1];
      if (node[a]->skip || node[b]->skip) continue;
      CHECK(c.end[a] < c.start[b], "edge %d -> %d: end %d, start %d (%d threads)", a, b, c.end[a],
            c.start[b], s->nr_threads);
    }
    CHECK(atomic_load(&c.max_holders) <= 1, "%d tasks held one lock at once",
          atomic_load(&c.max_holders));
    CHECK(atomic_load(&c.bad_thread) == 0, "thread id out of range");
    for (int i = 0; i < nr_locks; i++)
      CHECK(atomic_load(&pool[i].held) == 0, "lock %d left held", i);
  }
  scheduler_clear(s);
  free(edge);
  free(node);
  free(perm);
  free(c.start);
  free(c.end);
  free(c.runs);
  return nr_runs;
}

/** A cycle must be rejected (error_bug exits): run it in a child process. */
static void test_cycle(void) {
  fflush(stdout);
  fflush(stderr);
  pid_t pid = fork();
  if (pid == 0) {
    if (!freopen("/dev/null", "w", stderr)) _exit(3);
    struct scheduler s;
    scheduler_init(&s, 1);
    struct task *a = scheduler_addtask(&s, task_type_test, task_subtype_none, NULL, NULL);
    struct task *b = scheduler_addtask(&s, task_type_test, task_subtype_none, NULL, NULL);
    struct task *c = scheduler_addtask(&s, task_type_test, task_subtype_none, NULL, NULL);
    scheduler_addunlock(&s, a, b);
    scheduler_addunlock(&s, b, c);
    scheduler_addunlock(&s, c, b);
    scheduler_finalize(&s);
    _exit(0); /* not reached if the cycle was found */
  }
  int status;
  waitpid(pid, &status, 0);
  CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 1, "a cyclic graph was accepted (status %d)",
        status);
}

/** Work of the --dump demo: a few microseconds per task. */
static void test_demo_work(void *ctx, struct task *t, int thread_id) {
  volatile double x = 0;
  for (int i = 0; i < 2000 * (1 + (int)t->subtype); i++) x += i;
}

#ifdef BOLIDE_DEBUG_CHECKS
/** Debug checks: a task whose lock is never free must be reported as a
 *  deadlock (error_bug exits), not hang: run it in a child process. */
static void test_deadlock_detection(void) {
  fflush(stdout);
  fflush(stderr);
  pid_t pid = fork();
  if (pid == 0) {
    if (!freopen("/dev/null", "w", stderr)) _exit(3);
    struct scheduler s;
    scheduler_init(&s, 2);
    s.deadlock_seconds = 0.5;
    static struct sched_lock lock;
    sched_lock_init(&lock);
    sched_lock_try(&lock); /* held by nobody that will ever release it */
    struct task *a = scheduler_addtask(&s, task_type_test, task_subtype_none, NULL, NULL);
    struct task *b = scheduler_addtask(&s, task_type_test, task_subtype_none, NULL, NULL);
    b->locks[0] = &lock;
    scheduler_addunlock(&s, a, b);
    scheduler_finalize(&s);
    scheduler_run(&s, test_demo_work, NULL);
    _exit(0); /* not reached if the deadlock was found */
  }
  int status;
  waitpid(pid, &status, 0);
  CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 1, "a deadlock was not detected (status %d)",
        status);
}
#endif

/** --dump FILE: a graph shaped like one SPH step on 32 "cells", 2 threads;
 *  print timers, write the dump, check it has one sane line per task. */
static int test_dump(const char *path) {
  enum { NC = 32 };
  struct scheduler s;
  scheduler_init(&s, 2);
  struct task *drift[NC], *ghost[NC], *kick[NC];
  static int cells[NC];
  for (int c = 0; c < NC; c++) {
    drift[c] = scheduler_addtask(&s, task_type_drift, task_subtype_none, &cells[c], NULL);
    ghost[c] = scheduler_addtask(&s, task_type_ghost, task_subtype_none, &cells[c], NULL);
    kick[c] = scheduler_addtask(&s, task_type_kick2, task_subtype_none, &cells[c], NULL);
    drift[c]->cell_index = ghost[c]->cell_index = kick[c]->cell_index = c;
  }
  static struct sched_lock locks[NC];
  for (int c = 0; c < NC; c++) sched_lock_init(&locks[c]);
  for (int sub = task_subtype_density; sub <= task_subtype_force; sub += 2)
    for (int c = 0; c < NC; c++)
      for (int d = 0; d < 2; d++) { /* self, and pair with the next cell */
        const int c2 = (c + d) % NC;
        struct task *t = scheduler_addtask(&s, d ? task_type_pair : task_type_self, sub, &cells[c],
                                           d ? &cells[c2] : NULL);
        t->cell_index = c;
        t->locks[0] = &locks[c];
        t->locks[1] = &locks[c2];
        /* drift -> density -> ghost -> force -> kick */
        struct task *before = sub == task_subtype_density ? drift[c] : ghost[c];
        struct task *after = sub == task_subtype_density ? ghost[c] : kick[c];
        scheduler_addunlock(&s, before, t);
        scheduler_addunlock(&s, t, after);
        if (d) {
          scheduler_addunlock(&s, sub == task_subtype_density ? drift[c2] : ghost[c2], t);
          scheduler_addunlock(&s, t, sub == task_subtype_density ? ghost[c2] : kick[c2]);
        }
      }
  scheduler_finalize(&s);
  for (int run = 0; run < 3; run++) scheduler_run(&s, test_demo_work, NULL);
  scheduler_print_timers(&s, stdout);

  char tmp[4096];
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  FILE *f = fopen(tmp, "w");
  if (!f) error_exit("cannot write %s", tmp);
  if (scheduler_dump_tasks(&s, f) != 0 || fclose(f) != 0) error_exit("cannot write %s", tmp);
  if (rename(tmp, path) != 0) error_exit("cannot rename %s to %s", tmp, path);

  f = fopen(path, "r");
  if (!f) error_exit("cannot read %s", path);
  char line[256];
  int lines = 0;
  while (fgets(line, sizeof line, f)) {
    if (line[0] == '#') continue;
    int rid, cell;
    double t0, t1;
    char type[64], subtype[64];
    CHECK(sscanf(line, "%d %lf %lf %63s %63s %d", &rid, &t0, &t1, type, subtype, &cell) == 6,
          "bad dump line: %s", line);
    CHECK(rid >= 0 && rid < 2 && t0 >= 0 && t1 >= t0 && cell >= 0 && cell < NC, "bad dump line: %s",
          line);
    lines++;
  }
  fclose(f);
  CHECK(lines == s.nr_tasks, "%d lines in the dump for %d tasks", lines, s.nr_tasks);
  scheduler_free(&s);
  return test_failures ? 1 : 0;
}

/** The watchdog: a deadlock (or a very slow machine) fails the test. */
static void test_alarm(int sig) {
  static const char msg[] = "FAIL: watchdog: the scheduler test did not finish in time\n";
  if (write(2, msg, sizeof msg - 1) < 0) _exit(1);
  _exit(1);
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  if (argc == 3 && strcmp(argv[1], "--dump") == 0) return test_dump(argv[2]);
  signal(SIGALRM, test_alarm);
  alarm(300); /* a hang detector: 16 threads on 2 loaded cores take ~90 s */

  test_cycle();
#ifdef BOLIDE_DEBUG_CHECKS
  test_deadlock_detection();
#endif

  static const int threads[] = {1, 2, 3, 4, 8, 16};
  unsigned rng = 12345;
  int runs = 0, graphs = 0;
  for (size_t k = 0; k < sizeof threads / sizeof threads[0]; k++) {
    struct scheduler s;
    scheduler_init(&s, threads[k]);
    for (int g = 0; g < 250; g++) {
      /* mostly small graphs (many repetitions), now and then a big one */
      const int n = (g % 25 == 24) ? 1000 + test_rand(&rng) % 2000 : 1 + test_rand(&rng) % 200;
      /* first run: everything active, or all skipped, or a random subset */
      const int pskip0 = g % 10 == 0 ? 100 : g % 3 == 0 ? 30 : 0;
      runs += test_random_graph(&s, n, &rng, 3, pskip0);
      graphs++;
    }
    scheduler_free(&s);
  }
  printf("%d graphs, %d runs, %d failures\n", graphs, runs, test_failures);
  return test_failures ? 1 : 0;
}
