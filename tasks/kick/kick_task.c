/* The kick family's task (tasks/task_families.h). */
#include "src/engine.h"
#include "tasks/kick/kick_cpu.h"
#include "tasks/kick/timestep.h"

/** Second half kick and new time step of a task cell (kick2_part, the same
 *  function as the GPU's): the smallest time step of its particles into
 *  e->cell_dt_min, their counts by time bin into e->cell_bins; with
 *  individual time steps only the particles whose step ends now
 *  (kick2_cell_bins_cpu), the cell's earliest step end into e->cell_kick. */
void kick2_task(struct engine *e, struct task *tk) {
  const int t = tk->cell_index;
  struct timestep_props tp;
  engine_timestep_props(e, &tp);
  int64_t *bins = e->cell_bins + (size_t)t * (TIMELINE_NR_BINS + 1);
  if (e->individual)
    e->cell_dt_min[t] =
        kick2_cell_bins_cpu(&e->parts, e->tcells[t], &e->hp, e->mats, &tp, &e->timeline, e->ti_next,
                            e->first_force, bins, &e->cell_kick[t]);
  else
    e->cell_dt_min[t] = kick2_cell_cpu(&e->parts, e->tcells[t], e->first_force ? 0.0 : 0.5 * e->dt,
                                       &e->hp, e->mats, &tp, &e->timeline, bins);
}
