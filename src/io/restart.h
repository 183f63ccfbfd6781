/* Restart files: the complete state of a run (every particle field and the
 * engine's clocks) in one binary file, written under a temporary name and
 * renamed, so that `bolide --restart PARAMS.yml` resumes where the last one
 * was written.  The file records the particle-field table (names and sizes)
 * and refuses to load into a build whose table differs. */
#ifndef BOLIDE_RESTART_H
#define BOLIDE_RESTART_H

#include <stdint.h>

#include "budget.h"
#include "part.h"

/** The engine's scalars saved with the particles. */
struct restart_state {
  double time;         /**< simulation time */
  double dt;           /**< last global time step */
  double dt_next;      /**< smallest particle time step for the next step */
  int64_t step;        /**< steps done */
  int64_t updates;     /**< particle updates done */
  int64_t nr_removed;  /**< particles removed from an open box */
  int64_t snap_index;  /**< index of the next snapshot */
  int64_t next_out;    /**< next output time (index) */
  double next_stats;   /**< next statistics time */
  double box[3];       /**< box size */
  int64_t periodic;    /**< periodic box */
  struct budget_removed removed; /**< what particles removed from the box took with them */
  struct budget_start start;     /**< the run's totals at its start */
};

/** Write the state to DIR/restart.bin (through DIR/restart.bin.tmp; the
 *  previous file is kept as DIR/restart.prev.bin until the new one is in
 *  place).  flaw_eps: the engine's flat array of flaw thresholds, particle
 *  i owning flaw_eps[flaw_first[i] .. + n_flaws[i]] (NULL: no flaws); they
 *  are written as one flat array with N + 1 offsets in the particle order
 *  of the file.  Errors (disk full...) stop with one line, the old file
 *  intact. */
void restart_write(const char *dir, const struct restart_state *st, const struct parts *p,
                   const double *flaw_eps);

/** Read DIR/restart.bin into st and p (p allocated here) and the flaws into
 *  *flaw_eps (allocated here; p->flaw_first indexes it) and *nr_flaws.
 *  Stops with one line if missing, truncated, inconsistent or written by a
 *  build with other fields. */
void restart_read(const char *dir, struct restart_state *st, struct parts *p, double **flaw_eps,
                  int64_t *nr_flaws);

#endif
