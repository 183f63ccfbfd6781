/* The damage family's task (tasks/task_families.h). */
#include "tasks/damage/damage_part.h"
#include "src/engine.h"

/** The damage tasks run where a material is brittle (a chain of the
 *  registry: force -> damage -> kick2). */
int damage_active(const struct engine *e) {
  return e->damage;
}

/** Flaw activation and growth of d^(1/3) in a task cell over the step just
 *  computed (damage_iact.h), from the stress the force loop used. */
void damage_task(struct engine *e, struct task *tk) {
  struct parts *p = &e->parts;
  const struct cell *c = e->tcells[tk->cell_index];
  const double dt = e->first_force ? 0.0 : e->dt;
  if (e->time < e->damage_start) return; /* Damage:start_time: not yet */
  if (ENGINE_CELL_IDLE(e, c)) return;
  for (size_t i = c->offset; i < c->offset + c->count; i++) {
    if (PART_IS_INACTIVE(p, i)) continue;
    /* with time bins over the particle's own step (it ends now) */
    const double dt_i =
        e->individual && !e->first_force ? timeline_dt_of_bin(&e->timeline, p->time_bin[i]) : dt;
    damage_part(p, i, e->mats, e->flaw_eps, dt_i);
  }
}
