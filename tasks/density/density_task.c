/* The density family's tasks (tasks/task_families.h): the density sums of
 * a task cell and of a pair of task cells (density_cpu.c).  The
 * accumulators were zeroed by the drift; before the first force
 * computation, by the family's hook (density_reset_all). */
#include "tasks/density/density_cpu.h"
#include "tasks/density/density_wake.h"
#include "src/engine.h"
#include "tasks/hydro_parts.h"

/** With TimeIntegration:limiter_wake: density in a step of time bins,
 *  what the loops need to decide the wakes, in *w; else NULL. */
static const struct density_wake *density_task_wake(const struct engine *e,
                                                    struct density_wake *w) {
  if (!e->hp.wake_density || e->first_force) return NULL;
  *w = (struct density_wake){e->hp.bin_limit, e->hp.solids, e->hp.cfl, e->hp.beta, e->timeline};
  return w;
}

void density_self_task(struct engine *e, struct task *t) {
  if (ENGINE_CELL_SKIP(e, t->ci)) return;
  struct density_wake w;
  density_self_cpu(&e->parts, t->ci, density_task_wake(e, &w));
}

void density_pair_task(struct engine *e, struct task *t) {
  /* the pair list holds task cells; ci, cj are those cells */
  if (ENGINE_CELL_SKIP(e, t->ci) && ENGINE_CELL_SKIP(e, t->cj)) return;
  struct density_wake w;
  density_pair_cpu(&e->parts, t->ci, t->cj, e->pairs[e->task_pair[t->id]].shift,
                   density_task_wake(e, &w));
}

void density_reset_all(struct engine *e) {
  for (size_t i = 0; i < e->parts.count; i++) hydro_density_reset(&e->parts, i);
}
