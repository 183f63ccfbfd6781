/* Self-gravity's part of the engine outside its tasks (tasks/task_families.h:
 * the hooks gravity_engine_init and gravity_engine_clean, the entry points
 * gravity_*): its settings and state, the per-cell data and interaction
 * lists at each rebuild of the task graph, the far field that steps reuse
 * (Gravity:reuse_steps) and its place in the restart file.  The engine
 * (src/engine.c, src/engine_graph.c) holds the state behind e->grav and calls
 * these through the registry. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "src/engine.h"
#include "src/error.h"
#include "src/runner.h"
#include "tasks/gravity/gravity_state.h"
#include "tasks/gravity/gravity_walk.h"

void gravity_engine_init(struct engine *e) {
  gravity_props_init(&e->gp, e->params, &e->us);
  e->grav = error_calloc(1, sizeof *e->grav, "gravity state");
}

void gravity_engine_clean(struct engine *e) {
  struct gravity_state *g = e->grav;
  if (!g) return;
  free(g->cells);
  free(g->active);
  free(g->x0);
  free(g->remote);
  free(g->remote_idx);
  free(g->remote_partial);
  free(g->tops_used);
  restart_gravity_free(&g->restart);
  free(g);
  e->grav = NULL;
}

int64_t gravity_cell_doubles(void) {
  return (int64_t)(sizeof(struct gravity_cell) / sizeof(double));
}

/** gp.tops_used: the top-level cells with particles here or a record
 *  (gp.remote_idx), which the long-range walks visit; at each rebuild and
 *  each exchange of records, the only times either changes. */
static void gravity_tops_used_update(struct engine *e) {
  struct gravity_state *g = e->grav;
  const int nt = e->space.nr_top;
  if (g->tops_used_cap < nt) {
    g->tops_used = error_realloc(g->tops_used, (size_t)nt * sizeof(int), "gravity top-level cells");
    g->tops_used_cap = nt;
  }
  int n = 0;
  for (int c = 0; c < nt; c++)
    if (e->space.cells[c].count > 0 || (e->gp.remote_idx && e->gp.remote_idx[c] >= 0))
      g->tops_used[n++] = c;
  e->gp.tops_used = g->tops_used;
  e->gp.nr_tops_used = n;
  e->gp.tops_base = e->space.cells;
  e->gp.nr_tops = nt;
}

void gravity_graph_made(struct engine *e, int nr_tasks) {
  struct gravity_state *g = e->grav;
  const int cap = g->cells_cap;
  g->cells = gravity_cells_reserve(g->cells, &g->cells_cap, e->space.cells_capacity);
  if (g->cells_cap != cap || !g->active)
    g->active =
        error_realloc(g->active, (size_t)(g->cells_cap ? g->cells_cap : 1), "gravity active cells");
  if (e->gp.reuse_steps > 0) {
    /* the gravity tasks are the first nr_tasks: one list each */
    g->nr_lists = nr_tasks;
    g->lists = error_calloc(g->nr_lists, sizeof *g->lists, "gravity interaction lists");
  }
  gravity_tops_used_update(e);
}

void gravity_graph_free(struct engine *e) {
  struct gravity_state *g = e->grav;
  if (!g) return;
  for (int k = 0; k < g->nr_lists; k++) gravity_ilist_free(&g->lists[k]);
  free(g->lists);
  g->lists = NULL;
  g->nr_lists = 0;
}

int gravity_estimate_first(struct engine *e) {
  if (!e->gp.enabled) return 0;
  /* the estimate's threads would inherit thread 0's one core: spread them
   * (pinned, the 16 threads of a GPU host's run shared one core, and the
   * estimate took 15 s at 1.1e6 particles and more than 290 s at 1.1e7) */
  if (e->nr_threads > 1) runner_unpin_self(&e->sched.pool);
  const double w0 = error_walltime();
  const int done = gravity_estimate(&e->parts, e->space.cells, e->space.nr_top, e->grav->cells,
                                    &e->gp, e->nr_threads);
  if (e->nr_threads > 1) runner_repin_self(&e->sched.pool);
  if (done)
    error_log(1, "gravity: the first evaluation's scale of |a| estimated on the host in %.3f s",
              error_walltime() - w0);
  return done;
}

