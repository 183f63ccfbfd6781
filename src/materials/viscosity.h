/* Newtonian viscosity of fluids (theory/fluids.md): the deviatoric stress of
 * a viscous fluid and the time step of viscous diffusion.  Shared by the CPU
 * tasks and the CUDA kernels (extra_ghost_part.h, kick.h).
 *
 * A fluid material with dynamic viscosity eta (the material key
 * `viscosity`) carries the deviatoric stress
 *   S = 2 eta e',   e' = (gv + gv^T)/2 - tr(gv)/3 I
 * of its (corrected) velocity gradient gv^{ab} = dv^a/dx^b (Landau &
 * Lifshitz, Fluid Mechanics, Sec. 15, with zero bulk viscosity; the fluid of
 * the fluid-structure impacts of Eghtesad & Knezevic 2018, Comp. Part.
 * Mech. 5, 387).  S enters the momentum and energy
 * equations through the stress terms of the force loop (force_iact.h,
 * theory/solids.md E8-E9), the same terms that carry a solid's deviatoric
 * stress, so the viscous force is momentum-conserving pairwise and the
 * viscous heating S:e'/rho = 2 eta e':e'/rho is never negative. */
#ifndef BOLIDE_VISCOSITY_H
#define BOLIDE_VISCOSITY_H

#include "src/inline.h"

/** The viscous deviatoric stress S = 2 eta e' (xx xy xz yy yz zz) of the
 *  velocity gradient gv (row-major, gv[3a + b] = dv^a/dx^b). */
BOLIDE_INLINE void viscosity_stress(const double gv[9], double eta, double S[6]) {
  const double tr3 = (gv[0] + gv[4] + gv[8]) / 3.0;
  S[0] = 2.0 * eta * (gv[0] - tr3);
  S[1] = eta * (gv[1] + gv[3]);
  S[2] = eta * (gv[2] + gv[6]);
  S[3] = 2.0 * eta * (gv[4] - tr3);
  S[4] = eta * (gv[5] + gv[7]);
  S[5] = 2.0 * eta * (gv[8] - tr3);
}

/** Stability limit of explicit viscous diffusion, dt = 0.125 h^2 / nu with
 *  nu = eta / rho and h = H / 2 the half support of the kernel (Morris, Fox
 *  & Zhu 1997, J. Comput. Phys. 136, 214, whose h is the half support of
 *  their kernels); 1e300 for an inviscid fluid. */
BOLIDE_INLINE double viscosity_timestep(double H, double rho, double eta) {
  if (!(eta > 0.0) || !(rho > 0.0)) return 1e300;
  return 0.125 * 0.25 * H * H * rho / eta;
}

#endif
