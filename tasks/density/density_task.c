/* The density family's tasks (tasks/task_families.h): the density sums of
 * a task cell and of a pair of task cells (density_cpu.c).  The
 * accumulators were zeroed by the drift; before the first force
 * computation, by the family's hook (density_reset_all). */
#include "tasks/density/density_cpu.h"
#include "src/engine.h"
#include "tasks/hydro_parts.h"

void density_self_task(struct engine *e, struct task *t) {
  if (ENGINE_CELL_SKIP(e, t->ci)) return;
  density_self_cpu(&e->parts, t->ci);
}

void density_pair_task(struct engine *e, struct task *t) {
  /* the pair list holds task cells; ci, cj are those cells */
  if (ENGINE_CELL_SKIP(e, t->ci) && ENGINE_CELL_SKIP(e, t->cj)) return;
  density_pair_cpu(&e->parts, t->ci, t->cj, e->pairs[e->task_pair[t->id]].shift);
}

void density_reset_all(struct engine *e) {
  for (size_t i = 0; i < e->parts.count; i++) hydro_density_reset(&e->parts, i);
}
