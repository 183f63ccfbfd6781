/* Multi-rank runs: each MPI rank owns the particles of its share of the
 * top-level cells and holds copies of the foreign particles its own need
 * (issue 22; theory/mpi.md, "Multi-rank runs").
 *
 * The copies (PART_FOREIGN) are the other ranks' particles within one
 * interaction reach of the rank's cells.  The FORCE phase runs in stages
 * (density and ghost; gradient and extra ghost with solids; the rest), and
 * before it and between its stages every copy takes its owner's whole state
 * again (halo_refresh): an owned particle's force reads its neighbours'
 * densities, pressures and velocity gradients as their owners computed
 * them, and no rank computes a copy's sums (the cells of copies only are
 * skipped: ENGINE_CELL_SKIP).
 *
 * With self-gravity every other particle is a copy too, refreshed before
 * the gravity tasks in the fields the walks read of a source
 * (halo_refresh_gravity): every rank then holds the whole tree, builds the
 * multipoles of every cell, and runs the walks of the cells that hold a
 * particle of its own (the others are skipped).  Memory and exchange per
 * rank grow with the whole run's particles: the first form, exact to
 * round-off; remote multipoles in place of the far particles are the next.
 * Every function here is collective (every rank calls it) and does nothing
 * with one rank. */
#ifndef BOLIDE_HALO_H
#define BOLIDE_HALO_H

#include <stddef.h>
#include <stdint.h>

struct engine;
struct parts;

/** With more than one rank: stop with one line on what multi-rank runs do
 *  not support yet, else make e->halo.  Nothing with one rank. */
void halo_init(struct engine *e);

/** Before the space's rebuild: the foreign copies removed, then (after the
 *  first rebuild) every owned particle that left the rank's cells sent to
 *  its new owner; the space's h_max floor set to the largest h of all
 *  ranks, so that every rank chooses the top-level grid of one rank. */
void halo_rebuild_start(struct engine *e);

/** 1 with several ranks once the first rebuild has partitioned the cells:
 *  the rebuild then needs no cells before halo_rebuild (space_prepare). */
int halo_partitioned(const struct engine *e);

/** After the space's rebuild.  The first time, when every rank holds every
 *  particle of the initial conditions: the partition of the top-level cells
 *  (src/mpi/partition.h, on rank 0, broadcast), and each rank keeps its own.
 *  Then the copies of the particles the other ranks need, and the space
 *  rebuilt with them.  Returns 1 on the first call (whose particles removed
 *  from an open box every rank counted: rank 0 keeps the count). */
int halo_rebuild(struct engine *e);

/** Before every FORCE phase (after the drift and any rebuild): every
 *  foreign copy takes its owner's state, and the cells' bounds follow. */
void halo_refresh(struct engine *e);

/** The particles live on a GPU (src/gpu/gpu_engine.c): a refresh packs the
 *  owned particles' records from the device (pack: n records of the
 *  particles idx, the fields of sel or every field with NULL, in the
 *  layout of halo.c's blocks) and writes the copies' records into the
 *  device too (unpack: into slot[0 .. n), marked as copies whose msrc
 *  counts from q0), besides the host's arrays.  With gravity set (the GPU
 *  computes self-gravity's interactions), halo_refresh_gravity also writes
 *  the copies for gravity's position, mass, h and acceleration into the
 *  device.  NULL: the host's arrays only.  Nothing with one rank. */
struct halo_device {
  void *ctx;
  void (*pack)(void *ctx, const size_t *idx, size_t n, char *dst, const unsigned char *sel);
  void (*unpack)(void *ctx, const size_t *slot, size_t n, const char *src, const unsigned char *sel,
                 int64_t q0);
  int gravity;
};
void halo_set_device(struct engine *e, const struct halo_device *dev);

/** halo_refresh in two halves, so that the tasks that need no copy run
 *  while the exchange is in flight (engine_run_force_stages): _start packs
 *  the records (after -1: every field, before a FORCE phase; after k: the
 *  fields that stage k of the phase writes, the registry's column writes of
 *  its families) and posts the exchange (MPI_Ialltoallv), _finish waits for
 *  it and unpacks; halo_poll(engine) lets MPI progress it (the scheduler's
 *  poll hook: thread 0 calls it between its tasks). */
void halo_refresh_start(struct engine *e, int after);
void halo_refresh_finish(struct engine *e);
void halo_poll(void *engine);
/** halo_refresh_gravity in the same two halves. */
void halo_refresh_gravity_start(struct engine *e);
void halo_refresh_gravity_finish(struct engine *e);

/** Before the gravity tasks of a FORCE phase (after the stages that set h):
 *  gravity's copies take their owners' positions, masses, h and
 *  accelerations of the last pass.  Nothing without self-gravity. */
void halo_refresh_gravity(struct engine *e);

/** Self-gravity on several ranks in an open box: between the upward pass
 *  and the long-range walks of a FORCE phase, every rank sends the records
 *  of the top-level cells it provides (multipole, a_min, support, box) to
 *  all (MPI_Allgatherv), and the walks read the other ranks' cells from
 *  them (gravity_top_records_use).  halo_gravity_after, after the phase:
 *  a walk that needed particles it did not have asks for a rebuild.
 *  halo_gravity_by_records: whether the run goes by records (the FORCE
 *  phase then has a stage for the long-range walks). */
void halo_gravity_records(struct engine *e);
void halo_gravity_after(struct engine *e);
int halo_gravity_by_records(const struct engine *e);

/** The largest drift since the rebuild (dmax) and the largest smoothing
 *  length (h_max) of the particles of every rank, its copies left out. */
void halo_bounds(const struct engine *e, double *dmax, double *h_max);

/** Restart files (Restarts:enable): each rank writes its own restart file
 *  (STEM_rankNNNN.bin: its particles, copies included) and, with this,
 *  STEM_rankNNNN.halo.bin: the decomposition and the exchange lists of the
 *  last rebuild and the step, rotated as the restart file is (.prev).  A
 *  run resumed with the same number of ranks reads them back (halo_init,
 *  which also checks that every rank resumes the same step) and, after the
 *  cells of the last rebuild are restored (space_restore),
 *  halo_restored finds the copies again: the resumed run takes the steps of
 *  the uninterrupted one.  Another number of ranks reads every rank's
 *  restart file instead (restart_read_ranks, engine_rebuild_regrouped) and
 *  no halo file. */
void halo_write_restart(const struct engine *e);
void halo_restored(struct engine *e);

/** Rank 0: a copy of the owned particles of every rank into out (allocated
 *  here; rank 0's first, then rank 1's, ...); the other ranks send theirs
 *  and get an empty out. */
void halo_gather(const struct engine *e, struct parts *out);

/** The closing line of the run's log: the copies and the time of the
 *  exchanges. */
void halo_log(const struct engine *e);

/** Free e->halo. */
void halo_free(struct engine *e);

#endif
