/* The kick family's task (tasks/task_families.h). */
#include "damage/damage_part.h"
#include "engine.h"
#include "kick/kick_cpu.h"
#include "kick/kick_porous.h"

/** Second half kick and new time step of a task cell: the gravitational
 *  acceleration joins the hydrodynamic one here (the two families
 *  accumulate apart, engine_graph.c), and the gravitational time-step
 *  criterion joins the hydrodynamic ones. */
void kick2_task(struct engine *e, struct task *tk) {
  const int t = tk->cell_index;
  struct parts *p = &e->parts;
  const struct cell *c = e->tcells[t];
  const size_t end = c->offset + c->count;
  if (e->gp.enabled) {
    for (size_t i = c->offset; i < end; i++) {
      if (!e->hp.enabled) p->ax[i] = p->ay[i] = p->az[i] = 0.0;
      p->ax[i] += p->gax[i];
      p->ay[i] += p->gay[i];
      p->az[i] += p->gaz[i];
    }
  }
  /* porous materials: dalpha/dt from the rates of this force loop, the
   * kick, and the kicked state back on the crush curve (kick_porous.h) */
  if (e->porous)
    for (size_t i = c->offset; i < end; i++) kick2_porous_rate(p, i, e->mats);
  double dt = kick2_cell_cpu(p, c, e->first_force ? 0.0 : 0.5 * e->dt, &e->hp, e->mats);
  if (e->porous && !e->first_force)
    for (size_t i = c->offset; i < end; i++) kick2_porous_return(p, i, e->mats, e->hp.continuity);
  if (!e->hp.enabled) dt = 1e300;
  if (e->damage)
    for (size_t i = c->offset; i < end; i++) {
      const double dtd = damage_part_timestep(p, i, e->damage_max_change);
      if (dtd < dt) dt = dtd;
    }
  if (e->gp.enabled && (e->gp.eps > 0.0 || e->gp.h_factor > 0.0))
    for (size_t i = c->offset; i < end; i++) {
      const double ga[3] = {p->gax[i], p->gay[i], p->gaz[i]};
      /* eps_i: the absolute softening or h_factor * h_i */
      const double epsi = gravity_pair_softening(e->gp.eps, e->gp.h_factor, p->h[i], 0.0);
      const double dtg = gravity_timestep(ga, epsi, e->gp.eta);
      if (dtg < dt) dt = dtg;
    }
  e->cell_dt_min[t] = dt;
}
