/* The task graph of the engine, built on the top-level cells after every
 * rebuild:
 *
 *   drift(c)                                        phase DRIFT
 *   density(c,c'), density(c) -> ghost(c)           phase FORCE
 *   ghost(c), ghost(c') -> force(c,c') -> kick2(c)
 *
 * and with solids (a material with strength: e->hp.solids) the gradient
 * loop sits between the ghost and the force:
 *
 *   ghost(c), ghost(c') -> gradient(c,c') -> extra_ghost(c), extra_ghost(c')
 *   extra_ghost(c), extra_ghost(c') -> force(c,c')
 *
 * Pair tasks lock the cells they write (try-locks in the scheduler); the
 * ghost of a cell waits for every density task touching it, so that the h
 * iteration of a cell reads final neighbour positions and writes only its
 * own particles. */
#include "engine.h"

#include <stdlib.h>
#include <string.h>

#include "error.h"

/** Remember t as part of phase ph. */
static void engine_phase_add(struct engine *e, int ph, struct task *t, int *cap) {
  if (e->phase_count[ph] == cap[ph]) {
    cap[ph] = cap[ph] ? 2 * cap[ph] : 1024;
    e->phase_tasks[ph] = error_realloc(e->phase_tasks[ph], cap[ph] * sizeof(struct task *), "task lists");
  }
  e->phase_tasks[ph][e->phase_count[ph]++] = t;
}

/** Remember that task t works on pair number k (e->task_pair[t->id] = k). */
static void engine_task_pair_set(struct engine *e, const struct task *t, int k, int *cap) {
  if (t->id >= *cap) {
    const int n = 2 * t->id + 1024;
    e->task_pair = error_realloc(e->task_pair, n * sizeof(int), "task pairs");
    *cap = n;
  }
  e->task_pair[t->id] = k;
}

/** Record cj (with shift) as a neighbour of ci. */
static void engine_add_ngb(struct engine_cell_tasks *ct, int cj, const double shift[3]) {
  ct->ngb = error_realloc(ct->ngb, (ct->nr_ngb + 1) * sizeof(int), "cell neighbours");
  ct->ngb_shift = error_realloc(ct->ngb_shift, (ct->nr_ngb + 1) * sizeof(double[3]), "cell neighbours");
  ct->ngb[ct->nr_ngb] = cj;
  for (int k = 0; k < 3; k++) ct->ngb_shift[ct->nr_ngb][k] = shift[k];
  ct->nr_ngb++;
}

/** Free the per-cell task records. */
static void engine_graph_free(struct engine *e) {
  if (e->ct) {
    for (int c = 0; c < e->nr_ct; c++) {
      free(e->ct[c].ngb);
      free(e->ct[c].ngb_shift);
    }
    free(e->ct);
    e->ct = NULL;
    e->nr_ct = 0;
  }
  for (int ph = 0; ph < 2; ph++) {
    free(e->phase_tasks[ph]);
    e->phase_tasks[ph] = NULL;
    e->phase_count[ph] = 0;
  }
}

