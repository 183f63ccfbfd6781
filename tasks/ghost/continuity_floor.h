/* Density floor of the continuity equation (theory/sph.md, section 6,
 * "Particles that lose their neighbours"), written once for the CPU tasks
 * and the CUDA kernels (ghost_part.h, kick.h).
 *
 * The continuity rate dρ_i/dt = Σ_j m_j v_ij·∇_i W_ij (S14) does not scale
 * with ρ_i: it is the rate of the kernel sum around i.  When the neighbours
 * of a particle fly apart while its own density is below that sum (an ice
 * particle among equal-mass basalt particles, an ejected particle among a
 * few diverging neighbours) ρ_i falls linearly to zero in finite time, and
 * the EOS then sees densities the material cannot have (7e-71 kg/m^3 in
 * examples/CeresHitAndRun at contact).  The integrated density is therefore
 * held at or above
 *
 *     ρ_floor = max(density_floor, SPH:continuity_min_density_ratio × ρ_0)
 *
 * of the particle's material: at the floor a negative rate is set to zero,
 * so the particle keeps that density (it has become a spray of unconnected
 * fragments whose further expansion opens voids the particle does not
 * represent) until its neighbours converge on it again.  The floor changes
 * only the density the EOS and the force loop use; the pairwise exchange of
 * momentum and energy is untouched, so energy stays conserved. */
#ifndef BOLIDE_CONTINUITY_FLOOR_H
#define BOLIDE_CONTINUITY_FLOOR_H

#include "tasks/hydro/hydro_props.h"
#include "src/inline.h"
#include "src/materials/material.h"
#include "src/part.h"

/** The smallest continuity density of material mat: the larger of its
 *  density_floor and ratio * rho0 (0: no floor). */
BOLIDE_INLINE double continuity_rho_floor(const struct hydro_props *hp,
                                          const struct material *mat) {
  const double f = hp->continuity_min_ratio * mat->rho0;
  return (f > mat->density_floor) ? f : mat->density_floor;
}

/** Hold particle i's integrated and predicted densities at or above
 *  rho_floor; mark it with PART_RHO_FLOOR when it sits on the floor (its
 *  density may then not decrease: continuity_floor_rate). */
BOLIDE_INLINE void continuity_floor_part(struct parts *BOLIDE_RESTRICT p, size_t i,
                                         double rho_floor) {
  if (rho_floor > 0.0 && !(p->rho_fp[i] > rho_floor)) {
    p->rho_fp[i] = rho_floor;
    if (!(p->rho_full[i] > rho_floor)) p->rho_full[i] = rho_floor;
    p->flags[i] |= PART_RHO_FLOOR;
  } else {
    p->flags[i] &= ~PART_RHO_FLOOR;
  }
}

/** The density rate a particle on its floor may have: max(drho_dt, 0). */
BOLIDE_INLINE void continuity_floor_rate(struct parts *BOLIDE_RESTRICT p, size_t i) {
  if ((p->flags[i] & PART_RHO_FLOOR) && p->drho_dt[i] < 0.0) p->drho_dt[i] = 0.0;
}

#endif
