/* The task graph of the engine, built after every rebuild.
 *
 * Tasks work on *task cells*: each top-level cell's octree is cut where a
 * cell holds at most Scheduler:cell_task_size particles, so that a large
 * top-level cell gives many tasks and the workers stay busy.  Task cells
 * partition the particles, so a lock per task cell is exact.  A pair task
 * joins two task cells whose bounding boxes (at the rebuild) are closer than
 * the reach R = min(top-level cell width, ENGINE_REACH_FACTOR x the largest
 * kernel support at the rebuild); the engine rebuilds before any particle
 * pair could interact beyond it (H_max + 2 dx_max > R, engine_should_rebuild),
 * and the ghost caps h there.
 *
 *   drift(t)                                                phase DRIFT
 *   density(t), density(t,t') -> ghost(t)                   phase FORCE
 *   ghost(t), ghost(t') -> force(t,t') -> kick2(t), kick2(t')
 *
 * The ghost of a task cell waits for every density task touching it: its h
 * iteration then reads final neighbour positions and writes only its own
 * particles.  With solids (a material with strength: e->hp.solids) the
 * gradient loop sits between the ghost and the force:
 *
 *   ghost(t), ghost(t') -> gradient(t,t') -> extra_ghost(t), extra_ghost(t')
 *   extra_ghost(t), extra_ghost(t') -> force(t,t')
 *
 * With brittle materials the damage task of a task cell sits between its
 * force tasks and its kick: force(t), force(t,t') -> damage(t) -> kick2(t).
 * So does every family of shape chain in the registry (tasks/task_families.h),
 * in its order, in the runs its predicate selects.
 *
 * Self-gravity works on the top-level cells (tasks/gravity/gravity_cpu.h):
 *
 *   grav_up(c) -> grav(c,c'), grav(c) -> grav_down(c)       near pairs
 *   grav_up(all) -> grav_long_range(c) -> grav_down(c)      far field
 *   grav_down(c) -> kick2(t) for the task cells t of c
 *   ghost(t) -> grav_up(c)   only with the softening tied to h (the walks read h)
 *
 * The self interaction of a top-level cell holding more than
 * Scheduler:gravity_task_size particles is split along its octree
 * (engine_grav_self): self(q) of each progeny and pair(q, r) of each two
 * progeny, recursively while a cell holds more than that, at most
 * ENGINE_GRAV_SPLIT_DEPTH levels down (the walk does exactly that:
 * walk_self), each sub-task locking the cells it writes; an implicit
 * done(q) follows q's sub-tasks, pair(q, r) waits for done(q) and done(r)
 * (a task on q then never runs beside one on a descendant of q), and the
 * top-level pairs and the long-range task of c wait for done(c).  A near
 * pair with such a cell is split into pairs of the octants (of the split
 * cells), which lock the octants and come before the long-range tasks of
 * the split cells (which write the whole cell).  Without
 * the split a few large cells serialise the gravity of a concentrated body
 * (a planet: 14 occupied top-level cells at 1e5 particles).
 *
 * Gravity tasks write the gravity accumulators and take gravity locks;
 * hydro tasks write other fields, so the two families run side by side.
 * The kick adds the gravitational acceleration. */
#include "src/engine.h"

#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "tasks/hydro/kernel.h"
#include "tasks/task_families.h"

/** The per-task-cell tasks between the force tasks and the kick: the rows
 *  of shape chain(active) of the registry (tasks/task_families.h), in its
 *  order. */
struct engine_chain {
  int (*active)(const struct engine *); /**< 1: the run has these tasks */
  enum task_type type;                  /**< their type */
  enum task_subtype subtype;            /**< and subtype */
};
#define ENGINE_CHAIN_chain(active) \
  {                                \
    active, ENGINE_CHAIN_TAIL_
#define ENGINE_CHAIN_TAIL_(type, subtype)  \
  task_type_##type, task_subtype_##subtype \
  }                                        \
  ,
