/* Second half kick and new time step of a cell on the CPU. */
#ifndef BOLIDE_KICK_CPU_H
#define BOLIDE_KICK_CPU_H

#include <stdint.h>

#include "src/cell.h"
#include "tasks/hydro/hydro_props.h"
#include "src/materials/material.h"
#include "src/part.h"
#include "src/timeline.h"

struct timestep_props;
struct timeline;

/** Second half kick by dt_kick of every particle of c (kick2_part:
 *  velocities and energies become those of the end of the step, and the
 *  predicted ones equal them; plastic stresses back on the yield surface of
 *  their material in mats); returns the smallest new time step of its
 *  particles (timestep_part with tp).  With bins (TIMELINE_NR_BINS + 1
 *  counts; NULL: none) the particles are counted by the time bin of their
 *  own step on the time line tl (timeline_bin). */
double kick2_cell_cpu(struct parts *p, const struct cell *c, double dt_kick,
                      const struct hydro_props *hp, const struct material_table *mats,
                      const struct timestep_props *tp, const struct timeline *tl, int64_t *bins);

/** The kick with individual time steps (TimeIntegration:global_step:
 *  false) at ti_new on the time line tl: a particle of c whose step ends
 *  at ti_new (or every one, first: the first force computation, no kick)
 *  takes its second half kick by half its step (kick2_part) and the time
 *  bin of its new limit (timeline_bin; a longer bin only where ti_new
 *  allows it, timeline_bin_allowed); the others, in the middle of their
 *  step, only the rates (kick2_rates).  bins (TIMELINE_NR_BINS + 1):
 *  particles by bin after the kick; returns the smallest new time-step
 *  limit of those kicked (1e300: none). */
double kick2_cell_bins_cpu(struct parts *p, const struct cell *c, const struct hydro_props *hp,
                           const struct material_table *mats, const struct timestep_props *tp,
                           const struct timeline *tl, integertime_t ti_new, int first,
                           int64_t *bins, struct timeline_sums *sums);

#endif
