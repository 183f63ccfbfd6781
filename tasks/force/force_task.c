/* The force family's tasks (tasks/task_families.h): the forces within a
 * task cell and between a pair of task cells (force_cpu.c).  The
 * accumulators were zeroed by the ghost. */
#include "src/engine.h"
#include "tasks/force/force_cpu.h"

void force_self_task(struct engine *e, struct task *t) {
  if (ENGINE_CELL_SKIP(e, t->ci)) return;
  force_self_cpu(&e->parts, t->ci, &e->hp);
}

void force_pair_task(struct engine *e, struct task *t) {
  if (ENGINE_CELL_SKIP(e, t->ci) && ENGINE_CELL_SKIP(e, t->cj)) return;
  force_pair_cpu(&e->parts, t->ci, t->cj, e->pairs[e->task_pair[t->id]].shift, &e->hp);
}
