/* The damage family's task, and its start-up hook: the Weibull flaws
 * (tasks/task_families.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tasks/damage/damage_part.h"
#include "src/engine.h"
#include "src/error.h"
#include "src/io/params.h"
#include "src/materials/material.h"
#include "tasks/damage/flaws.h"

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
  /* (rk2/pc: once per step, at its end; tasks/drift/drift_integrate.c) */
  const double dt = e->first_force || e->stage_eval ? 0.0 : e->dt;
  if (e->time < e->damage_start) return; /* Damage:start_time: not yet */
  if (ENGINE_CELL_SKIP(e, c)) return;
  for (size_t i = c->offset; i < c->offset + c->count; i++) {
    if (PART_IS_INACTIVE(p, i)) continue;
    /* with time bins over the particle's own step (it ends now) */
    const double dt_i =
        e->individual && !e->first_force ? timeline_dt_of_bin(&e->timeline, p->time_bin[i]) : dt;
    damage_part(p, i, e->mats, e->flaw_eps, dt_i);
  }
}

/** Order of particle indices by id (flaws are drawn in id order, so that a
 *  run resumed from a restart file, whose particles are sorted by cell,
 *  draws the same flaws). */
static const int64_t *damage_sort_ids;
static int damage_cmp_by_id(const void *a, const void *b) {
  const int64_t x = damage_sort_ids[*(const size_t *)a], y = damage_sort_ids[*(const size_t *)b];
  return (x > y) - (x < y);
}

/** Weibull flaws for the brittle materials (weibull_k > 0 with a shear
 *  modulus): kept as read from a restart file or the initial conditions,
 *  else drawn from Damage:seed by the procedure of Benz & Asphaug (1995).
 *  Each particle keeps the slice flaw_first .. + n_flaws of e->flaw_eps.
 *  The family's start-up hook (tasks/task_families.h): the particles are
 *  read from e->input_file, the initial conditions or a restart file. */
void damage_init_flaws(struct engine *e) {
  const char *icname = e->input_file;
  if (e->restarted) {
    e->flaws_from = "the restart file";
  } else {
    /* Weibull flaws stored in the ICs (bolide-flaws; FlawThresholds and
     * FlawOffsets in the particle order of the file) */
    struct flaws fl;
    if (flaws_io_read(icname, e->parts.count, &fl)) {
      if (!e->parts.flaw_first) {
        /* (the damage fields are not held: no material takes damage) */
        error_warning(
            "%s: the Weibull flaws of the initial conditions are not used: no "
            "material has weibull_k and shear_modulus",
            icname);
        free(fl.offset);
        free(fl.eps);
      } else {
        for (size_t i = 0; i < e->parts.count; i++) {
          e->parts.flaw_first[i] = fl.offset[i];
          e->parts.n_flaws[i] = (int32_t)(fl.offset[i + 1] - fl.offset[i]);
        }
        e->flaw_eps = fl.eps;
        e->nr_flaws = fl.offset[e->parts.count];
        e->flaws_from = "the initial conditions";
        free(fl.offset);
      }
    }
  }
  for (int k = 0; k < e->mats->n; k++)
    if (material_is_brittle(&e->mats->mats[k])) e->damage = 1;
  struct parts *p = &e->parts;
  const size_t n = p->count;
  if (e->flaw_eps) {
    /* flaws given: particles of materials that take no damage keep theirs unused */
    size_t idle = 0, bare = 0;
    for (size_t i = 0; i < n; i++) {
      const struct material *mat = material_table_find(e->mats, p->mat[i]);
      const int brittle = mat && material_is_brittle(mat);
      idle += !brittle && p->n_flaws[i] > 0;
      bare += brittle && p->n_flaws[i] == 0;
    }
    if (idle && !e->restarted)
      error_warning(
          "%s: %zu particles have flaws but a material without weibull_k or shear_modulus: "
          "they take no damage",
          icname, idle);
    if (bare && !e->restarted)
      error_warning("%s: %zu particles of brittle materials have no flaws: they take no damage",
                    icname, bare);
  }
  if (!e->damage) return;
  if (!e->flaw_eps) {
    size_t *order = error_malloc(n * sizeof(size_t), "flaw order");
    for (size_t i = 0; i < n; i++) order[i] = i;
    damage_sort_ids = p->id;
    qsort(order, n, sizeof(size_t), damage_cmp_by_id);
    int32_t *mat = error_malloc(n * sizeof(int32_t), "flaw order");
    double *m = error_malloc(n * sizeof(double), "flaw order"),
           *rho = error_malloc(n * sizeof(double), "flaw order");
    for (size_t k = 0; k < n; k++) {
      mat[k] = p->mat[order[k]];
      m[k] = p->m[order[k]];
      rho[k] = p->rho[order[k]];
    }
    struct flaws fl;
    e->nr_flaws = flaws_generate_materials(n, mat, m, rho, e->mats,
                                           (uint64_t)params_get_int(e->params, "Damage:seed"), &fl);
    for (size_t k = 0; k < n; k++) {
      const size_t i = order[k];
      p->flaw_first[i] = fl.offset[k];
      p->n_flaws[i] = (int32_t)(fl.offset[k + 1] - fl.offset[k]);
    }
    e->flaw_eps = fl.eps;
    fl.eps = NULL;
    free(fl.offset);
    free(order);
    free(mat);
    free(m);
    free(rho);
  }
  if (!e->restarted)
    for (size_t i = 0; i < n; i++)
      if (p->dmg[i] > 0.0 && !(p->dcbrt[i] > 0.0)) p->dcbrt[i] = cbrt(p->dmg[i]);
  e->damage_max_change = params_get_real(e->params, "Damage:max_change");
  e->damage_start = params_get_real(e->params, "Damage:start_time");
  char from[64];
  snprintf(from, sizeof from, "Damage:seed %ld", params_get_int(e->params, "Damage:seed"));
  error_log(0, "damage: %lld Weibull flaws (%.1f per particle, %.1f MiB) from %s",
            (long long)e->nr_flaws, n ? (double)e->nr_flaws / (double)n : 0.0,
            (double)e->nr_flaws * sizeof(double) / 1048576.0, e->flaws_from ? e->flaws_from : from);
  if (e->damage_start > 0.0)
    error_log(0, "damage: no flaw activation or growth before t = %g (Damage:start_time)",
              e->damage_start);
  if (!e->hp.solids)
    error_warning("brittle materials without strength: damage has no stress to act on");
}
