/* Restart files: the complete state of a run (every particle field, the
 * engine's clocks and the cells of the last rebuild) in one binary file, so
 * that `bolide --restart PARAMS.yml` resumes where the last one was written
 * and takes exactly the steps of the uninterrupted run (issue 18).
 *
 * Format (version RESTART_VERSION, native byte order, checked): a header of
 * RESTART_HEADER_BYTES (magic, format version, byte-order mark, build, particle
 * count, FNV-64 hash of the parameters, payload length), the payload (the
 * particle-field table, the state, the parameters as text, the cells' h_max
 * and dx_max, every field array, the Weibull flaws, the far field of the last
 * full gravity evaluation that steps with Gravity:reuse_steps reuse) and a
 * 64-bit checksum of
 * everything before it (restart_checksum).  Every field is validated on
 * reading; a file of another parameter set is refused with one line that
 * names the first parameter that differs.
 *
 * Files in the restart folder, named after Restarts:basename (STEM below is
 * Restarts:subdir/Restarts:basename, "restart/restart" by default):
 * STEM.bin (the newest), STEM.prev.bin (the one before; a hard link made
 * before the newest is replaced, so that a complete file exists at every
 * instant) and STEM.bin.tmp while writing (removed at start if a killed run
 * left it). */
#ifndef BOLIDE_RESTART_H
#define BOLIDE_RESTART_H

#include <stddef.h>
#include <stdint.h>

#include "src/budget.h"
#include "src/part.h"

#define RESTART_VERSION 7
#define RESTART_HEADER_BYTES 128

/** The engine's scalars saved with the particles (every member 8 bytes: no
 *  padding, written as it is). */
struct restart_state {
  double time;                   /**< simulation time */
  double dt;                     /**< last global time step */
  double dt_next;                /**< smallest particle time step for the next step */
  int64_t step;                  /**< steps done */
  int64_t updates;               /**< particle updates done */
  int64_t nr_removed;            /**< particles removed from an open box */
  int64_t snap_index;            /**< index of the next snapshot */
  int64_t next_out;              /**< next output time (index in the list from time_begin) */
  double next_stats;             /**< next statistics time */
  double box[3];                 /**< box size */
  int64_t periodic;              /**< periodic box */
  struct budget_removed removed; /**< what particles removed from the box took with them */
  struct budget_start start;     /**< the run's totals at its start */
  double rebuild_h_max;          /**< the space's h_max at the last rebuild (its top-level grid) */
  int64_t need_rebuild;          /**< 1: a task asked for a rebuild at the next step */
  int64_t stats_offset;          /**< length of the statistics file when the file was written */
  int64_t ti_current;            /**< the time on the integer time line (individual time steps,
                                      since format 5; 0 with the global step) */
  int64_t nr_ranks;              /**< MPI ranks of the run that wrote the file (since format 6;
                                      1: STEM.bin, more: STEM_rankNNNN.bin, one per rank) */
  int64_t rank;                  /**< the rank that wrote it, 0 .. nr_ranks - 1 */
};

/** The cells' h_max and dx_max at the end of the step (space.cells order). */
struct restart_cells {
  int64_t n;
  double *h_max;
  double *dx_max;
};

/** The far field of the last full gravity evaluation (Gravity:reuse_steps
 *  > 0, CPU runs), what the steps that reuse it read (the gravity family's
 *  gravity_reuse_decide and gravity_replay): saved since format 4 so
 *  that a resumed run reuses it where the uninterrupted run does, and stays
 *  bit-identical.  present = 0: none (no reuse, no full evaluation yet, or
 *  a GPU run, whose far field stays on the device); the rest is then empty. */
struct restart_gravity {
  int64_t present;      /**< 1: the members below hold the state */
  int64_t reused;       /**< steps since the evaluation that reused it (gravity_state.reused) */
  int64_t replays;      /**< steps of the run that reused a far field (gravity_state.replays) */
  double d_min;         /**< shortest far-field distance of the evaluation (finite, > 0) */
  double *x0;           /**< positions at the evaluation, 3 per particle (x, y, z) */
  int64_t nr_cells;     /**< the space's cells (restart_cells.n) */
  int64_t nr_saved;     /**< cells whose gravity data are saved: those with particles (the
                             walks and the replay read no other) */
  int64_t cell_doubles; /**< doubles per cell: sizeof(struct gravity_cell) / 8 */
  int32_t *cell_index;  /**< nr_saved cell indices, increasing, < nr_cells */
  double *cells;        /**< nr_saved * cell_doubles: their struct gravity_cell (multipole,
                             local expansion, a_min, h_support) */
  int64_t nr_lists;     /**< interaction lists: one per gravity task of the graph, by task id */
  int64_t *list_count;  /**< interactions of each list */
  double *list_d_min;   /**< d_min of each list (>= 0; HUGE_VAL: none; 0: a task
                             that records nothing) */
  int32_t *items;       /**< 4 per interaction, the lists one after the other: cell a, cell b
                             (-1: none, a P2P within a), kind (0: P2P, 1: M2P), symmetric */
};

