/* The ghost family's task (tasks/task_families.h): the h iteration of a
 * task cell against its neighbouring task cells, then the equation of state
 * (ghost_cpu.c). */
#include <stdatomic.h>

#include "src/engine_tasks.h"
#include "tasks/ghost/ghost_cpu.h"

void ghost_task(struct engine *e, struct task *tk) {
  const int t = tk->cell_index;
  const int wakes = e->hp.wake_density && e->individual && !e->first_force;
  if (ENGINE_CELL_SKIP(e, e->tcells[t])) {
    /* (TimeIntegration:limiter_wake: density: a cell none of whose
     * particles ends its step still takes those the density phase woke) */
    const struct cell *c = e->tcells[t];
    int woken = 0;
    if (wakes && !c->foreign)
      for (size_t i = c->offset; i < c->offset + c->count && !woken; i++)
        woken = e->parts.wake[i] > 0;
    if (!woken) return;
  }
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
  const struct ghost_wake gw = {e->ti_current, e->timeline.time_base};
  if (ghost_cell_cpu(&e->parts, e->tcells[t], &ngbs, &e->hp, e->mats, H_limit, wakes ? &gw : NULL,
                     &resummed))
    atomic_store((_Atomic int *)&e->need_rebuild, 1);
  if (resummed && !e->first_force) atomic_fetch_add((_Atomic long long *)&e->h_resummed, resummed);
}
