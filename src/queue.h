/* Queues of ready tasks: one per worker thread.
 *
 * A queue is a binary max-heap of tasks ordered by weight (cost of the task
 * plus the longest cost path behind it), protected by a mutex.  Taking a
 * task scans the heap from the top for the first task whose locks can all be
 * taken: a task in conflict stays in the queue for a later try, it is never
 * waited on.  Other workers steal from the queue with the same call. */
#ifndef BOLIDE_QUEUE_H
#define BOLIDE_QUEUE_H

#include <pthread.h>
#include <stdatomic.h>

#include "src/task.h"

/** A heap of ready tasks. */
struct queue {
  pthread_mutex_t mutex; /**< protects tasks and size */
  struct task **tasks;   /**< the heap: tasks[0] has the largest weight */
  int size;              /**< allocated entries */
  atomic_int count;      /**< tasks in the heap (read without the mutex to skip empty queues) */
};

/** An empty queue. */
void queue_init(struct queue *q);

/** Free the queue's memory. */
void queue_free(struct queue *q);

/** Add a ready task. */
void queue_insert(struct queue *q, struct task *t);

/** Remove and return the heaviest task whose locks could all be taken (the
 *  caller owns them), or NULL if the queue is empty or every task in it is in
 *  conflict. */
struct task *queue_gettask(struct queue *q);

#endif