/** What a file must match to be resumed by this run (restart_read_buffer). */
struct restart_expect {
  const char *params; /**< parameters in use (params_to_string; the Restarts section is ignored) */
  const int32_t *mat_ids; /**< material ids of the run */
  int nr_mats;            /**< their number */
  int64_t nr_out;         /**< number of output times of the run */
  double time_begin;      /**< TimeIntegration:time_begin */
  double time_end;        /**< TimeIntegration:time_end */
  const int32_t
      *u_floor; /**< per material of mat_ids: 1 when its EOS needs u >= 0 (NULL: no check) */
  int64_t grav_cell_doubles; /**< doubles per gravity cell of this build's expansion order (0: no
                                check) */
  /** the damage family's check of the flaw thresholds, n particles with offset[n + 1]
   *  (ragged_io_check_fn; NULL: the offsets only) */
  int (*flaws_check)(size_t n, const int64_t *offset, const double *eps, char *msg, size_t len);
};

/** Everything a file holds (free with restart_data_free). */
struct restart_data {
  struct restart_state st;
  struct parts p;   /**< the particles in the order of the writing run */
  double *flaw_eps; /**< flat flaw thresholds, p.flaw_first indexes it (NULL: none) */
  int64_t nr_flaws; /**< their number */
  struct restart_cells cells;
  struct restart_gravity grav; /**< the reused far field (grav.present 0: none) */
};

/** Write the state to STEM.bin through STEM.bin.tmp (see the
 *  top comment for the rotation).  flaw_eps: the engine's flat array of flaw
 *  thresholds, particle i owning flaw_eps[flaw_first[i] .. + n_flaws[i]]
 *  (NULL: no flaws).  params: the parameters in use (params_to_string).
 *  grav: the reused far field (NULL or grav->present 0: none).
 *  Errors (disk full...) stop with one line, the older files intact. */
void restart_write(const char *stem, const struct restart_state *st, const struct parts *p,
                   const double *flaw_eps, const struct restart_cells *cells, const char *params,
                   const struct restart_gravity *grav);

/** Parse and validate a restart file held in memory (buf, len bytes; name:
 *  its name for messages).  ex: what the run expects (NULL: only the file's
 *  own consistency is checked).  Returns 0 and fills *out, or -1 with one
 *  line in err (nothing allocated).  Never exits and never reads outside
 *  buf: the entry point of the restart fuzzer. */
int restart_read_buffer(const void *buf, size_t len, const char *name,
                        const struct restart_expect *ex, struct restart_data *out, char *err,
                        size_t errlen);

/** Free the arrays of g and zero it. */
void restart_gravity_free(struct restart_gravity *g);

/** Free what restart_read_buffer or restart_read allocated. */
void restart_data_free(struct restart_data *d);

/** Read STEM.bin; if it is missing or invalid, STEM.prev.bin
 *  with a warning naming the problem of the newer one (which is renamed to
 *  STEM.bin.bad).  Stops with one line if neither can be resumed.  used:
 *  the name of the file read. */
void restart_read(const char *stem, const struct restart_expect *ex, struct restart_data *out,
                  char *used, size_t usedlen);

/** The restart files of a run at BASE (Restarts:subdir/Restarts:basename,
 *  no rank suffix) as they lie: the ranks of the run that wrote
 *  BASE_rank0000.bin (or its .prev.bin) from its state, read without the
 *  particles (0: no such file, -1: one that cannot be read), in *ranks;
 *  whether BASE.bin or BASE.prev.bin exists (a one-rank run's), returned. */
int restart_layout(const char *base, int *ranks);

/** Read the files of a run on n ranks (BASE_rank0000.bin ..; n = 0: the one
 *  file BASE.bin of a one-rank run), each as restart_read does (with its
 *  .prev.bin as fallback), into one set: the particles each rank owned
 *  (its foreign copies left out) in the order of the ranks, their flaws
 *  in one array, the state of rank 0's file with the particles removed
 *  from the box summed over the ranks and the smallest of their next time
 *  steps (each rank's file holds its own cells'); no cells and no far field (the
 *  resumed run builds both anew).  Stops with one line when a file is
 *  missing or refused, or when the files are not one step of one run.
 *  used: the name of the first file read. */
void restart_read_ranks(const char *base, int n, const struct restart_expect *ex,
                        struct restart_data *out, char *used, size_t usedlen);

/** After the first restart written by a run on n ranks: remove the files
 *  of any other layout at BASE (n > 1: BASE.bin and BASE.prev.bin, the
 *  files BASE_rankNNNN.* of ranks n and up; n = 1: every BASE_rankNNNN.*),
 *  and with stale_prev also BASE_rankNNNN.prev.bin and .halo.prev.bin of
 *  ranks below n (n = 1: BASE.prev.bin), written by the run resumed in
 *  another layout, so that a later --restart finds one run's files.
 *  Logged. */
void restart_remove_layouts(const char *base, int n, int stale_prev);

/** Remove STEM.bin.tmp left by a killed run (logged). */
void restart_remove_stale(const char *stem);

/** The checksum of the files: FNV-1a-64 over 64-bit little-endian words
 *  (each followed by an xor-shift h ^= h >> 29), then the remaining bytes one
 *  by one; h: the value so far (RESTART_HASH_INIT to start).  Chunks of a
 *  stream must be multiples of 8 bytes except the last. */
#define RESTART_HASH_INIT 0xcbf29ce484222325ULL
uint64_t restart_checksum(const void *buf, size_t len, uint64_t h);

#endif
