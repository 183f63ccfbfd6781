/* Run-time constants of the hydrodynamics scheme (from the SPH section). */
#ifndef BOLIDE_HYDRO_PROPS_H
#define BOLIDE_HYDRO_PROPS_H

struct params;

/** Hydrodynamics settings shared by the density, ghost, force and time-step
 *  tasks.  Plain data: copied to the GPU as is. */
struct hydro_props {
  int enabled;          /**< SPH:hydro */
  double eta;           /**< SPH:resolution_eta, h = eta * (1/n)^(1/3) */
  double h_tolerance;   /**< relative tolerance of the h iteration */
  double h_max;         /**< largest smoothing length */
  int max_iterations;   /**< of the h iteration */
  double cfl;           /**< Courant factor */
  double log_max_volume_change; /**< ln of the largest kernel-volume change per step */
  double alpha;         /**< artificial viscosity alpha (Monaghan 1997) */
  double beta;          /**< signal-velocity beta (Monaghan 1997) */
  int balsara;          /**< Balsara (1995) switch on/off */
  double alpha_u;       /**< artificial conduction (Price 2008), 0 = off */
  int continuity;       /**< 1: density from the continuity equation */
  double xsph;          /**< XSPH epsilon (Monaghan 1989), 0 = off */
};

/** Read the SPH section. */
void hydro_props_init(struct hydro_props *hp, const struct params *p);

#endif
