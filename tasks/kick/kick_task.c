/* The kick family's task, and the message that names what set a time step
 * below dt_min (kick_dt_culprit, an entry of tasks/task_families.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "src/engine.h"
#include "tasks/kick/kick_cpu.h"
#include "tasks/kick/timestep.h"

/** Second half kick and new time step of a task cell (kick2_part, the same
 *  function as the GPU's): the smallest time step of its particles into
 *  e->cell_dt_min, their counts by time bin into e->cell_bins; with
 *  individual time steps only the particles whose step ends now
 *  (kick2_cell_bins_cpu), the cell's earliest step end into e->cell_kick.
 *  With TimeIntegration:scheme rk2 or pc nothing is kicked (the drift's
 *  stages put the states; tasks/drift/drift_integrate.c): the rates and the time
 *  step only. */
/** What decides the kick and the time step of a particle in this run
 *  (tasks/kick/timestep.h): hydrodynamics, porosity, damage, gravity. */
static void kick_timestep_props(const struct engine *e, struct timestep_props *tp) {
  memset(tp, 0, sizeof *tp);
  tp->hydro = e->hp.enabled;
  tp->porous = e->porous;
  tp->damage_max_change = e->damage ? e->damage_max_change : 0.0;
  tp->gravity = e->gp.enabled;
  tp->grav_eps = e->gp.eps;
  tp->grav_h_factor = e->gp.h_factor;
  tp->grav_eta = e->gp.eta;
}

void kick2_task(struct engine *e, struct task *tk) {
  const int t = tk->cell_index;
  struct timestep_props tp;
  kick_timestep_props(e, &tp);
  int64_t *bins = e->cell_bins + (size_t)t * (TIMELINE_NR_BINS + 1);
  if (e->individual)
    e->cell_dt_min[t] =
        kick2_cell_bins_cpu(&e->parts, e->tcells[t], &e->hp, e->mats, &tp, &e->timeline, e->ti_next,
                            e->first_force, bins, &e->cell_kick[t]);
  else
    e->cell_dt_min[t] =
        kick2_cell_cpu(&e->parts, e->tcells[t],
                       e->first_force || e->scheme != ENGINE_SCHEME_KDK ? 0.0 : 0.5 * e->dt, &e->hp,
                       e->mats, &tp, &e->timeline, bins);
}

/** Which particle and which criterion set the smallest time step (the
 *  criteria of the kick, timestep_part_criteria, recomputed from the state
 *  of the last kick), written into why: the message of the engine when a
 *  step falls below TimeIntegration:dt_min. */
void kick_dt_culprit(const struct engine *e, char *why, size_t len) {
  const struct parts *p = &e->parts;
  struct timestep_props tp;
  kick_timestep_props(e, &tp);
  double best = HUGE_VAL;
  size_t ib = 0;
  int crit = TIMESTEP_NR;
  for (size_t i = 0; i < p->count; i++) {
    double d[TIMESTEP_NR];
    timestep_part_criteria(p, i, &e->hp, e->mats, &tp, d);
    for (int k = 0; k < TIMESTEP_NR; k++)
      if (d[k] < best) {
        best = d[k];
        ib = i;
        crit = k;
      }
  }
  if (p->count == 0) {
    snprintf(why, len, "no particles");
    return;
  }
  const size_t i = ib;
  snprintf(
      why, len,
      "particle id %lld (material %d) at (%g, %g, %g) limited by the %s: h %g, rho %g, u %g, P %g, "
      "c_s %g, v_sig %g, |a| %g, div v %g",
      (long long)p->id[i], (int)p->mat[i], p->x[i], p->y[i], p->z[i], timestep_criterion_name(crit),
      p->h[i], p->rho[i], p->u[i], p->P[i], p->cs[i], p->v_sig[i],
      sqrt(p->ax[i] * p->ax[i] + p->ay[i] * p->ay[i] + p->az[i] * p->az[i]), p->div_v[i]);
}
