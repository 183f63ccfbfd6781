/* The scheduler's callback: what each task of the engine's graph does. */
#include <stdatomic.h>

#include "damage/damage_part.h"
#include "density/density_cpu.h"
#include "drift/drift_cpu.h"
#include "engine_tasks.h"
#include "error.h"
#include "force/force_cpu.h"
#include "ghost/ghost_cpu.h"
#include "gradient/gradient_cpu.h"
#include "kernel.h"
#include "material.h"
#include "kick/kick_cpu.h"
#include "kick/kick_porous.h"

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

/** The damage task of task cell number t: flaw activation and growth of
 *  d^(1/3) over the step just computed (tasks/damage/damage_iact.h), from
 *  the stress the force loop used. */
static void engine_damage(struct engine *e, int t) {
  struct parts *p = &e->parts;
  const struct cell *c = e->tcells[t];
  const double dt = e->first_force ? 0.0 : e->dt;
  if (e->time < e->damage_start) return; /* Damage:start_time: not yet */
  for (size_t i = c->offset; i < c->offset + c->count; i++) damage_part(p, i, e->mats, e->flaw_eps, dt);
}

/** Second half kick and new time step of task cell number t: the
 *  gravitational acceleration joins the hydrodynamic one here (the two
 *  families accumulate apart, engine_graph.c), and the gravitational
 *  time-step criterion joins the hydrodynamic ones. */
static void engine_kick2(struct engine *e, int t) {
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

/** A gravity walk task: self (cj == ci), near pair, or long range (cj
 *  NULL); records its particle-level interactions when the far field may
 *  be reused, or replays them on a step that reuses it. */
static void engine_gravity_task(struct engine *e, const struct task *t, const struct cell *ci,
                                const struct cell *cj) {
  struct parts *p = &e->parts;
  struct gravity_ilist *il = t->id < e->nr_gilists ? &e->gilists[t->id] : NULL;
  if (e->gp.replay) {
    gravity_replay(p, il, e->gcells, &e->gp);
    return;
  }
  gravity_record_begin(il);
  if (cj)
    gravity_interact_cells(p, ci, cj, e->gcells, &e->gp);
  else
    gravity_long_range(p, ci, e->space.cells, e->space.nr_top, e->gcells, &e->gp);
  gravity_record_end();
}

void engine_run_task(void *ctx, struct task *t, int thread_id) {
  struct engine *e = ctx;
  struct parts *p = &e->parts;
  struct cell *ci = t->ci, *cj = t->cj;
  (void)thread_id;
  switch (t->type) {
    case task_type_drift:
      drift_cell_cpu(p, ci, 0.5 * e->dt, e->dt, e->hp.xsph, e->hp.h_max);
      break;
    case task_type_self:
      /* the accumulators were zeroed by the drift (density) and the ghost (force) */
      if (t->subtype == task_subtype_grav)
        engine_gravity_task(e, t, ci, ci);
      else if (t->subtype == task_subtype_density)
        density_self_cpu(p, ci);
      else if (t->subtype == task_subtype_gradient)
        gradient_self_cpu(p, ci);
      else if (t->subtype == task_subtype_force)
        force_self_cpu(p, ci, &e->hp);
      break;
    case task_type_pair: {
      if (t->subtype == task_subtype_grav) {
        engine_gravity_task(e, t, ci, cj);
        break;
      }
      const double *shift = e->pairs[e->task_pair[t->id]].shift;
      /* the pair list holds task cells; ci, cj are those cells */
      if (t->subtype == task_subtype_density)
        density_pair_cpu(p, ci, cj, shift);
      else if (t->subtype == task_subtype_gradient)
        gradient_pair_cpu(p, ci, cj, shift);
      else if (t->subtype == task_subtype_force)
        force_pair_cpu(p, ci, cj, shift, &e->hp);
      break;
    }
    case task_type_ghost:
      engine_ghost(e, t->cell_index);
      break;
    case task_type_extra_ghost:
      extra_ghost_cell_cpu(p, ci, &e->hp, e->mats);
      break;
    case task_type_kick2:
      engine_kick2(e, t->cell_index);
      break;
    case task_type_grav_up:
      gravity_up(p, ci, e->gcells, &e->gp);
      break;
    case task_type_grav_long_range:
      if (ci)
        engine_gravity_task(e, t, ci, NULL);
      else /* Gravity:direct: exact summation in one task */
        gravity_direct_h(p, e->gp.G, e->gp.eps, e->gp.softening, e->gp.h_factor, 1);
      break;
    case task_type_grav_down:
      gravity_down(p, ci, e->gcells, &e->gp);
      break;
    case task_type_implicit:
      break;
    case task_type_damage:
      engine_damage(e, t->cell_index);
      break;
    default:
      error_bug("the engine has no work for task type %s", task_type_names[t->type]);
  }
}
