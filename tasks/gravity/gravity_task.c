/* The gravity family's tasks (tasks/task_families.h): the upward pass, the
 * walks (self, near pair, long range) and the downward pass of the
 * top-level cells and their split (engine_graph.c). */
#include "src/engine.h"
#include "tasks/gravity/gravity_state.h"

/** A gravity walk task: self (cj == ci), near pair, or long range (cj
 *  NULL); records its particle-level interactions when the far field may
 *  be reused, or replays them on a step that reuses it. */
static void gravity_walk_task(struct engine *e, const struct task *t, const struct cell *ci,
                              const struct cell *cj) {
  /* several MPI ranks: no walk whose receiving cells hold only copies (src/mpi/halo.h) */
  if (ci->foreign && (!cj || cj->foreign)) return;
  if (cj && cj != ci && e->gp.top_partial &&
      (e->gp.top_partial[ci->top] || e->gp.top_partial[cj->top]))
    /* several MPI ranks: a cell of another rank holding only some of its
     * particles here (copies for the hydrodynamics) is far from every cell
     * of this rank's, by the boxes of all its particles: the long-range walk
     * reads it from its record (the flags of the last rebuild, not the
     * records of the last step: a pair walk after a rebuild comes before
     * this step's records) */
    return;
  struct parts *p = &e->parts;
  struct gravity_ilist *il = t->id < e->grav->nr_lists ? &e->grav->lists[t->id] : NULL;
  if (e->gp.replay) {
    gravity_replay(p, il, e->grav->cells, &e->gp);
    return;
  }
  /* (a step of active particles only records nothing: its walks are not
   * the whole far field that a later step could replay) */
  gravity_record_begin(e->gp.active ? NULL : il);
  if (cj && cj != ci && (ci->foreign || cj->foreign))
    /* a pair across ranks: each rank walks it for its own cell only */
    gravity_interact_pair_one_way(p, ci->foreign ? cj : ci, ci->foreign ? ci : cj, e->grav->cells,
                                  &e->gp);
  else if (cj)
    gravity_interact_cells(p, ci, cj, e->grav->cells, &e->gp);
  else
    gravity_long_range(p, ci, e->space.cells, e->space.nr_top, e->grav->cells, &e->gp);
  gravity_record_end();
}

void gravity_up_task(struct engine *e, struct task *t) {
  gravity_up(&e->parts, t->ci, e->grav->cells, &e->gp);
}

void gravity_self_task(struct engine *e, struct task *t) {
  gravity_walk_task(e, t, t->ci, t->ci);
}

void gravity_pair_task(struct engine *e, struct task *t) {
  gravity_walk_task(e, t, t->ci, t->cj);
}

void gravity_long_range_task(struct engine *e, struct task *t) {
  /* (several MPI ranks with the walks on the GPU: the cell's tree from the
   * device's upward pass, where the walks with the records read it) */
  if (t->ci && e->gp.remote_only && e->grav->back.mp && gravity_remote_reads(t->ci, &e->gp))
    gravity_back_fill(&e->grav->back, t->ci, e->grav->cells);
  if (t->ci)
    gravity_walk_task(e, t, t->ci, NULL);
  else /* Gravity:direct: exact summation in one task */
    gravity_direct_h(&e->parts, e->gp.G, e->gp.eps, e->gp.softening, e->gp.h_factor, 1);
}

void gravity_down_task(struct engine *e, struct task *t) {
  if (((const struct cell *)t->ci)->foreign) return; /* (copies only: src/mpi/halo.h) */
  /* (several ranks, walks on the GPU: only where the host's walks with the
   * records put something in the field tensors) */
  if (e->gp.remote_only && !gravity_remote_reads(t->ci, &e->gp)) return;
  gravity_down(&e->parts, t->ci, e->grav->cells, &e->gp);
}
