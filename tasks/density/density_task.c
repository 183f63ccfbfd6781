/* The density family's tasks (tasks/task_families.h): the density sums of
 * a task cell and of a pair of task cells (density_cpu.c).  The
 * accumulators were zeroed by the drift. */
#include "tasks/density/density_cpu.h"
#include "src/engine.h"

void density_self_task(struct engine *e, struct task *t) {
  density_self_cpu(&e->parts, t->ci);
}

void density_pair_task(struct engine *e, struct task *t) {
  /* the pair list holds task cells; ci, cj are those cells */
  density_pair_cpu(&e->parts, t->ci, t->cj, e->pairs[e->task_pair[t->id]].shift);
}