/** With individual time steps (TimeIntegration:global_step: false) on
 *  the CPU: whether the coming FORCE phase computes gravity only for the
 *  cells that hold a particle ending its step (sets e->gp.active; NULL:
 *  every cell).  The particles in the middle of their step keep the
 *  acceleration and potential of their last evaluation, which nothing
 *  reads until their step ends (the kick adds it only to particles that
 *  end their step); `full` (an output follows: statistics and snapshots
 *  need every potential) computes all.  Such a step is not a full
 *  evaluation for the far-field reuse (Gravity:reuse_steps): it drops the
 *  far field kept for it.  The GPU runner does the same on the device when
 *  its walks run there (Scheduler:gpu_walks: device, the default), and
 *  computes all otherwise. */
void gravity_active_decide(struct engine *e, int full) {
  struct gravity_state *g = e->grav;
  e->gp.active = NULL;
  e->gp.active_step = 0;
  if (!e->gp.enabled || !e->gp.active_only || e->gp.direct || !e->individual || e->first_force ||
      full)
    return;
  e->gp.active_step = 1;
  if (!e->gpu) e->gp.active = g->active; /* (the GPU runner marks its cells on the device) */
  e->gp.active_ti = e->ti_current;
  g->active_steps++;
  g->d_min = HUGE_VAL; /* (no replay of a far field these steps overwrite) */
}

/** Whether the coming force phase may reuse the gravitational far field of
 *  the last full evaluation (Gravity:reuse_steps, gravity_cpu.h): not after
 *  a rebuild, not more than reuse_steps times in a row, and only while
 *  every particle has moved less than reuse_tolerance times the shortest
 *  far-field distance of that evaluation.  Sets e->gp.replay. */
void gravity_reuse_decide(struct engine *e, int rebuilt) {
  struct gravity_state *g = e->grav;
  e->gp.replay = 0;
  if (!e->gp.enabled || e->gp.direct || e->gp.reuse_steps <= 0 || g->x0 == NULL || rebuilt ||
      e->gp.active_step || g->reused >= e->gp.reuse_steps || !(g->d_min < HUGE_VAL))
    return;
  const struct parts *p = &e->parts;
  const double *x0 = g->x0;
  double d2max = 0.0;
  for (size_t i = 0; i < p->count; i++) {
    const double dx = p->x[i] - x0[3 * i], dy = p->y[i] - x0[3 * i + 1],
                 dz = p->z[i] - x0[3 * i + 2];
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 > d2max) d2max = d2;
  }
  const double lim = e->gp.reuse_tol * g->d_min;
  if (d2max < lim * lim) {
    e->gp.replay = 1;
    g->reused++;
    g->replays++;
  }
}

/** After a force phase that evaluated gravity in full (reuse on): remember
 *  the positions and the shortest far-field distance of the walks. */
void gravity_reuse_remember(struct engine *e) {
  if (!e->gp.enabled || e->gp.direct || e->gp.reuse_steps <= 0 || e->gp.replay || e->gp.active_step)
    return;
  struct gravity_state *g = e->grav;
  const struct parts *p = &e->parts;
  g->x0 = error_realloc(g->x0, 3 * (p->count ? p->count : 1) * sizeof(double),
                        "gravity reuse positions");
  for (size_t i = 0; i < p->count; i++) {
    g->x0[3 * i] = p->x[i];
    g->x0[3 * i + 1] = p->y[i];
    g->x0[3 * i + 2] = p->z[i];
  }
  g->d_min = HUGE_VAL;
  for (int k = 0; k < g->nr_lists; k++)
    if (g->lists[k].d_min > 0.0 && g->lists[k].d_min < g->d_min) g->d_min = g->lists[k].d_min;
  g->reused = 0;
}

/** The far field that the coming steps may reuse, for the restart file
 *  (r->present 0: none; CPU runs only, the GPU's stays on the device):
 *  the positions and shortest distance of the last full evaluation, the
 *  multipole and local expansion of every cell with particles (the walks
 *  skip empty cells, and gravity_up leaves those below the top level
 *  unset) and every task's interaction list (cells by index).  Free with
 *  restart_gravity_free. */
