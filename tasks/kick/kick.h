/* Second half kick and new time step of one particle, shared by the CPU task
 * (kick_cpu.c) and the CUDA kernel (kick_gpu.cu). */
#ifndef BOLIDE_KICK_H
#define BOLIDE_KICK_H

#include <math.h>

#include "tasks/drift/drift.h"
#include "tasks/ghost/continuity_floor.h"
#include "tasks/gradient/extra_ghost_part.h"
#include "tasks/hydro/hydro_props.h"
#include "tasks/hydro_parts.h"
#include "src/inline.h"
#include "src/materials/material.h"
#include "src/part.h"
#include "src/timeline.h"
#include "tasks/kick/kick_porous.h"
#include "tasks/kick/timestep.h"
#include "src/materials/viscosity.h"

/** The kicked stress of a plastic particle back onto its yield surface
 *  (extra_ghost_plastic_return, with the yield stress of this step's
 *  state and the velocity gradient of this step's extra ghost), so that
 *  the state after the kick, which snapshots, statistics and restart files
 *  hold, never lies outside the yield surface. */
BOLIDE_INLINE void kick2_plastic_return(struct parts *BOLIDE_RESTRICT p, size_t i,
                                        const struct material_table *mats) {
  const struct material *mat = material_table_find(mats, p->mat[i]);
  if (!mat || mat->strength == STRENGTH_NONE || mat->strength == STRENGTH_ELASTIC ||
      !(mat->shear_modulus > 0.0))
    return;
  double S[6], dS[6];
  EXTRA_GHOST_GET6(S, p, S, i);
  const double gv[9] = {p->gvxx[i], p->gvxy[i], p->gvxz[i], p->gvyx[i], p->gvyy[i],
                        p->gvyz[i], p->gvzx[i], p->gvzy[i], p->gvzz[i]};
  const double eps_rate = gradient_stress_rate(gv, S, mat->shear_modulus, dS);
  extra_ghost_plastic_return(p, i, mat, S, eps_rate);
  EXTRA_GHOST_PUT6(S, p, S, i);
}

/** The rates of particle i that the force phase leaves for the kick to
 *  complete: with self-gravity the gravitational acceleration joins the
 *  hydrodynamic one (a gravity-only run has no hydrodynamic one), and so
 *  does a uniform external acceleration (ConstantPotential:g_cgs); a fixed
 *  boundary particle's acceleration is 0 (theory/boundaries.md); for
 *  porous materials dalpha/dt (kick_porous.h); with the continuity
 *  equation the density rate of a particle on its floor
 *  (continuity_floor.h).  With time bins the particles that do not end
 *  their step take only these (the drift predicts their state with them). */
BOLIDE_INLINE void kick2_rates(struct parts *BOLIDE_RESTRICT p, size_t i,
                               const struct hydro_props *hp, const struct material_table *mats,
                               const struct timestep_props *tp) {
  if (!tp->hydro && (tp->gravity || hp->external)) p->ax[i] = p->ay[i] = p->az[i] = 0.0;
  if (tp->gravity) {
    p->ax[i] += p->gax[i];
    p->ay[i] += p->gay[i];
    p->az[i] += p->gaz[i];
  }
  if (hp->external) {
    p->ax[i] += hp->g_ext[0];
    p->ay[i] += hp->g_ext[1];
    p->az[i] += hp->g_ext[2];
  }
  const struct material *mat = material_table_find(mats, p->mat[i]);
  if (mat && mat->boundary) {
    /* a fixed boundary particle: an infinite mass that no force moves (its
     * velocity, zero, stays; theory/boundaries.md B1); its density, energy
     * and stress still change with its rates */
    p->ax[i] = p->ay[i] = p->az[i] = 0.0;
    p->xsphx[i] = p->xsphy[i] = p->xsphz[i] = 0.0;
  }
  if (tp->porous) kick2_porous_rate(p, i, mats);
  if (hp->continuity) continuity_floor_rate(p, i);
}

/** The kick and the new time step of particle i, on the CPU and the GPU:
 *  with self-gravity the gravitational acceleration joins the hydrodynamic
 *  one (the two families accumulate apart, engine_graph.c; a gravity-only
 *  run has no hydrodynamic one); for porous materials dalpha/dt from the
 *  rates of this force loop (kick_porous.h); the kick by dt_kick (0 after
 *  the first force computation); a plastic particle's stress back onto its
 *  yield surface (kick2_plastic_return); the predicted state made the
 *  kicked one (kick_sync_predicted); the time step of the kicked state
 *  (timestep_part); then the kicked state of a porous particle back on its
 *  crush curve (not after the first force computation).  With the
 *  continuity equation a particle on its density floor does not expand
 *  further (continuity_floor.h). */
BOLIDE_INLINE double kick2_part(struct parts *BOLIDE_RESTRICT p, size_t i, double dt_kick,
                                const struct hydro_props *hp, const struct material_table *mats,
                                const struct timestep_props *tp) {
  kick2_rates(p, i, hp, mats, tp);
  kick_part(p, i, dt_kick);
  if (hp->solids) kick2_plastic_return(p, i, mats);
  kick_sync_predicted(p, i);
  const double dt = timestep_part(p, i, hp, mats, tp);
  if (tp->porous && (dt_kick > 0.0 || hp->stage_end))
    kick2_porous_return(p, i, mats, hp->continuity);
  return dt;
}

