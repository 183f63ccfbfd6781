/* Kick and drift of a cell on the CPU. */
#ifndef BOLIDE_DRIFT_CPU_H
#define BOLIDE_DRIFT_CPU_H

#include "src/cell.h"
#include "src/part.h"
#include "src/timeline.h"

/** First half kick by dt_kick, then drift by dt, of every particle of c;
 *  updates the cell's h_max and dx_max.  h_continuity: SPH:h_evolution:
 *  continuity (drift_part). */
void drift_cell_cpu(struct parts *p, struct cell *c, double dt_kick, double dt, double xsph,
                    double h_max, int h_continuity);

/** The same with individual time steps (TimeIntegration:global_step:
 *  false): every particle of c drifts from ti_old to ti_new on the time
 *  line tl; a particle whose step begins at ti_old (its time bin's step
 *  divides ti_old) first takes its half kick by half its step, and every
 *  one's predicted state is that of ti_new (drift_part_to, from the middle
 *  of its own step). */
void drift_cell_bins_cpu(struct parts *p, struct cell *c, const struct timeline *tl,
                         integertime_t ti_old, integertime_t ti_new, double xsph, double h_max,
                         int h_continuity);

#endif