void gravity_restart_save(const struct engine *e, struct restart_gravity *r) {
  const struct gravity_state *g = e->grav;
  memset(r, 0, sizeof *r);
  if (!e->gp.enabled || e->gp.direct || e->gp.reuse_steps <= 0 || !g->x0 ||
      !(g->d_min < HUGE_VAL) || e->gpu || g->nr_lists < 1)
    return;
  const struct parts *p = &e->parts;
  const int nc = e->space.nr_cells;
  r->present = 1;
  r->reused = g->reused;
  r->replays = g->replays;
  r->d_min = g->d_min;
  r->x0 = error_malloc(3 * (p->count ? p->count : 1) * sizeof(double), "restart far field");
  memcpy(r->x0, g->x0, 3 * p->count * sizeof(double));
  r->nr_cells = nc;
  r->cell_doubles = sizeof(struct gravity_cell) / sizeof(double);
  r->cell_index =
      error_malloc(((size_t)nc ? (size_t)nc : 1) * sizeof(int32_t), "restart far field");
  r->cells = error_malloc(((size_t)nc ? (size_t)nc : 1) * sizeof(struct gravity_cell),
                          "restart far field");
  for (int c = 0; c < nc; c++)
    if (e->space.cells[c].count > 0) {
      r->cell_index[r->nr_saved] = c;
      memcpy((struct gravity_cell *)r->cells + r->nr_saved++, g->cells + c,
             sizeof(struct gravity_cell));
    }
  r->nr_lists = g->nr_lists;
  r->list_count = error_malloc((size_t)g->nr_lists * sizeof(int64_t), "restart far field");
  r->list_d_min = error_malloc((size_t)g->nr_lists * sizeof(double), "restart far field");
  size_t items = 0;
  for (int k = 0; k < g->nr_lists; k++) items += (size_t)g->lists[k].count;
  r->items = error_malloc(16 * (items ? items : 1), "restart far field");
  size_t q = 0;
  for (int k = 0; k < g->nr_lists; k++) {
    const struct gravity_ilist *il = &g->lists[k];
    r->list_count[k] = il->count;
    r->list_d_min[k] = il->d_min;
    for (int j = 0; j < il->count; j++, q++) {
      const struct gravity_iitem *it = &il->item[j];
      int32_t *o = r->items + 4 * q;
      o[0] = it->a->index;
      o[1] = it->b ? it->b->index : -1;
      o[2] = it->kind;
      o[3] = it->symmetric;
    }
  }
}

void gravity_restart_read(struct engine *e, struct restart_gravity *r) {
  restart_gravity_free(&e->grav->restart);
  e->grav->restart = *r;
  memset(r, 0, sizeof *r);
}

/** After the first rebuild of a resumed run (the cells and task graph of
 *  the uninterrupted run, space_restore): the far field of the restart
 *  file back in place, so that the coming steps reuse it as the
 *  uninterrupted run does.  A GPU run drops it (its far field lives on the
 *  device): its first step evaluates gravity in full, within the reuse
 *  tolerance of the uninterrupted run. */
void gravity_restart_restore(struct engine *e) {
  struct gravity_state *g = e->grav;
  struct restart_gravity *r = &g->restart;
  if (!r->present) return;
  if (e->gpu || !e->gp.enabled || e->gp.direct || e->gp.reuse_steps <= 0) {
    if (e->gpu)
      error_log(0,
                "gravity: the far field of the restart file is not used on the GPU: the first step "
                "evaluates it in full");
    restart_gravity_free(r);
    return;
  }
  const struct parts *p = &e->parts;
  if (r->nr_cells != e->space.nr_cells || r->nr_lists != g->nr_lists)
    error_exit(
        "%s: the far field of %lld cells and %lld gravity tasks does not match the restored cells "
        "(%d) and task graph (%d gravity tasks)",
        e->restart_file, (long long)r->nr_cells, (long long)r->nr_lists, e->space.nr_cells,
        g->nr_lists);
  g->x0 = error_realloc(g->x0, 3 * (p->count ? p->count : 1) * sizeof(double),
                        "gravity reuse positions");
  memcpy(g->x0, r->x0, 3 * p->count * sizeof(double));
  g->d_min = r->d_min;
  g->reused = (int)r->reused;
  g->replays = (long)r->replays;
  for (int64_t c = 0; c < r->nr_saved; c++)
    memcpy(g->cells + r->cell_index[c], (const struct gravity_cell *)r->cells + c,
           sizeof(struct gravity_cell));
  size_t q = 0;
  for (int k = 0; k < g->nr_lists; k++) {
    struct gravity_ilist *il = &g->lists[k];
    const int n = (int)r->list_count[k];
    if (n > il->capacity) {
      il->item = error_realloc(il->item, (size_t)n * sizeof *il->item, "gravity interaction list");
      il->capacity = n;
    }
    il->count = n;
    il->d_min = r->list_d_min[k];
    for (int j = 0; j < n; j++, q++) {
      const int32_t *it = r->items + 4 * q;
      il->item[j] = (struct gravity_iitem){
          &e->space.cells[it[0]], it[1] >= 0 ? &e->space.cells[it[1]] : NULL, it[2], it[3]};
    }
  }
  restart_gravity_free(r);
}

