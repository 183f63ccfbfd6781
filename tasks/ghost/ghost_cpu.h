/* The ghost task on the CPU (see ghost_cpu.c). */
#ifndef BOLIDE_GHOST_CPU_H
#define BOLIDE_GHOST_CPU_H

#include "src/cell.h"
#include "tasks/hydro/hydro_props.h"
#include "src/part.h"

struct material_table;

/** Where the ghost of a top-level cell finds its neighbours. */
struct ghost_ngbs {
  int n;                     /**< number of neighbouring top-level cells, itself included */
  struct cell *const *cells; /**< the cells */
  const double (*shift)[3];  /**< periodic shift of each */
};

/** Finish the density sums of the particles of top-level cell c, iterate
 *  their smoothing lengths to the target neighbour number (re-running the
 *  gather density loop over ngbs for the particles that need it), then
 *  evaluate the equation of state.  H_limit: the largest kernel support the
 *  cells allow; a particle that needs more is capped there and the function
 *  returns 1 (rebuild the cells), else 0.  *resummed: the particles whose sums
 *  were redone, summed over the rounds.  A particle that does not converge
 *  in hp->max_iterations stops the run with an error naming it. */
int ghost_cell_cpu(struct parts *p, struct cell *c, const struct ghost_ngbs *ngbs,
                   const struct hydro_props *hp, const struct material_table *mats, double H_limit,
                   long long *resummed);

#endif
