/* The ghost task on the CPU (see ghost_cpu.c). */
#ifndef BOLIDE_GHOST_CPU_H
#define BOLIDE_GHOST_CPU_H

#include "src/cell.h"
#include "tasks/hydro/hydro_props.h"
#include "src/part.h"
#include "src/timeline.h"

struct material_table;

/** Where the ghost of a top-level cell finds its neighbours. */
struct ghost_ngbs {
  int n;                     /**< number of neighbouring top-level cells, itself included */
  struct cell *const *cells; /**< the cells */
  const double (*shift)[3];  /**< periodic shift of each */
};

/** With TimeIntegration:limiter_wake: density in a step of time bins: the
 *  step's end on the time line and its tick, for the particles the
 *  density phase woke (kick_wake_part, tasks/kick/kick.h). */
struct ghost_wake {
  integertime_t ti;
  double time_base;
};

/** Finish the density sums of the particles of top-level cell c, iterate
 *  their smoothing lengths to the target neighbour number (re-running the
 *  gather density loop over ngbs for the particles that need it), then
 *  evaluate the equation of state; a sleeping particle woken by the
 *  density phase (wake != NULL, its wake field set) becomes active with its
 *  predicted h and density (kick_wake_part).  H_limit: the largest kernel support the
 *  cells allow; a particle that needs more is capped there and the function
 *  returns 1 (rebuild the cells), else 0.  *resummed: the particles whose sums
 *  were redone, summed over the rounds.  A particle that does not converge
 *  in hp->max_iterations stops the run with an error naming it. */
int ghost_cell_cpu(struct parts *p, struct cell *c, const struct ghost_ngbs *ngbs,
                   const struct hydro_props *hp, const struct material_table *mats, double H_limit,
                   const struct ghost_wake *wake, long long *resummed);

#endif
