/* The drift family's task (tasks/task_families.h): first half kick and
 * drift of a task cell (drift_cpu.c); and its hook after the initial
 * conditions. */
#include "tasks/drift/drift_cpu.h"
#include "src/engine.h"
#include "tasks/drift/drift.h"

void drift_task(struct engine *e, struct task *t) {
  if (((const struct cell *)t->ci)->foreign) return; /* (MPI: copies, src/mpi/halo.c) */
  if (e->stage)
    e->stage_err[t->cell_index] = drift_cell_stage_cpu(&e->parts, t->ci, e->stage, &e->hp);
  else if (e->individual)
    drift_cell_bins_cpu(&e->parts, t->ci, &e->timeline, e->ti_current, e->ti_next, &e->hp, e->mats);
  else
    drift_cell_cpu(&e->parts, t->ci, 0.5 * e->dt, e->dt, e->hp.xsph, e->hp.h_max,
                   e->hp.h_continuity);
}

void drift_sync_ic(struct engine *e) {
  /* the predicted values of the initial conditions are the integrated ones */
  for (size_t i = 0; i < e->parts.count; i++) kick_sync_predicted(&e->parts, i);
}
