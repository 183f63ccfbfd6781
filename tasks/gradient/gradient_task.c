/* The gradient family's tasks (tasks/task_families.h): the gradient sums of
 * a task cell and of a pair of task cells, and the extra ghost that closes
 * them (gradient_cpu.c). */
#include "src/engine.h"
#include "tasks/gradient/gradient_cpu.h"

void gradient_self_task(struct engine *e, struct task *t) {
  if (ENGINE_CELL_SKIP(e, t->ci)) return;
  gradient_self_cpu(&e->parts, t->ci);
}

void gradient_pair_task(struct engine *e, struct task *t) {
  if (ENGINE_CELL_SKIP(e, t->ci) && ENGINE_CELL_SKIP(e, t->cj)) return;
  gradient_pair_cpu(&e->parts, t->ci, t->cj, e->pairs[e->task_pair[t->id]].shift);
}

void extra_ghost_task(struct engine *e, struct task *t) {
  if (ENGINE_CELL_SKIP(e, t->ci)) return;
  extra_ghost_cell_cpu(&e->parts, t->ci, &e->hp, e->mats);
}
