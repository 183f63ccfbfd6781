/* Gravity parameters from the parameter file (section Gravity).  Apart from
 * gravity_cpu.c so that programs and tests that set the parameters directly
 * (gravity_props_set) do not link the parameter parser. */
#include <math.h>

#include "src/error.h"
#include "tasks/gravity/gravity_cpu.h"
#include "src/io/params.h"
#include "src/io/units.h"

void gravity_props_init(struct gravity_props *gp, const struct params *params,
                        const struct unit_system *us) {
  double eps = params_get_real(params, "Gravity:softening");
  if (eps == 0.0) eps = params_get_real(params, "Gravity:max_physical_baryon_softening");
  /* choices "spline|plummer" in the order of enum gravity_softening */
  const int kind = params_get_enum(params, "Gravity:softening_kernel");
  gravity_props_set(gp, units_G(us), params_get_real(params, "Gravity:theta_cr"), eps, kind,
                    (int)params_get_int(params, "Gravity:multipole_order"));
  gp->enabled = params_get_bool(params, "Gravity:enabled");
  gp->direct = params_get_bool(params, "Gravity:direct");
  gp->eta = params_get_real(params, "Gravity:eta");
  gp->epsilon_fmm = params_get_real(params, "Gravity:epsilon_fmm");
  gp->reuse_steps = (int)params_get_int(params, "Gravity:reuse_steps");
  gp->active_only = params_get_bool(params, "Gravity:active_only");
  gp->reuse_tol = params_get_real(params, "Gravity:reuse_tolerance");
  gp->h_factor = params_get_real(params, "Gravity:softening_h_factor");
  if (gp->h_factor > 0.0 && kind != GRAVITY_SOFTENING_SPLINE)
    error_exit(
        "%s: Gravity:softening_h_factor > 0 (softening tied to h) needs Gravity:softening_kernel: "
        "spline (the Plummer expansions use one constant softening)",
        params_filename(params));
  if (gp->enabled && gp->h_factor > 0.0 && gp->reuse_steps > 0) {
    /* the kept cell supports would not follow h (theory/gravity.md) */
    error_warning(
        "Gravity:reuse_steps %d is not used: the far-field reuse does not follow the "
        "changes of h that Gravity:softening_h_factor ties the softening to",
        gp->reuse_steps);
    gp->reuse_steps = 0;
  }
  if (gp->enabled && eps > 0.0 && gp->h_factor > 0.0)
    error_warning(
        "Gravity:softening %g is not used: Gravity:softening_h_factor %g sets eps_i = "
        "factor * h_i",
        eps, gp->h_factor);
  if (gp->enabled && eps == 0.0 && gp->h_factor <= 0.0)
    error_warning("Gravity:softening is 0: close pairs of particles will see a singular force");
}
