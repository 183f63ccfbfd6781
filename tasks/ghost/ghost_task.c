/* The ghost family's task (tasks/task_families.h): the h iteration of a
 * task cell against its neighbouring task cells, then the equation of state
 * (ghost_cpu.c). */
#include <stdatomic.h>

#include "src/engine_tasks.h"
#include "tasks/ghost/ghost_cpu.h"

void ghost_task(struct engine *e, struct task *tk) {
  const int t = tk->cell_index;
  if (ENGINE_CELL_SKIP(e, e->tcells[t])) return;
  struct engine_cell_tasks *ct = &e->ct[t];
  struct cell *cells[ct->nr_ngb > 0 ? ct->nr_ngb : 1];
  double dx_max = 0.0;
  for (int k = 0; k < ct->nr_ngb; k++) {
    cells[k] = e->tcells[ct->ngb[k]];
    if (cells[k]->dx_max > dx_max) dx_max = cells[k]->dx_max;
  }
  struct ghost_ngbs ngbs = {ct->nr_ngb, cells, (const double(*)[3])ct->ngb_shift};
  /* a pair (i, j) is found while H_i + |dx_i| + |dx_j| stays below the reach */
  const double H_limit = engine_H_limit(e) - 2.0 * dx_max;
  long long resummed;
  if (ghost_cell_cpu(&e->parts, e->tcells[t], &ngbs, &e->hp, e->mats, H_limit, &resummed))
    atomic_store((_Atomic int *)&e->need_rebuild, 1);
  if (resummed && !e->first_force) atomic_fetch_add((_Atomic long long *)&e->h_resummed, resummed);
}
