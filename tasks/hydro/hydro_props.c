/* Hydrodynamics settings from the SPH section. */
#include "tasks/hydro/hydro_props.h"

#include <math.h>

#include "tasks/hydro/kernel.h"
#include "src/io/params.h"

void hydro_props_init(struct hydro_props *hp, const struct params *p) {
  hp->enabled = params_get_bool(p, "SPH:hydro");
  hp->eta = params_get_real(p, "SPH:resolution_eta");
  hp->h_tolerance = params_get_real(p, "SPH:h_tolerance");
  hp->h_taylor = params_get_bool(p, "SPH:h_taylor") ? sqrt(hp->h_tolerance / 6.0) : 0.0;
  hp->h_max = params_get_real(p, "SPH:h_max");
  hp->max_iterations = (int)params_get_int(p, "SPH:max_ghost_iterations");
  hp->h_continuity = params_get_enum(p, "SPH:h_evolution") == 1;
  hp->cfl = params_get_real(p, "SPH:CFL_condition");
  hp->log_max_volume_change = log(params_get_real(p, "SPH:max_volume_change"));
  hp->alpha = params_get_real(p, "SPH:viscosity_alpha");
  hp->beta = params_get_real(p, "SPH:viscosity_beta");
  hp->balsara = params_get_bool(p, "SPH:balsara");
  hp->alpha_u = params_get_real(p, "SPH:conductivity_alpha");
  hp->continuity = params_get_enum(p, "SPH:density") == 1;
  hp->continuity_cspm = params_get_bool(p, "SPH:continuity_correction");
  hp->continuity_min_ratio = params_get_real(p, "SPH:continuity_min_density_ratio");
  if (hp->continuity_cspm && !hp->continuity)
    params_error(p, "SPH:continuity_correction", "needs SPH:density: continuity");
  hp->xsph = params_get_real(p, "SPH:xsph_epsilon");
  hp->free_surface = params_get_bool(p, "SPH:free_surface");
  hp->free_surface_threshold = params_get_real(p, "SPH:free_surface_threshold");
  /* with summation density the kernel sum is ~1 everywhere: rho_j is itself
   * the kernel sum at j, so the surface's low densities make up its missing
   * neighbours (theory/fluids.md) */
  if (hp->free_surface && !hp->continuity)
    params_error(p, "SPH:free_surface", "needs SPH:density: continuity");
  hp->fluid_solid_interface = params_get_bool(p, "SPH:fluid_solid_interface");
  if (hp->fluid_solid_interface && !hp->continuity_cspm)
    params_error(p, "SPH:fluid_solid_interface",
                 "needs SPH:density: continuity and SPH:continuity_correction: true");
  hp->solids = 0; /* set by the engine from the materials */
  hp->momentum_form = params_get_enum(p, "SPH:momentum_form");
  hp->gradient_correction = params_get_bool(p, "SPH:velocity_gradient_correction");
  hp->as_eps = params_get_real(p, "SPH:artificial_stress_epsilon");
  hp->as_n = params_get_real(p, "SPH:artificial_stress_n");
  /* the kernel at the mean particle spacing dp = h / eta (Monaghan 2000, Sec. 4) */
  hp->as_wdp_inv = 1.0 / kernel_W(1.0 / hp->eta, 1.0);
  hp->max_rel_change = params_get_real(p, "SPH:max_relative_change");
}