/* ---------------------------------------- top-level cells of other ranks */

/** Doubles of a record ahead of the multipole's: a_min, h_support, bmin,
 *  bmax, count, split. */
#define GRAVITY_REC_EXTRA 10
#define GRAVITY_REC_MP ((int)(sizeof(struct gravity_multipole) / sizeof(double)))

int gravity_top_record_doubles(void) {
  return GRAVITY_REC_MP + GRAVITY_REC_EXTRA;
}

void gravity_top_record_pack(const struct engine *e, int c, double *out) {
  const struct gravity_cell *g = e->grav->cells + c;
  const struct cell *cl = e->space.cells + c;
  memcpy(out, &g->mp, sizeof g->mp);
  double *x = out + GRAVITY_REC_MP;
  x[0] = g->a_min;
  x[1] = g->h_support;
  for (int k = 0; k < 3; k++) {
    x[2 + k] = cl->bmin[k];
    x[5 + k] = cl->bmax[k];
  }
  x[8] = (double)cl->count;
  x[9] = cl->split ? 1.0 : 0.0;
}

/** Record rec (gravity_top_record_pack) into r (complete left 0). */
static void gravity_top_record_unpack(const double *rec, struct gravity_remote *r) {
  memcpy(&r->mp, rec, sizeof r->mp);
  const double *x = rec + GRAVITY_REC_MP;
  r->a_min = x[0];
  r->h_support = x[1];
  for (int k = 0; k < 3; k++) {
    r->bmin[k] = x[2 + k];
    r->bmax[k] = x[5 + k];
  }
  r->count = (long long)x[8];
  r->split = x[9] != 0.0;
  r->complete = 0;
}

void gravity_top_records_use(struct engine *e, const double *recs, const int *row,
                             const unsigned char *use, const unsigned char *complete) {
  struct gravity_state *g = e->grav;
  const int nt = e->space.nr_top, R = gravity_top_record_doubles();
  if (g->remote_idx_cap < nt) {
    g->remote_idx = error_realloc(g->remote_idx, (size_t)nt * sizeof(int), "gravity remote cells");
    g->remote_idx_cap = nt;
  }
  int n = 0;
  for (int c = 0; c < nt; c++) n += use[c] && row[c] >= 0;
  if (g->remote_cap < n) {
    g->remote = error_realloc(g->remote, (size_t)n * sizeof *g->remote, "gravity remote cells");
    g->remote_partial =
        error_realloc(g->remote_partial, (size_t)n * sizeof(int), "gravity remote cells");
    g->remote_cap = n;
  }
  n = 0;
  int np = 0;
  for (int c = 0; c < nt; c++) {
    g->remote_idx[c] = use[c] && row[c] >= 0 ? n : -1;
    if (g->remote_idx[c] < 0) continue;
    gravity_top_record_unpack(recs + (size_t)row[c] * R, g->remote + n);
    g->remote[n].complete = complete[c] != 0;
    if (!g->remote[n].complete) g->remote_partial[np++] = c;
    n++;
  }
  e->gp.remote_idx = g->remote_idx;
  e->gp.remote = g->remote;
  e->gp.remote_partial = g->remote_partial;
  e->gp.nr_remote_partial = np;
  gravity_tops_used_update(e);
}