void engine_make_graph(struct engine *e) {
  struct space *s = &e->space;
  struct scheduler *sched = &e->sched;
  engine_graph_free(e);
  scheduler_clear(sched);
  const int nc = s->nr_top;
  e->ct = error_calloc(nc, sizeof(struct engine_cell_tasks), "cell tasks");
  e->nr_ct = nc;
  free(e->pairs);
  e->pairs = NULL;
  e->cell_dt_min = error_realloc(e->cell_dt_min, nc * sizeof(double), "cell time steps");
  e->cell_dx_max = error_realloc(e->cell_dx_max, nc * sizeof(double), "cell drifts");
  int cap[2] = {0, 0};

  /* per-cell tasks */
  for (int c = 0; c < nc; c++) {
    struct cell *ci = &s->cells[c];
    struct engine_cell_tasks *ct = &e->ct[c];
    const double zero[3] = {0, 0, 0};
    engine_add_ngb(ct, c, zero);
    ct->drift = scheduler_addtask(sched, task_type_drift, task_subtype_none, ci, NULL);
    ct->drift->cell_index = c;
    engine_phase_add(e, ENGINE_PHASE_DRIFT, ct->drift, cap);
    if (ci->count == 0) continue;
    ct->ghost = scheduler_addtask(sched, task_type_ghost, task_subtype_none, ci, NULL);
    ct->kick2 = scheduler_addtask(sched, task_type_kick2, task_subtype_none, ci, NULL);
    engine_phase_add(e, ENGINE_PHASE_FORCE, ct->ghost, cap);
    engine_phase_add(e, ENGINE_PHASE_FORCE, ct->kick2, cap);

    /* density(c) -> ghost(c);  ghost(c) -> force(c) -> kick2(c) */
    struct task *ds = scheduler_addtask(sched, task_type_self, task_subtype_density, ci, NULL);
    struct task *fs = scheduler_addtask(sched, task_type_self, task_subtype_force, ci, NULL);
    ds->locks[0] = fs->locks[0] = &ci->lock;
    ds->cell_index = fs->cell_index = ct->ghost->cell_index = ct->kick2->cell_index = c;
    scheduler_addunlock(sched, ds, ct->ghost);
    scheduler_addunlock(sched, fs, ct->kick2);
    engine_phase_add(e, ENGINE_PHASE_FORCE, ds, cap);
    engine_phase_add(e, ENGINE_PHASE_FORCE, fs, cap);
    if (e->hp.solids) {
      /* ghost(c) -> gradient(c) -> extra_ghost(c) -> force(c) */
      ct->extra_ghost = scheduler_addtask(sched, task_type_extra_ghost, task_subtype_none, ci, NULL);
      struct task *gs = scheduler_addtask(sched, task_type_self, task_subtype_gradient, ci, NULL);
      gs->locks[0] = &ci->lock;
      gs->cell_index = ct->extra_ghost->cell_index = c;
      scheduler_addunlock(sched, ct->ghost, gs);
      scheduler_addunlock(sched, gs, ct->extra_ghost);
      scheduler_addunlock(sched, ct->extra_ghost, fs);
      engine_phase_add(e, ENGINE_PHASE_FORCE, gs, cap);
      engine_phase_add(e, ENGINE_PHASE_FORCE, ct->extra_ghost, cap);
    } else {
      scheduler_addunlock(sched, ct->ghost, fs);
    }
  }

  /* pair tasks between neighbouring top-level cells */
  struct space_pair *pairs = NULL;
  const int np = (int)space_top_pairs(s, &pairs);
  int cap_tp = 0;
  for (int k = 0; k < np; k++) {
    const int a = pairs[k].ci, b = pairs[k].cj;
    struct cell *ci = &s->cells[a], *cj = &s->cells[b];
    double mshift[3];
    for (int d = 0; d < 3; d++) mshift[d] = -pairs[k].shift[d];
    engine_add_ngb(&e->ct[a], b, pairs[k].shift);
    engine_add_ngb(&e->ct[b], a, mshift);
    if (ci->count == 0 || cj->count == 0) continue;
    struct task *dp = scheduler_addtask(sched, task_type_pair, task_subtype_density, ci, cj);
    struct task *fp = scheduler_addtask(sched, task_type_pair, task_subtype_force, ci, cj);
    dp->locks[0] = fp->locks[0] = &ci->lock;
    /* a cell paired with its own periodic image takes its lock once */
    dp->locks[1] = fp->locks[1] = (a == b) ? NULL : &cj->lock;
    dp->cell_index = fp->cell_index = a;
    engine_task_pair_set(e, dp, k, &cap_tp);
    engine_task_pair_set(e, fp, k, &cap_tp);
    /* density(ci,cj) -> ghost(ci), ghost(cj);  force(ci,cj) -> kick2(ci), kick2(cj) */
    scheduler_addunlock(sched, dp, e->ct[a].ghost);
    scheduler_addunlock(sched, dp, e->ct[b].ghost);
    scheduler_addunlock(sched, fp, e->ct[a].kick2);
    scheduler_addunlock(sched, fp, e->ct[b].kick2);
    engine_phase_add(e, ENGINE_PHASE_FORCE, dp, cap);
    engine_phase_add(e, ENGINE_PHASE_FORCE, fp, cap);
    if (e->hp.solids) {
      /* ghost(ci), ghost(cj) -> gradient(ci,cj) -> extra_ghost(ci), extra_ghost(cj) -> force(ci,cj) */
      struct task *gp = scheduler_addtask(sched, task_type_pair, task_subtype_gradient, ci, cj);
      gp->locks[0] = &ci->lock;
      gp->locks[1] = (a == b) ? NULL : &cj->lock;
      gp->cell_index = a;
      engine_task_pair_set(e, gp, k, &cap_tp);
      scheduler_addunlock(sched, e->ct[a].ghost, gp);
      scheduler_addunlock(sched, e->ct[b].ghost, gp);
      scheduler_addunlock(sched, gp, e->ct[a].extra_ghost);
      scheduler_addunlock(sched, gp, e->ct[b].extra_ghost);
      scheduler_addunlock(sched, e->ct[a].extra_ghost, fp);
      scheduler_addunlock(sched, e->ct[b].extra_ghost, fp);
      engine_phase_add(e, ENGINE_PHASE_FORCE, gp, cap);
    } else {
      /* ghost(ci), ghost(cj) -> force(ci,cj) */
      scheduler_addunlock(sched, e->ct[a].ghost, fp);
      scheduler_addunlock(sched, e->ct[b].ghost, fp);
    }
  }
  e->pairs = pairs;
  e->nr_pairs = np;
  scheduler_finalize(sched);
  error_log(1, "task graph: %d cells, %d pairs, %d tasks", nc, np, sched->nr_tasks);
}

void engine_activate_phase(struct engine *e, int phase) {
  struct scheduler *sched = &e->sched;
  for (int k = 0; k < sched->nr_tasks; k++) scheduler_task(sched, k)->skip = 1;
  for (int k = 0; k < e->phase_count[phase]; k++) e->phase_tasks[phase][k]->skip = 0;
}

void engine_graph_clean(struct engine *e) {
  engine_graph_free(e);
  free(e->pairs);
  e->pairs = NULL;
  free(e->task_pair);
  e->task_pair = NULL;
}
