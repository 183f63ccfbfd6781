/* Self-gravity's part of the GPU runner's FORCE phase (tasks/task_families.h:
 * the entry points gravity_gpu_*, which src/gpu/gpu_engine.c calls): the
 * device state of the family (gpu_gravity.h) and, per evaluation, the cell
 * tree on the device after a rebuild, the multipoles' staging, the CPU
 * workers' recorded walks and the device part that completes ga and pot.
 * The runner decides when each runs (serial or beside the hydrodynamics)
 * and keeps the timers.  Built only when configure finds nvcc (HAVE_CUDA). */
#include <stdlib.h>
#include <string.h>

#include "src/engine.h"
#include "src/engine_tasks.h"
#include "src/error.h"
#include "tasks/gravity/gpu_gravity.h"
#include "tasks/gravity/gravity_state.h"

/** Self-gravity's state of the GPU runner. */
struct gravity_gpu {
  struct gpu_grav *dev;         /**< the device state */
  struct gpu_grav_host host;    /**< its host side: the tree as index arrays */
  struct gravity_multipole *mp; /**< pinned staging of the multipoles (grav_up tasks fill it) */
  struct gravity_gpu_rec *rec;  /**< interactions recorded by each CPU worker */
  int nr_rec;                   /**< workers (length of rec) */
  int up_on_device;             /**< Scheduler:gpu_multipoles: device (P2M, M2M on the GPU) */
  int walk_on_device;           /**< Scheduler:gpu_walks: device (the walks on the GPU too) */
  unsigned char *skip;          /**< several MPI ranks: the walks' skips per top-level cell */
  int skip_cap;                 /**< its length */
};

struct gravity_gpu *gravity_gpu_new(struct gpu *g, int up_on_device, int walk_on_device,
                                    int reproducible) {
  struct gravity_gpu *gg = error_calloc(1, sizeof *gg, "GPU gravity state");
  gg->dev = gpu_grav_new(g);
  gpu_grav_set_reproducible(gg->dev, reproducible);
  gg->host.built_rebuild = -1;
  gg->up_on_device = up_on_device;
  gg->walk_on_device = walk_on_device;
  return gg;
}

void gravity_gpu_free(struct gravity_gpu *gg) {
  if (!gg) return;
  gpu_grav_free(gg->dev);
  for (int w = 0; w < gg->nr_rec; w++) gravity_gpu_rec_free(&gg->rec[w]);
  free(gg->rec);
  gpu_grav_host_free(&gg->host);
  free(gg->skip);
  free(gg);
}

int gravity_gpu_prepare(struct engine *e, struct gravity_gpu *gg) {
  if (e->gp.replay) return 0;
  struct gpu_grav_host *h = &gg->host;
  if (h->built_rebuild != e->space.nr_rebuilds || h->built_cells != e->space.cells) {
    gpu_grav_tree_build(h, &e->space);
    gpu_grav_set_tree(gg->dev, &h->tree);
  }
  gg->mp = gpu_grav_multipoles(gg->dev, e->space.nr_cells);
  /* a step of active particles only (time bins): the cells marked, walked
   * and completed on the device; with the walks on the host all */
  gpu_grav_set_active(gg->dev, e->gp.active_step && gg->up_on_device && gg->walk_on_device);
  /* Scheduler:gpu_multipoles: device: P2M and M2M on the GPU, the
   * multipoles back where the CPU walks; the runner skips the grav_up
   * tasks */
  /* (several MPI ranks: the multipoles back for the records and the host's
   * walks with them) */
  /* (several MPI ranks with the walks on the device: the top-level cells
   * back for the records, the others where the host's walks with the
   * records read them: gravity_long_range_task) */
  const int ranks_walk = gg->walk_on_device && e->halo;
  e->grav->back.mp = NULL;
  if (gg->up_on_device)
    gpu_grav_up_cells(gg->dev, &e->parts, &e->space,
                      gg->walk_on_device && !e->halo ? NULL : e->grav->cells, &e->gp, 1,
                      ranks_walk ? e->space.nr_top : -1, ranks_walk ? &e->grav->back : NULL);
  /* Scheduler:gpu_walks: device: the walks too; nothing left for the CPU
   * but, on several MPI ranks, the walks with the other ranks' records
   * (gravity_long_range with remote_only) */
  if (gg->walk_on_device) {
    const unsigned char *skip = NULL;
    if (e->halo) {
      /* the top-level cells of copies only receive nothing, those of which
       * only some particles are here are read by their records */
      const int nt = e->space.nr_top;
      if (nt > gg->skip_cap) {
        gg->skip = error_realloc(gg->skip, (size_t)nt, "GPU gravity skips");
        gg->skip_cap = nt;
      }
      for (int c = 0; c < nt; c++)
        gg->skip[c] = e->gp.top_partial && e->gp.top_partial[c] ? 2
                      : e->space.cells[c].foreign               ? 1
                                                                : 0;
      skip = gg->skip;
    }
    gpu_grav_walk_cells(gg->dev, h, &e->space, &e->gp, skip);
    return 0;
  }
  const int nw = e->sched.nr_threads > 0 ? e->sched.nr_threads : 1;
  if (nw > gg->nr_rec) {
    gg->rec = error_realloc(gg->rec, nw * sizeof *gg->rec, "gravity lists");
    memset(gg->rec + gg->nr_rec, 0, (nw - gg->nr_rec) * sizeof *gg->rec);
    gg->nr_rec = nw;
  }
  for (int w = 0; w < gg->nr_rec; w++)
    gg->rec[w].part.n = gg->rec[w].field.n = gg->rec[w].part_sym.n = gg->rec[w].field_sym.n = 0;
  return 1;
}

/** The engine's task, with the calling worker's interactions recorded in
 *  its own list; after a grav_up task, its cell's multipoles go to the
 *  upload staging. */
void gravity_gpu_task(struct engine *e, struct gravity_gpu *gg, struct task *t, int thread_id) {
  gravity_gpu_record(&gg->rec[thread_id]);
  engine_run_task(e, t, thread_id);
  gravity_gpu_record(NULL);
  if (t->type == task_type_grav_up) gpu_grav_pack_multipoles(gg->mp, t->ci, e->grav->cells);
}

/** gpu_grav_run: grouping included, or the replay of a step that reuses
 *  the far field; leaves ga and pot complete on both sides for the kick, on
 *  stream 0 after whatever is queued there. */
void gravity_gpu_device(struct engine *e, struct gravity_gpu *gg) {
  const struct gravity_props *gp = &e->gp;
  gpu_grav_run(gg->dev, &e->parts, gp->replay ? NULL : gg->rec, gp->replay ? 0 : gg->nr_rec, gp->G,
               gp->eps, gp->softening, gp->eps2_expansion, gp->order, 1, gp->replay);
}

void gravity_gpu_print(const struct gravity_gpu *gg, FILE *f) {
  gpu_grav_print(gg ? gg->dev : NULL, f);
}