/** With TimeIntegration:limiter_wake: density, the ghost's part of the
 *  wake of particle i, asleep in the middle of its step of bin b (2^b
 *  ticks, begun at ti - d) when the density phase at ti asked it to wake
 *  (wake > 0): its step is cut to d = ti mod 2^b and closes with the
 *  kick-drift-kick of a step of d, its force at ti computed in this step.
 *  Its first half kick gave it 2^b / 2 of the rates of its step's start,
 *  now d / 2 (the drift over d used the longer one's velocity: that part of
 *  it stays); it becomes active for the rest of the step (PART_WOKEN; its h
 *  and density stay the drift's predictions, its sums of the gradient and
 *  force loops start from zero) and kick2_part_bins gives it the second
 *  half kick, d / 2 of its new rates. */
BOLIDE_INLINE void kick_wake_part(struct parts *BOLIDE_RESTRICT p, size_t i, integertime_t ti,
                                  double time_base, int solids) {
  const integertime_t step = timeline_step_of_bin(p->time_bin[i] > 0 ? p->time_bin[i] : 1);
  kick_part(p, i, 0.5 * (double)(ti % step - step) * time_base);
  p->flags[i] = (p->flags[i] & ~PART_INACTIVE) | PART_WOKEN;
  hydro_force_reset(p, i);
  if (solids) hydro_gradient_reset(p, i);
}

/** The kick of particle i with individual time steps at ti_new on the time
 *  line tl (TimeIntegration:global_step: false): a particle whose step ends
 *  at ti_new (or any, first: the first force computation, no kick) takes
 *  its second half kick by half its step (kick2_part) and the time bin of
 *  its new limit (timeline_bin; a longer bin only where ti_new allows it,
 *  timeline_bin_allowed), its new limit in *dt; the others, in the middle
 *  of their step, nothing (*dt = 1e300).  *ti_end: the
 *  end of its step.  Returns 1 when it was kicked. */
BOLIDE_INLINE int kick2_part_bins(struct parts *BOLIDE_RESTRICT p, size_t i,
                                  const struct hydro_props *hp, const struct material_table *mats,
                                  const struct timestep_props *tp, const struct timeline *tl,
                                  integertime_t ti_new, int first, integertime_t *ti_end,
                                  double *dt) {
  const int old_bin = p->time_bin[i];
  const integertime_t step = timeline_step_of_bin(old_bin > 0 ? old_bin : 1);
  if (p->flags[i] & PART_WOKEN) {
    /* woken in the density phase (kick_wake_part): the second half kick of
     * its step cut to d, with the rates of now; then the bin of its new
     * limit, at most the one asked for and the longest ti_new allows */
    *dt = kick2_part(p, i, 0.5 * (double)(ti_new % step) * tl->time_base, hp, mats, tp);
    int bin = timeline_bin(tl, *dt);
    if (hp->bin_limit && p->ngb_bin_min[i] + hp->bin_limit < bin)
      bin = p->ngb_bin_min[i] + hp->bin_limit;
    if (TIMELINE_NR_BINS + 1 - p->wake[i] < bin) bin = TIMELINE_NR_BINS + 1 - p->wake[i];
    const int sync = timeline_max_active_bin(ti_new);
    if (bin > sync) bin = sync;
    if (bin < 1) bin = 1;
    p->wake[i] = 0;
    p->flags[i] &= ~PART_WOKEN;
    p->time_bin[i] = bin;
    *ti_end = ti_new + timeline_step_of_bin(bin);
    return 1;
  }
  if (!first && ti_new % step != 0) {
    /* (its rates are those of the start of its step: the FORCE phase
     * skipped it, PART_INACTIVE) */
    if (p->wake[i] > 0) {
      /* the limiter: a neighbour with a much shorter step asks it to wake.
       * Its step ends now, at ti_new, after d = ti_new - its start: the
       * first half kick gave it a dt_old / 2 of its rates, a whole step
       * of d gives it d of them (those of the step's start: its force at
       * ti_new was not computed), so it takes d - dt_old / 2 more; then it
       * starts a step of the bin asked for (at most the longest that ti_new
       * allows) with its next drift's half kick */
      const integertime_t ti_begin = ti_new - ti_new % step;
      kick_part(p, i, ((double)(ti_new - ti_begin) - 0.5 * (double)step) * tl->time_base);
      if (hp->solids) kick2_plastic_return(p, i, mats);
      kick_sync_predicted(p, i);
      int bin = TIMELINE_NR_BINS + 1 - p->wake[i];
      const int sync = timeline_max_active_bin(ti_new);
      if (bin > sync) bin = sync;
      if (bin < 1) bin = 1;
      p->wake[i] = 0;
      p->time_bin[i] = bin;
      *ti_end = ti_new + timeline_step_of_bin(bin);
      *dt = 1e300;
      return 0;
    }
    *ti_end = timeline_next_sync(old_bin > 0 ? old_bin : 1, ti_new);
    *dt = 1e300;
    return 0;
  }
  *dt = kick2_part(p, i, first ? 0.0 : 0.5 * (double)step * tl->time_base, hp, mats, tp);
  int want = timeline_bin(tl, *dt);
  /* the limiter: at most bin_limit bins longer than the shortest neighbour's
   * (the force loop's; none in a gravity-only run) */
  if (hp->bin_limit && hp->enabled && !first && p->ngb_bin_min[i] + hp->bin_limit < want)
    want = p->ngb_bin_min[i] + hp->bin_limit;
  p->wake[i] = 0;
  const int bin = first ? want : timeline_bin_allowed(old_bin, want, ti_new);
  p->time_bin[i] = bin;
  *ti_end = ti_new + timeline_step_of_bin(bin > 0 ? bin : 1);
  return 1;
}

#endif
