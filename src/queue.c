/* Queues of ready tasks: see queue.h. */
#include "src/queue.h"

#include <stdlib.h>

#include "src/error.h"

void queue_init(struct queue *q) {
  pthread_mutex_init(&q->mutex, NULL);
  q->size = 64;
  q->tasks = error_malloc(q->size * sizeof(struct task *), "task queue");
  atomic_init(&q->count, 0);
}

void queue_free(struct queue *q) {
  pthread_mutex_destroy(&q->mutex);
  free(q->tasks);
  q->tasks = NULL;
  q->size = 0;
}

/** Move entry k up the heap while it is heavier than its parent. */
static void queue_sift_up(struct task **h, int k) {
  struct task *t = h[k];
  while (k > 0 && h[(k - 1) / 2]->weight < t->weight) {
    h[k] = h[(k - 1) / 2];
    k = (k - 1) / 2;
  }
  h[k] = t;
}

/** Move entry k down the heap while a child is heavier. */
static void queue_sift_down(struct task **h, int n, int k) {
  struct task *t = h[k];
  for (;;) {
    int c = 2 * k + 1;
    if (c >= n) break;
    if (c + 1 < n && h[c + 1]->weight > h[c]->weight) c++;
    if (h[c]->weight <= t->weight) break;
    h[k] = h[c];
    k = c;
  }
  h[k] = t;
}

void queue_insert(struct queue *q, struct task *t) {
  pthread_mutex_lock(&q->mutex);
  int n = atomic_load_explicit(&q->count, memory_order_relaxed);
  if (n == q->size) {
    q->size *= 2;
    q->tasks = error_realloc(q->tasks, q->size * sizeof(struct task *), "task queue");
  }
  q->tasks[n] = t;
  queue_sift_up(q->tasks, n);
  atomic_store(&q->count, n + 1);
  pthread_mutex_unlock(&q->mutex);
}

struct task *queue_gettask(struct queue *q) {
  if (atomic_load_explicit(&q->count, memory_order_relaxed) == 0) return NULL;
  pthread_mutex_lock(&q->mutex);
  int n = atomic_load_explicit(&q->count, memory_order_relaxed);
  struct task *t = NULL;
  /* array order is roughly weight order: the first lockable task is a heavy one */
  for (int k = 0; k < n; k++) {
    if (!task_lock(q->tasks[k])) continue;
    t = q->tasks[k];
    /* remove entry k: the last entry takes its place, then restore the heap */
    q->tasks[k] = q->tasks[n - 1];
    n--;
    if (k < n) {
      queue_sift_down(q->tasks, n, k);
      queue_sift_up(q->tasks, k);
    }
    break;
  }
  atomic_store(&q->count, n);
  pthread_mutex_unlock(&q->mutex);
  return t;
}
