/* bolide-ic planet and impact: hydrostatic profiles of layered planets
 * (Kegerreis et al. 2019, MNRAS 487, 5029, Appendix A; the method of woma,
 * Ruiz-Bonilla et al. 2021), stretched equal-area (SEA) particle shells
 * (Kegerreis et al. 2019, Sect. 2) and two bodies on a collision course.
 * Equations: theory/planets.md. */
#ifndef BOLIDE_IC_PLANET_H
#define BOLIDE_IC_PLANET_H

#include <stddef.h>
#include <stdint.h>

#include "src/materials/material.h"
#include "src/part.h"

/** Largest number of layers of one planet. */
#define IC_PLANET_MAX_LAYERS 8

/** Temperature-density relation of a layer. */
enum ic_planet_trho {
  IC_PLANET_TRHO_POWER, /**< T = K rho^alpha, K fixed at the top of the layer (alpha 0: isothermal)
                         */
  IC_PLANET_TRHO_ADIABATIC, /**< du = P / rho^2 drho along the profile (isentropic) */
};

/** One layer, centre outward. */
struct ic_planet_layer {
  struct material mat;      /**< its material (from the library) */
  enum ic_planet_trho trho; /**< temperature-density relation */
  double alpha;             /**< exponent of the power law */
  double mass_frac;         /**< fraction of the total mass (mass mode), else 0 */
  double r_out;             /**< outer radius (radius mode), else 0 */
  double *u_cold;           /**< Tillotson: tabulated cold energy (woma's u_cold), NULL otherwise */
  double cold_lo;           /**< density of u_cold[0] */
  double cold_drho;         /**< density step of u_cold */
  int cold_n;               /**< entries of u_cold */
};

/** What the planet is made from (command line or body specification). */
struct ic_planet_spec {
  int n_layers;                                       /**< layers, centre outward */
  struct ic_planet_layer layer[IC_PLANET_MAX_LAYERS]; /**< the layers */
  double M;                                           /**< total mass (mass mode), 0: unknown */
  double R;                                           /**< outer radius (radius mode), 0: unknown */
  double P_s;                                         /**< surface pressure */
  double T_s;                                         /**< surface temperature */
  int n_prof;                                         /**< radial steps of the profile */
};

/** Radial profile, centre (index 0, r = 0) outward. */
struct ic_planet_profile {
  size_t n;                             /**< points */
  double *r, *m, *rho, *P, *T, *u;      /**< radius, enclosed mass, density, pressure, T, u */
  int *layer;                           /**< layer index of each point */
  int n_layers;                         /**< layers */
  double R, M;                          /**< outer radius and total mass */
  double r_layer[IC_PLANET_MAX_LAYERS]; /**< outer radius of each layer */
};

/** Parse a temperature-density relation ("isothermal", "adiabatic",
 *  "power=ALPHA"); returns 0 or -1. */
int ic_planet_parse_trho(const char *s, struct ic_planet_layer *l);

/** Prepare the layers (cold-energy tables) and check the specification;
 *  stops with one line naming `what` (the option or body) on bad input. */
void ic_planet_spec_prepare(struct ic_planet_spec *s, const char *what);

/** Specific internal energy of layer l at density rho and temperature T
 *  (Tillotson: u_cold(rho) + cv T, the woma convention). */
double ic_planet_u_rho_T(const struct ic_planet_layer *l, double rho, double T);
/** Temperature of layer l at (rho, u) (inverse of ic_planet_u_rho_T). */
double ic_planet_T_rho_u(const struct ic_planet_layer *l, double rho, double u);

/** Integrate the hydrostatic profile and iterate on R (mass mode) or M
 *  (radius mode) until the mass is used up at the centre. */
void ic_planet_profile_make(struct ic_planet_spec *s, struct ic_planet_profile *prof, double G);
/** Uniform sphere of one material at density rho and energy u. */
void ic_planet_profile_uniform(struct ic_planet_profile *prof, const struct material *mat, double R,
                               double rho, double u, int n);
/** Write the profile as a table (r m rho P T u layer) to path (temp + rename). */
void ic_planet_profile_write(const struct ic_planet_profile *prof, const char *path);
void ic_planet_profile_free(struct ic_planet_profile *prof);
void ic_planet_spec_free(struct ic_planet_spec *s);

/** N points on the unit sphere by stretched equal-area regions (Kegerreis
 *  et al. 2019, Sect. 2.1), randomly rotated with the generator state rng.
 *  For 4 < N <= 20000 the stretching (a, b) and the collar count are those
 *  of a small search that minimise the spread of the shell's SPH density
 *  (theory/planets.md, "One shell of N points"); a = 0.2, b = 2 above. */
void ic_sea_shell(int N, double *x, double *y, double *z, uint64_t *rng);
/** The same with stretching parameter a (b = 10 a). */
void ic_sea_shell_a(int N, double a, double *x, double *y, double *z, uint64_t *rng);

/** Options of the SEA placement of a planet (theory/planets.md, "SEA
 *  planet: the 1 % bar"). */
struct ic_sea_options {
  int density_iter;       /**< iterations of the shells' density against rho_SPH (0: none) */
  int relax;              /**< steps of relaxation along the shells (0: none) */
  double shell_thickness; /**< shell thickness over the particle spacing (m/rho)^(1/3) */
  double stretch_a;       /**< a of the latitude stretching (b = 10 a) */
};
/** The defaults of bolide-ic planet (theory/planets.md). */
#define IC_SEA_OPTIONS_DEFAULT \
  { .density_iter = 6, .relax = 30, .shell_thickness = 1.2, .stretch_a = 0.15 }

/** Particles of a profile on SEA shells: about N of them, masses equal
 *  within rounding, h = eta (m/rho)^(1/3), MaterialIDs mat_id[layer], ids
 *  first_id, first_id+1, ...  Prints one line per layer to stdout when
 *  verbose. */
void ic_sea_planet(const struct ic_planet_profile *prof, const int32_t *mat_id, size_t N,
                   double eta, uint64_t seed, int64_t first_id, struct parts *p,
                   const struct ic_sea_options *opt, int verbose);

/** SPH density rho of n points as Bolide computes it at start-up: h solves
 *  sum_j W(r_ij, h) = (eta / h)^3 (h: the guess in, the solution out). */
void ic_sph_density(size_t n, const double *x, const double *y, const double *z, const double *m,
                    double eta, double *h, double *rho);

/** `steps` steps of relaxation of the points along their spheres about the
 *  origin, towards rho_SPH = rho_t; leaves h and rho of the final positions. */
void ic_sea_relax(size_t n, double *x, double *y, double *z, const double *m, const double *rho_t,
                  double eta, double *h, double *rho, int steps);

/** splitmix64 (Steele, Lea & Flood 2014). */
uint64_t ic_rng_next(uint64_t *s);
/** Uniform random number in [0, 1). */
double ic_rng_uniform(uint64_t *s);

#endif