#define ENGINE_CHAIN_cell(type, subtype)
#define ENGINE_CHAIN_self(type, subtype)
#define ENGINE_CHAIN_pair(type, subtype)
#define ENGINE_CHAIN_ROW_(family, shape, type, subtype, cpu) ENGINE_CHAIN_##shape(type, subtype)
static const struct engine_chain engine_chain[] = {
    TASK_FAMILY_TASKS(ENGINE_CHAIN_ROW_){NULL, task_type_none, task_subtype_none}};
#undef ENGINE_CHAIN_ROW_
/** Their number (the table ends with an empty row). */
#define ENGINE_NR_CHAIN ((int)(sizeof engine_chain / sizeof engine_chain[0]) - 1)

/** Growable list of tasks. */
static void engine_phase_add(struct engine *e, int ph, struct task *t, int *cap) {
  if (e->phase_count[ph] == cap[ph]) {
    cap[ph] = cap[ph] ? 2 * cap[ph] : 1024;
    e->phase_tasks[ph] =
        error_realloc(e->phase_tasks[ph], cap[ph] * sizeof(struct task *), "task lists");
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

/** Record task cell b (with shift) as a neighbour of task cell a. */
static void engine_add_ngb(struct engine_cell_tasks *ct, int b, const double shift[3]) {
  if (ct->nr_ngb == ct->ngb_cap) {
    /* (doubling: one realloc per entry was a third of a 1e6-particle graph's time) */
    ct->ngb_cap = ct->ngb_cap ? 2 * ct->ngb_cap : 32;
    ct->ngb = error_realloc(ct->ngb, (size_t)ct->ngb_cap * sizeof(int), "cell neighbours");
    ct->ngb_shift =
        error_realloc(ct->ngb_shift, (size_t)ct->ngb_cap * sizeof(double[3]), "cell neighbours");
  }
  ct->ngb[ct->nr_ngb] = b;
  for (int k = 0; k < 3; k++) ct->ngb_shift[ct->nr_ngb][k] = shift[k];
  ct->nr_ngb++;
}

/** Append a pair of task cells to e->pairs. */
static int engine_add_pair(struct engine *e, int a, int b, const double shift[3], int *cap) {
  if (e->nr_pairs == *cap) {
    *cap = *cap ? 2 * *cap : 1024;
    e->pairs = error_realloc(e->pairs, *cap * sizeof(struct space_pair), "task cell pairs");
  }
  struct space_pair *q = &e->pairs[e->nr_pairs];
  q->ci = a;
  q->cj = b;
  for (int k = 0; k < 3; k++) q->shift[k] = shift[k];
  return e->nr_pairs++;
}

/** Collect the task cells below c: c itself if small enough or a leaf. */
static void engine_collect_tcells(struct engine *e, struct cell *c, int max_count, int *cap) {
  if (c->count == 0) return;
  if (c->split && (int)c->count > max_count) {
    for (int q = 0; q < 8; q++)
      if (c->progeny[q]) engine_collect_tcells(e, c->progeny[q], max_count, cap);
    return;
  }
  if (e->nr_tcells == *cap) {
    *cap = *cap ? 2 * *cap : 1024;
    e->tcells = error_realloc(e->tcells, *cap * sizeof(struct cell *), "task cells");
  }
  e->tcells[e->nr_tcells++] = c;
}

/** Free the per-task-cell records. */
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
  free(e->pairs);
  e->pairs = NULL;
  e->nr_pairs = 0;
  free(e->tcells);
  e->tcells = NULL;
  e->nr_tcells = 0;
  free(e->tcell_top);
  e->tcell_top = NULL;
  free(e->grav_down);
  e->grav_down = NULL;
  free(e->glocks);
  e->glocks = NULL;
  free(e->gsublocks);
  e->gsublocks = NULL;
  gravity_graph_free(e);
}

/** A top-level cell's self gravity is split while a cell holds more than
 *  Scheduler:gravity_task_size particles, at most this many levels down. */
#define ENGINE_GRAV_SPLIT_DEPTH 3

/** The self-gravity tasks of cell c (the walk_self of gravity_cpu.c as tasks,
 *  see the top comment), after `after`; returns the task that follows them
 *  all.  top: c's top-level cell (for the dumps). */
static struct task *engine_grav_self(struct engine *e, struct cell *c, struct task *after,
                                     int depth, int top, int *cap) {
  struct scheduler *sched = &e->sched;
  if (!c->split || c->count <= (size_t)e->grav_task_size || depth >= ENGINE_GRAV_SPLIT_DEPTH) {
    struct task *t = scheduler_addtask(sched, task_type_self, task_subtype_grav, c, c);
    t->cell_index = top;
    t->locks[0] = &e->gsublocks[c->index];
    scheduler_addunlock(sched, after, t);
    engine_phase_add(e, ENGINE_PHASE_FORCE, t, cap);
    return t;
  }
  struct task *done = scheduler_addtask(sched, task_type_implicit, task_subtype_grav, NULL, NULL);
  engine_phase_add(e, ENGINE_PHASE_FORCE, done, cap);
  struct task *sub[8] = {NULL};
  for (int q = 0; q < 8; q++) {
    struct cell *cq = c->progeny[q];
    if (cq == NULL || cq->count == 0) continue;
    sched_lock_init(&e->gsublocks[cq->index]);
    sub[q] = engine_grav_self(e, cq, after, depth + 1, top, cap);
    scheduler_addunlock(sched, sub[q], done);
  }
  for (int q = 0; q < 8; q++)
    for (int r = q + 1; r < 8; r++) {
      if (!sub[q] || !sub[r]) continue;
      struct task *t =
          scheduler_addtask(sched, task_type_pair, task_subtype_grav, c->progeny[q], c->progeny[r]);
      t->cell_index = top;
      t->locks[0] = &e->gsublocks[c->progeny[q]->index];
      t->locks[1] = &e->gsublocks[c->progeny[r]->index];
      scheduler_addunlock(sched, sub[q], t);
      scheduler_addunlock(sched, sub[r], t);
      scheduler_addunlock(sched, t, done);
      engine_phase_add(e, ENGINE_PHASE_FORCE, t, cap);
    }
  return done;
}

/** The cells a near pair of top-level cell c is split into: c's non-empty
 *  octants when its self tasks were split, else c itself.  Returns their
 *  number. */
static int engine_grav_units(struct cell *c, int split, struct cell *units[8]) {
  int n = 0;
  if (!split) {
    units[n++] = c;
    return n;
  }
  for (int q = 0; q < 8; q++)
    if (c->progeny[q] && c->progeny[q]->count > 0) units[n++] = c->progeny[q];
  return n;
}

/** The gravity tasks of the top-level cells (see the top comment). */
static void engine_make_gravity_tasks(struct engine *e, const int *first, int *cap) {
  struct space *s = &e->space;
  struct scheduler *sched = &e->sched;
  const int nt = s->nr_top;
  e->glocks = error_calloc(nt, sizeof(struct sched_lock), "gravity locks");
  e->gsublocks = error_calloc(s->cells_capacity, sizeof(struct sched_lock), "gravity locks");
  e->grav_down = error_calloc(nt, sizeof(struct task *), "gravity tasks");
  struct task **up = error_calloc(nt, sizeof(struct task *), "gravity tasks");
  struct task **gself = error_calloc(nt, sizeof(struct task *), "gravity tasks");
  struct task **glr = error_calloc(nt, sizeof(struct task *), "gravity tasks");
  struct task *all_up = scheduler_addtask(sched, task_type_implicit, task_subtype_grav, NULL, NULL);
  engine_phase_add(e, ENGINE_PHASE_FORCE, all_up, cap);
  for (int c = 0; c < nt; c++) {
    if (s->cells[c].count == 0) continue;
    struct cell *ci = &s->cells[c];
    sched_lock_init(&e->glocks[c]);
    up[c] = scheduler_addtask(sched, task_type_grav_up, task_subtype_grav, ci, NULL);
    sched_lock_init(&e->gsublocks[ci->index]);
    /* self(c), or its split: then gself[c] is the implicit done(c) */
    gself[c] = engine_grav_self(e, ci, up[c], 0, c, cap);
    const int split = gself[c]->type != task_type_self;
    struct task *lr = glr[c] =
        scheduler_addtask(sched, task_type_grav_long_range, task_subtype_grav, ci, NULL);
    e->grav_down[c] = scheduler_addtask(sched, task_type_grav_down, task_subtype_grav, ci, NULL);
    up[c]->cell_index = lr->cell_index = e->grav_down[c]->cell_index = c;
    up[c]->locks[0] = lr->locks[0] = e->grav_down[c]->locks[0] = &e->glocks[c];
    if (!split) gself[c]->locks[0] = &e->glocks[c];
    /* grav_up(c) -> all_up -> long_range(c);  grav_up(c) -> self(c) -> grav_down(c) */
    scheduler_addunlock(sched, up[c], all_up);
    scheduler_addunlock(sched, all_up, lr);
    scheduler_addunlock(sched, gself[c], e->grav_down[c]);
    scheduler_addunlock(sched, lr, e->grav_down[c]);
    if (split)
      scheduler_addunlock(sched, gself[c], lr);
    else
      gself[c] = NULL; /* the lock orders it against the pairs */
    /* grav_down(c) -> kick2(t) for the task cells of c */
    for (int t = first[c]; t < first[c + 1]; t++)
      scheduler_addunlock(sched, e->grav_down[c], e->ct[t].kick2);
    /* softening tied to h (Gravity:softening_h_factor): ghost(t) -> grav_up(c), so that
     * every gravity task reads the step's final h (the long range waits for every up) */
    if (e->gp.h_factor > 0.0 && e->hp.enabled)
      for (int t = first[c]; t < first[c + 1]; t++)
        scheduler_addunlock(sched, e->ct[t].ghost, up[c]);
    engine_phase_add(e, ENGINE_PHASE_FORCE, up[c], cap);
    engine_phase_add(e, ENGINE_PHASE_FORCE, lr, cap);
    engine_phase_add(e, ENGINE_PHASE_FORCE, e->grav_down[c], cap);
  }
  /* near pairs of top-level cells: grav_up(c), grav_up(c') -> grav(c,c') -> grav_down(c),
   * grav_down(c'); a pair with a split cell (gself set: its self tasks were split) is split too,
   * into pairs of the octants of the split cells (engine_grav_units): they lock those octants, wait
   * for done() of the split cells and come before their long-range tasks, the other writers of the
   * whole cell */
  for (int a = 0; a < nt; a++) {
    if (!up[a]) continue;
    for (int b = a + 1; b < nt; b++) {
      if (!up[b] || !gravity_top_pair_is_near(&s->cells[a], &s->cells[b], &e->gp)) continue;
      /* (several MPI ranks: two cells of copies only receive nothing from
       * each other: gravity_walk_task) */
      if (s->cells[a].foreign && s->cells[b].foreign) continue;
      struct cell *ua[8], *ub[8];
      const int na = engine_grav_units(&s->cells[a], gself[a] != NULL, ua);
      const int nb = engine_grav_units(&s->cells[b], gself[b] != NULL, ub);
      for (int i = 0; i < na; i++)
        for (int j = 0; j < nb; j++) {
          struct task *pt =
              scheduler_addtask(sched, task_type_pair, task_subtype_grav, ua[i], ub[j]);
          pt->cell_index = a;
          pt->locks[0] = ua[i] == &s->cells[a] ? &e->glocks[a] : &e->gsublocks[ua[i]->index];
          pt->locks[1] = ub[j] == &s->cells[b] ? &e->glocks[b] : &e->gsublocks[ub[j]->index];
          scheduler_addunlock(sched, up[a], pt);
          scheduler_addunlock(sched, up[b], pt);
          if (gself[a]) {
            scheduler_addunlock(sched, gself[a], pt);
            scheduler_addunlock(sched, pt, glr[a]);
          }
          if (gself[b]) {
            scheduler_addunlock(sched, gself[b], pt);
            scheduler_addunlock(sched, pt, glr[b]);
          }
          scheduler_addunlock(sched, pt, e->grav_down[a]);
          scheduler_addunlock(sched, pt, e->grav_down[b]);
          engine_phase_add(e, ENGINE_PHASE_FORCE, pt, cap);
        }
    }
  }
  free(up);
  free(gself);
  free(glr);
}

/** The tasks of a pair of task cells a, b (b seen at x + shift). */
static void engine_make_pair_tasks(struct engine *e, int a, int b, const double shift[3],
                                   int *cap) {
  struct scheduler *sched = &e->sched;
  struct cell *ci = e->tcells[a], *cj = e->tcells[b];
  const int k = engine_add_pair(e, a, b, shift, &cap[2]);
  struct task *dp = scheduler_addtask(sched, task_type_pair, task_subtype_density, ci, cj);
  struct task *fp = scheduler_addtask(sched, task_type_pair, task_subtype_force, ci, cj);
  dp->locks[0] = fp->locks[0] = &ci->lock;
  /* a cell paired with its own periodic image takes its lock once */
  dp->locks[1] = fp->locks[1] = (a == b) ? NULL : &cj->lock;
  dp->cell_index = fp->cell_index = a;
  engine_task_pair_set(e, dp, k, &cap[3]);
  engine_task_pair_set(e, fp, k, &cap[3]);
  double mshift[3];
  for (int d = 0; d < 3; d++) mshift[d] = -shift[d];
  engine_add_ngb(&e->ct[a], b, shift);
  engine_add_ngb(&e->ct[b], a, mshift);
  /* density(a,b) -> ghost(a), ghost(b);  force(a,b) -> kick2(a), kick2(b) */
  scheduler_addunlock(sched, dp, e->ct[a].ghost);
  scheduler_addunlock(sched, dp, e->ct[b].ghost);
  scheduler_addunlock(sched, fp, e->ct[a].force_done);
  scheduler_addunlock(sched, fp, e->ct[b].force_done);
  engine_phase_add(e, ENGINE_PHASE_FORCE, dp, cap);
  engine_phase_add(e, ENGINE_PHASE_FORCE, fp, cap);
  if (e->hp.solids) {
    /* ghost(a), ghost(b) -> gradient(a,b) -> extra_ghost(a), extra_ghost(b) -> force(a,b) */
    struct task *gp = scheduler_addtask(sched, task_type_pair, task_subtype_gradient, ci, cj);
    gp->locks[0] = &ci->lock;
    gp->locks[1] = (a == b) ? NULL : &cj->lock;
    gp->cell_index = a;
    engine_task_pair_set(e, gp, k, &cap[3]);
    scheduler_addunlock(sched, e->ct[a].ghost, gp);
    scheduler_addunlock(sched, e->ct[b].ghost, gp);
    scheduler_addunlock(sched, gp, e->ct[a].extra_ghost);
    scheduler_addunlock(sched, gp, e->ct[b].extra_ghost);
    scheduler_addunlock(sched, e->ct[a].extra_ghost, fp);
    scheduler_addunlock(sched, e->ct[b].extra_ghost, fp);
    engine_phase_add(e, ENGINE_PHASE_FORCE, gp, cap);
  } else {
    /* ghost(a), ghost(b) -> force(a,b) */
    scheduler_addunlock(sched, e->ct[a].ghost, fp);
    scheduler_addunlock(sched, e->ct[b].ghost, fp);
  }
}

/** Candidate pairs of task cells (engine_make_graph): indices into
 *  e->tcells, gathered by engine_pairs_descend, then sorted. */
struct engine_pair_list {
  int *ab; /**< 2 per pair */
  size_t n, cap;
};

/** Every pair (a, b) of task cells below A and below B (B seen at x +
 *  shift) whose boxes come closer than reach (squared: reach2), added to
 *  L.  A pair of cells farther apart is pruned whole: a child's box lies
 *  inside its parent's (space_finish_cell), so no pair below it is
 *  closer, and the test at the task cells is the one of the pair loops
 *  it replaces.  tc[i]: the task-cell index of cell i, or -1 above the
 *  task cells (such a cell holds particles and is split). */
static void engine_pairs_descend(const int *tc, struct cell *A, struct cell *B,
                                 const double shift[3], double reach2, struct engine_pair_list *L) {
  if (cell_bbox_dist2(A, B, shift) >= reach2) return;
  const int ta = tc[A->index], tb = tc[B->index];
  if (ta >= 0 && tb >= 0) {
    if (L->n == L->cap) {
      L->cap = L->cap ? 2 * L->cap : 4096;
      L->ab = error_realloc(L->ab, 2 * L->cap * sizeof(int), "task cell pairs");
    }
    L->ab[2 * L->n] = ta;
    L->ab[2 * L->n + 1] = tb;
    L->n++;
    return;
  }
  if (ta < 0) {
    for (int q = 0; q < 8; q++)
      if (A->progeny[q] && A->progeny[q]->count > 0)
        engine_pairs_descend(tc, A->progeny[q], B, shift, reach2, L);
  } else {
    for (int q = 0; q < 8; q++)
      if (B->progeny[q] && B->progeny[q]->count > 0)
        engine_pairs_descend(tc, A, B->progeny[q], shift, reach2, L);
  }
}

/** The pairs of distinct task cells within cell C (C above the task
 *  cells): those of each child, and those between two children. */
static void engine_pairs_within(const int *tc, struct cell *C, double reach2,
                                struct engine_pair_list *L) {
  if (tc[C->index] >= 0) return;
  static const double zero[3] = {0, 0, 0};
  for (int q = 0; q < 8; q++) {
    struct cell *cq = C->progeny[q];
    if (!cq || cq->count == 0) continue;
    engine_pairs_within(tc, cq, reach2, L);
    for (int r = q + 1; r < 8; r++)
      if (C->progeny[r] && C->progeny[r]->count > 0)
        engine_pairs_descend(tc, cq, C->progeny[r], zero, reach2, L);
  }
}

static int engine_pair_cmp(const void *x, const void *y) {
  const int *a = x, *b = y;
  if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
  return (a[1] > b[1]) - (a[1] < b[1]);
}

/* the reach of an interaction until the next rebuild (see the top comment) */
double engine_reach(const struct space *s) {
  double reach = s->width[0];
  for (int k = 1; k < 3; k++)
    if (s->width[k] < reach) reach = s->width[k];
  if (ENGINE_REACH_FACTOR * kernel_gamma * s->h_max < reach)
    reach = ENGINE_REACH_FACTOR * kernel_gamma * s->h_max;
  return reach;
}

/** The tasks of the pairs in L, in the order of (a, b): the order of the
 *  loops over all pairs of task cells that the descent replaces, so that
 *  the graph does not change. */
static void engine_make_listed_pairs(struct engine *e, struct engine_pair_list *L,
                                     const double shift[3], int *cap) {
  /* qsort's pointer must be valid even for no element (C11 7.22.5; UBSan) */
  if (L->n > 1) qsort(L->ab, L->n, 2 * sizeof(int), engine_pair_cmp);
  for (size_t k = 0; k < L->n; k++)
    engine_make_pair_tasks(e, L->ab[2 * k], L->ab[2 * k + 1], shift, cap);
  L->n = 0;
}

void engine_make_graph(struct engine *e) {
  struct space *s = &e->space;
  struct scheduler *sched = &e->sched;
  engine_graph_free(e);
  scheduler_clear(sched);
  /* cap: phase lists (2), pairs, task->pair map */
  int cap[4] = {0, 0, 0, 0}, cap_tc = 0;

  /* task cells, top-level cell by top-level cell; first[c]..first[c+1] are c's */
  int *first = error_malloc((s->nr_top + 1) * sizeof(int), "task cell index");
  for (int c = 0; c < s->nr_top; c++) {
    first[c] = e->nr_tcells;
    engine_collect_tcells(e, &s->cells[c], e->cell_task_size, &cap_tc);
  }
  first[s->nr_top] = e->nr_tcells;
  const int nt = e->nr_tcells;
  e->ct = error_calloc(nt ? nt : 1, sizeof(struct engine_cell_tasks), "cell tasks");
  e->nr_ct = nt;
  e->cell_dt_min = error_realloc(e->cell_dt_min, (nt ? nt : 1) * sizeof(double), "cell time steps");
  e->cell_bins = error_realloc(
      e->cell_bins, (nt ? nt : 1) * (TIMELINE_NR_BINS + 1) * sizeof(int64_t), "cell time bins");
  memset(e->cell_bins, 0, (nt ? nt : 1) * (TIMELINE_NR_BINS + 1) * sizeof(int64_t));
  e->cell_kick =
      error_realloc(e->cell_kick, (nt ? nt : 1) * sizeof(struct timeline_sums), "cell step ends");

  /* tasks of each task cell: drift(t);  density(t) -> ghost(t) -> force(t) -> kick2(t) */
  for (int t = 0; t < nt; t++) {
    struct cell *c = e->tcells[t];
    struct engine_cell_tasks *ct = &e->ct[t];
    const double zero[3] = {0, 0, 0};
    engine_add_ngb(ct, t, zero);
    ct->drift = scheduler_addtask(sched, task_type_drift, task_subtype_none, c, NULL);
    ct->ghost = scheduler_addtask(sched, task_type_ghost, task_subtype_none, c, NULL);
    ct->kick2 = scheduler_addtask(sched, task_type_kick2, task_subtype_none, c, NULL);
    ct->drift->cell_index = ct->ghost->cell_index = ct->kick2->cell_index = t;
    /* the chains of the registry, e.g. force(t), force(t,t') -> damage(t) -> kick2(t) */
    ct->force_done = ct->kick2;
    for (int k = ENGINE_NR_CHAIN - 1; k >= 0; k--) {
      if (!engine_chain[k].active(e)) continue;
      struct task *d =
          scheduler_addtask(sched, engine_chain[k].type, engine_chain[k].subtype, c, NULL);
      d->cell_index = t;
      scheduler_addunlock(sched, d, ct->force_done);
      engine_phase_add(e, ENGINE_PHASE_FORCE, d, cap);
      ct->force_done = d;
    }
    engine_phase_add(e, ENGINE_PHASE_DRIFT, ct->drift, cap);
    engine_phase_add(e, ENGINE_PHASE_FORCE, ct->kick2, cap);
    if (!e->hp.enabled) continue; /* gravity-only run: no hydro tasks */
    struct task *ds = scheduler_addtask(sched, task_type_self, task_subtype_density, c, NULL);
    struct task *fs = scheduler_addtask(sched, task_type_self, task_subtype_force, c, NULL);
    ds->locks[0] = fs->locks[0] = &c->lock;
    ds->cell_index = fs->cell_index = t;
    scheduler_addunlock(sched, ds, ct->ghost);
    scheduler_addunlock(sched, fs, ct->force_done);
    engine_phase_add(e, ENGINE_PHASE_FORCE, ds, cap);
    engine_phase_add(e, ENGINE_PHASE_FORCE, ct->ghost, cap);
    engine_phase_add(e, ENGINE_PHASE_FORCE, fs, cap);
    if (e->hp.solids) {
      /* ghost(t) -> gradient(t) -> extra_ghost(t) -> force(t) */
      ct->extra_ghost = scheduler_addtask(sched, task_type_extra_ghost, task_subtype_none, c, NULL);
      struct task *gs = scheduler_addtask(sched, task_type_self, task_subtype_gradient, c, NULL);
      gs->locks[0] = &c->lock;
      gs->cell_index = ct->extra_ghost->cell_index = t;
      scheduler_addunlock(sched, ct->ghost, gs);
      scheduler_addunlock(sched, gs, ct->extra_ghost);
      scheduler_addunlock(sched, ct->extra_ghost, fs);
      engine_phase_add(e, ENGINE_PHASE_FORCE, gs, cap);
      engine_phase_add(e, ENGINE_PHASE_FORCE, ct->extra_ghost, cap);
    } else {
      /* ghost(t) -> force(t) */
      scheduler_addunlock(sched, ct->ghost, fs);
    }
  }

  const double reach = engine_reach(s);
  e->reach = reach;
  const double reach2 = reach * reach;
  const double zero[3] = {0, 0, 0};

  e->tcell_top = error_malloc((nt ? nt : 1) * sizeof(int), "task cell tops");
  for (int c = 0; c < s->nr_top; c++)
    for (int t = first[c]; t < first[c + 1]; t++) e->tcell_top[t] = c;
  if (e->gp.enabled && e->gp.direct) {
    /* Gravity:direct: one task of exact summation -> every kick2 */
    struct task *d =
        scheduler_addtask(sched, task_type_grav_long_range, task_subtype_grav, NULL, NULL);
    for (int t = 0; t < nt; t++) scheduler_addunlock(sched, d, e->ct[t].kick2);
    engine_phase_add(e, ENGINE_PHASE_FORCE, d, cap);
  } else if (e->gp.enabled) {
    engine_make_gravity_tasks(e, first, cap);
    /* the gravity tasks are the first sched->nr_tasks: the family's per-cell
     * data and interaction lists for them */
    gravity_graph_made(e, sched->nr_tasks);
  }
  if (!e->hp.enabled) {
    free(first);
    scheduler_finalize(sched);
    return;
  }

  /* task-cell index of every cell (-1: above the task cells, or empty) */
  int *tc = error_malloc((s->nr_cells ? s->nr_cells : 1) * sizeof(int), "task cell map");
  for (int i = 0; i < s->nr_cells; i++) tc[i] = -1;
  for (int t = 0; t < nt; t++) tc[e->tcells[t]->index] = t;
  struct engine_pair_list L = {NULL, 0, 0};

  /* pairs of task cells inside one top-level cell, a < b, within reach:
   * found by descending the octree (a dense top-level cell holds
   * thousands of task cells, whose all-pairs test was quadratic) */
  for (int c = 0; c < s->nr_top; c++) {
    if (first[c + 1] - first[c] < 2) continue;
    engine_pairs_within(tc, &s->cells[c], reach2, &L);
    engine_make_listed_pairs(e, &L, zero, cap);
  }

  /* pairs of task cells in neighbouring top-level cells (or a cell and its
   * periodic image: then every ordered pair, a == b included) */
  struct space_pair *top = NULL;
  const size_t ntop = space_top_pairs(s, &top);
  for (size_t k = 0; k < ntop; k++) {
    const int ci = top[k].ci, cj = top[k].cj;
    if (first[ci] == first[ci + 1] || first[cj] == first[cj + 1]) continue;
    engine_pairs_descend(tc, &s->cells[ci], &s->cells[cj], top[k].shift, reach2, &L);
    engine_make_listed_pairs(e, &L, top[k].shift, cap);
  }
  free(L.ab);
  free(tc);
  free(top);
  free(first);
  scheduler_finalize(sched);
  error_log(1, "task graph: %d top-level cells, %d task cells, %d pairs, %d tasks", s->nr_top, nt,
            e->nr_pairs, sched->nr_tasks);
}

void engine_activate_phase(struct engine *e, int phase) {
  struct scheduler *sched = &e->sched;
  for (int k = 0; k < sched->nr_tasks; k++) scheduler_task(sched, k)->skip = 1;
  for (int k = 0; k < e->phase_count[phase]; k++) e->phase_tasks[phase][k]->skip = 0;
}

void engine_graph_clean(struct engine *e) {
  engine_graph_free(e);
  free(e->task_pair);
  e->task_pair = NULL;
}