/** Whether the walk between top-level cells a (receiving) and b, known
 *  by their records of an earlier step, still ends at the top (M2L, or M2P
 *  to a's particles) after every particle has moved up to drift and h has
 *  grown: each radius taken drift*2 larger, the distance 2 drift shorter,
 *  the powers scaled with the radius, a_min halved, the supports a quarter
 *  larger.  A margin for the steps until the next rebuild, not a bound:
 *  the walks check the records of each step (gravity_long_range). */
static int gravity_top_far_with_margin(const struct gravity_remote *a,
                                       const struct gravity_remote *b, double drift,
                                       const struct gravity_props *gp) {
  struct gravity_multipole ma = a->mp, mb = b->mp;
  const double ra = ma.r_max + 2.0 * drift, rb = mb.r_max + 2.0 * drift;
  for (int n = 0; n <= gp->order; n++) {
    ma.power[n] *= ma.r_max > 0.0 ? pow(ra / ma.r_max, n) : 1.0;
    mb.power[n] *= mb.r_max > 0.0 ? pow(rb / mb.r_max, n) : 1.0;
  }
  if (ma.r_max <= 0.0)
    for (int n = 2; n <= gp->order; n++) ma.power[n] = ma.M[0] * pow(ra, n);
  if (mb.r_max <= 0.0)
    for (int n = 2; n <= gp->order; n++) mb.power[n] = mb.M[0] * pow(rb, n);
  ma.r_max = ra;
  mb.r_max = rb;
  double r = 0.0;
  for (int k = 0; k < 3; k++) r += (mb.com[k] - ma.com[k]) * (mb.com[k] - ma.com[k]);
  r = sqrt(r) - 2.0 * drift;
  if (r <= 0.0) return 0;
  const struct gravity_walk_params wp = {gp->G,         gp->theta,    gp->epsilon_fmm,
                                         gp->h_support, gp->h_factor, gp->order};
  if (!gravity_walk_accept(&ma, &mb, 0.5 * a->a_min, 0.5 * b->a_min, 1.25 * a->h_support,
                           1.25 * b->h_support, r * r, &wp))
    return 0;
  /* (a leaf b larger than twice a: M2P/P2L from b's particles) */
  return b->split || rb <= GRAVITY_LOPSIDED * ra;
}

void gravity_top_needed(const struct engine *e, const double *recs, const int *row,
                        const unsigned char *mine, const long long *count, const double *box,
                        double drift, unsigned char *need) {
  const int nt = e->space.nr_top, R = gravity_top_record_doubles();
  const struct gravity_props *gp = &e->gp;
  int na = 0;
  int *own = error_malloc((size_t)nt * sizeof(int) + 1, "gravity needed cells");
  for (int c = 0; c < nt; c++)
    if (mine[c] && count[c] > 0) own[na++] = c;
  struct gravity_remote *ra = error_malloc((size_t)na * sizeof *ra + 1, "gravity needed cells");
  for (int k = 0; k < na; k++)
    if (row[own[k]] >= 0) gravity_top_record_unpack(recs + (size_t)row[own[k]] * R, ra + k);
  struct gravity_remote rb;
  for (int b = 0; b < nt; b++) {
    /* (a cell of this rank's own particles: all of them, the other ranks'
     * in it too) */
    need[b] = mine[b];
    if (mine[b] || count[b] == 0) continue;
    if (row[b] >= 0) gravity_top_record_unpack(recs + (size_t)row[b] * R, &rb);
    for (int k = 0; k < na && !need[b]; k++) {
      const int a = own[k];
      need[b] = gravity_walk_top_near(box + 6 * a, box + 6 * a + 3, box + 6 * b, box + 6 * b + 3,
                                      gp->theta, gp->h_support) ||
                row[a] < 0 || row[b] < 0 || !gravity_top_far_with_margin(ra + k, &rb, drift, gp);
    }
  }
  free(ra);
  free(own);
}

void gravity_log_end(const struct engine *e) {
  if (e->gp.enabled && e->individual)
    error_log(0,
              "gravity: %ld of %ld steps computed it only for the cells with particles that end "
              "their step (time bins; the others and every output step for all)",
              e->grav->active_steps, e->step);
  if (e->gp.enabled && e->gp.reuse_steps > 0)
    error_log(0,
              "gravity: %ld of %ld steps reused the far field (Gravity:reuse_steps %d, "
              "reuse_tolerance %g)",
              e->grav->replays, e->step, e->gp.reuse_steps, e->gp.reuse_tol);
}
