/* bolide-ic: the initial-condition generators and their options. */
#ifndef BOLIDE_IC_TOOLS_H
#define BOLIDE_IC_TOOLS_H

#include <stdint.h>

#include "src/part.h"

/** Particle arrangements of a uniform region. */
enum icgen_lattice {
  ICGEN_CUBIC, /**< simple cubic: one particle per cubic cell */
  ICGEN_FCC,   /**< face-centred cubic: four particles per cubic cell */
  ICGEN_HCP,   /**< hexagonal close packed: ABAB layers of triangular lattices */
};

/** Every option of every subcommand (each takes what applies to it). */
struct icgen_opts {
  const char *output;         /**< output file */
  enum icgen_lattice lattice; /**< --lattice */
  int n;                      /**< --n: lattice cells (cubic/hcp: particles) along x; 0 = unset */
  int nx[3];                  /**< --nx NX,NY,NZ (0 = unset) */
  double size[3];             /**< --size L[,Ly,Lz] */
  double rho;                 /**< --rho density */
  double u;                   /**< --u specific internal energy */
  double perturb;             /**< --perturb: random displacement in units of the spacing */
  uint64_t seed;              /**< --seed of the displacement */
  int periodic;               /**< --periodic / --no-periodic */
  int32_t mat;                /**< --mat material id */
  double eta;                 /**< --eta: h = eta x mean spacing */
  double energy;              /**< sedov: --energy deposited */
  double radius;              /**< sedov: --radius of the deposit (0: 2 h) */
  int kernel_weighting;       /**< sedov: --weighting kernel (1) or uniform (0) */
  double gamma;               /**< sod: adiabatic index used to turn P into u */
};

/** Uniform box (lattice, optionally perturbed).  Fills p; box = side lengths. */
void icgen_box(const struct icgen_opts *o, struct parts *p);
/** Sod shock tube in 3-D: two lattices with density ratio 8 along x, equal
 *  particle masses, periodic in x with interfaces at x = 0 and x = Lx/2. */
void icgen_sod(const struct icgen_opts *o, struct parts *p);
/** Sedov-Taylor blast: a uniform lattice with energy E deposited at the centre. */
void icgen_sedov(const struct icgen_opts *o, struct parts *p);

#endif
