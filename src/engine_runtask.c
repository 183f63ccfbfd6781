/* The scheduler's callback: what each task of the engine's graph does. */
#include <stdatomic.h>

#include "density/density_cpu.h"
#include "drift/drift_cpu.h"
#include "engine_tasks.h"
#include "error.h"
#include "force/force_cpu.h"
#include "ghost/ghost_cpu.h"
#include "kernel.h"
#include "kick/kick_cpu.h"

/** The largest kernel support the current cells and task graph allow. */
double engine_H_limit(const struct engine *e) {
  const struct space *s = &e->space;
  double w = e->reach;
  if (s->periodic)
    for (int k = 0; k < 3; k++)
      if (0.5 * s->dim[k] < w) w = 0.5 * s->dim[k];
  return w;
}

/** The ghost task of task cell number t. */
static void engine_ghost(struct engine *e, int t) {
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
  if (ghost_cell_cpu(&e->parts, e->tcells[t], &ngbs, &e->hp, e->mats, H_limit))
    atomic_store((_Atomic int *)&e->need_rebuild, 1);
}

void engine_run_task(void *ctx, struct task *t, int thread_id) {
  struct engine *e = ctx;
  struct parts *p = &e->parts;
  struct cell *ci = t->ci, *cj = t->cj;
  (void)thread_id;
  switch (t->type) {
    case task_type_drift:
      drift_cell_cpu(p, ci, 0.5 * e->dt, e->dt);
      break;
    case task_type_self:
      /* the accumulators were zeroed by the drift (density) and the ghost (force) */
      if (t->subtype == task_subtype_density)
        density_self_cpu(p, ci);
      else if (t->subtype == task_subtype_force)
        force_self_cpu(p, ci, &e->hp);
      break;
    case task_type_pair: {
      const double *shift = e->pairs[e->task_pair[t->id]].shift;
      /* the pair list holds task cells; ci, cj are those cells */
      if (t->subtype == task_subtype_density)
        density_pair_cpu(p, ci, cj, shift);
      else if (t->subtype == task_subtype_force)
        force_pair_cpu(p, ci, cj, shift, &e->hp);
      break;
    }
    case task_type_ghost:
      engine_ghost(e, t->cell_index);
      break;
    case task_type_kick2:
      e->cell_dt_min[t->cell_index] = kick2_cell_cpu(p, ci, e->first_force ? 0.0 : 0.5 * e->dt, &e->hp);
      break;
    default:
      error_bug("the engine has no work for task type %s", task_type_names[t->type]);
  }
}
