/* Run-time constants of the hydrodynamics scheme (from the SPH section). */
#ifndef BOLIDE_HYDRO_PROPS_H
#define BOLIDE_HYDRO_PROPS_H

struct params;

/** Hydrodynamics settings shared by the density, ghost, force and time-step
 *  tasks.  Plain data: copied to the GPU as is. */
struct hydro_props {
  int enabled;        /**< SPH:hydro */
  double eta;         /**< SPH:resolution_eta, h = eta * (1/n)^(1/3) */
  double h_tolerance; /**< relative tolerance of the h iteration */
  double h_taylor;    /**< largest relative Newton step of h taken with the sums corrected to first
                           order (SPH:h_taylor: sqrt(h_tolerance / 6); 0: none) */
  double h_max;       /**< largest smoothing length */
  int max_iterations; /**< of the h iteration */
  int h_continuity;   /**< SPH:h_evolution: continuity (dh/dt = -h/(3 rho) drho/dt, no iteration) */
  int bin_limit;      /**< time bins: TimeIntegration:max_bin_ratio (the force loop's limiter);
                           0 with the global step */
  int wake_density;   /**< time bins: TimeIntegration:limiter_wake density (the density loop
                           wakes, tasks/density/density_wake.h); 0 with the global step */
  int stage_end;      /**< 1 during the evaluation at the end of a step of TimeIntegration:scheme
                           rk2 or pc: the kick, which kicks nothing there, returns porous
                           particles to their crush curve (tasks/drift/drift_integrate.c) */
  double cfl;         /**< Courant factor */
  double log_max_volume_change; /**< ln of the largest kernel-volume change per step */
  double alpha;                 /**< artificial viscosity alpha (Monaghan 1997) */
  double beta;                  /**< signal-velocity beta (Monaghan 1997) */
  int balsara;                  /**< Balsara (1995) switch on/off */
  double alpha_u;               /**< artificial conduction (Price 2008), 0 = off */
  int continuity;               /**< 1: density from the continuity equation */
  int continuity_cspm;          /**< 1: drho/dt = -rho tr(corrected velocity gradient) (CSPM) */
  double continuity_min_ratio;  /**< continuity density floor in units of the material's rho0 */
  double xsph;                  /**< XSPH epsilon (Monaghan 1989), 0 = off */
  int free_surface; /**< 1: pressure 0 on fluid particles at the free surface (SPH:free_surface) */
  double free_surface_threshold; /**< kernel sum sum_j V_j W_ij below which a fluid particle is on
                                    it */
  int fluid_solid_interface;     /**< 1: fluid-solid pairs take the interface treatment
                                    (SPH:fluid_solid_interface, theory/fluids.md F6-F8) */
  int solids;        /**< 1 when a material has strength: gradient tasks and stress terms run */
  int momentum_form; /**< HYDRO_MOMENTUM_STANDARD or HYDRO_MOMENTUM_SYMMETRIC */
  int gradient_correction; /**< 1: linear-consistency correction of the velocity gradient */
  double as_eps;           /**< artificial stress epsilon_s (Monaghan 2000), 0 = off */
  double as_n;             /**< artificial stress exponent n */
  double as_wdp_inv;       /**< 1 / W(dp, h = 1) with dp = h / eta, the mean particle spacing */
  double max_rel_change; /**< time-step limit on relative changes of rho, u, S per step (0 = off) */
  int external;          /**< 1: a uniform external acceleration g_ext (ConstantPotential:g_cgs) */
  double g_ext[3];       /**< the external acceleration in internal units (set by the engine) */
};

/** Forms of the momentum equation (SPH:momentum_form). */
enum hydro_momentum_form {
  HYDRO_MOMENTUM_STANDARD = 0,  /**< sigma_i/rho_i^2 + sigma_j/rho_j^2 (Gray et al. 2001) */
  HYDRO_MOMENTUM_SYMMETRIC = 1, /**< (sigma_i + sigma_j)/(rho_i rho_j) (Monaghan 1992) */
};

/** Read the SPH section. */
void hydro_props_init(struct hydro_props *hp, const struct params *p);

#endif
