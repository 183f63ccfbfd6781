/* Weibull flaws of brittle materials (Benz & Asphaug 1995, Sect. 3.2;
 * theory/damage.md D1-D2).
 *
 * Every brittle particle carries a few activation thresholds (strains); all
 * of them live in one flat array, the particle's own being a slice
 * eps[offset[i] .. offset[i+1]-1], sorted ascending (theory/architecture.md,
 * "Data layout").  In files the slices follow the particle order of the file
 * (/PartType0/FlawThresholds and /PartType0/FlawOffsets, N + 1 entries); in
 * the engine, whose particles are reordered on every rebuild, each particle
 * keeps the index of its first flaw and its count, and the flat array stays
 * where it is.
 *
 * The procedure of Benz & Asphaug: draw a random brittle particle, give it
 * the next flaw eps_j = (j / (k V))^(1/m), j = 1, 2, ..., until every
 * brittle particle has at least one.  The number of flaws with threshold
 * below eps is then exactly floor(k V eps^m) (the Weibull law), and about
 * N (ln N + 0.577) flaws are drawn in all (the coupon collector). */
#ifndef BOLIDE_FLAWS_H
#define BOLIDE_FLAWS_H

#include <stddef.h>
#include <stdint.h>

/** Flaws of n_parts particles in the layout of the files. */
struct flaws {
  size_t n_parts;  /**< number of particles */
  int64_t *offset; /**< n_parts + 1 offsets into eps; offset[0] = 0 */
  double *eps;     /**< offset[n_parts] thresholds, ascending per particle */
};

/** State of the xoshiro256** generator (Blackman & Vigna 2021), seeded by
 *  splitmix64 (Steele et al. 2014): portable, so that a seed gives the same
 *  flaws on every machine. */
struct flaws_rng {
  uint64_t s[4]; /**< generator state */
};

/** Seed the generator (any seed, 0 included). */
void flaws_rng_seed(struct flaws_rng *r, uint64_t seed);
/** Next 64 random bits. */
uint64_t flaws_rng_next(struct flaws_rng *r);
/** Uniform integer in [0, n), n >= 1, without modulo bias (Lemire 2019). */
uint64_t flaws_rng_below(struct flaws_rng *r, uint64_t n);

/** Threshold of the j-th flaw (j >= 1) of a body of volume V with Weibull
 *  parameters k (per volume) and m: (j / (k V))^(1/m)  (BA95; D1). */
double flaws_threshold(int64_t j, double k, double m, double V);

/** Total volume sum m_i / rho_i of the particles with select[i] != 0. */
double flaws_volume(size_t n, const double *mass, const double *rho, const unsigned char *select);

/** Give flaws to the n particles with brittle[i] != 0 by the procedure of
 *  Benz & Asphaug (above), with Weibull k, m, the body's volume V and a
 *  seed.  Particles with brittle[i] == 0 keep their flaws from `keep` (may
 *  be NULL: none), so that several materials can be done one after the
 *  other.  Fills out (allocated here; out may not alias keep).  Returns the
 *  number of flaws drawn (0 if no particle is brittle). */
int64_t flaws_generate(size_t n, const unsigned char *brittle, double k, double m, double V,
                       uint64_t seed, const struct flaws *keep, struct flaws *out);

struct material_table;

/** Flaws for every brittle material of table t (weibull_k > 0), for
 *  start-up from a recorded seed when the initial conditions have none: one
 *  flaws_generate per material, in table order, with V the sum of m/rho of
 *  its particles (rho0 of the material where rho <= 0) and the seed
 *  seed + material id, so that adding a material leaves the others' flaws
 *  unchanged.  Fills out (every particle zero flaws if no material is
 *  brittle); returns the total number of flaws. */
int64_t flaws_generate_materials(size_t n, const int32_t *mat, const double *mass,
                                 const double *rho, const struct material_table *t, uint64_t seed,
                                 struct flaws *out);

/** Check the layout: offsets start at 0 and never decrease, thresholds are
 *  finite, non-negative and ascending within each particle.  Returns 0, or
 *  -1 with the first problem in msg. */
int flaws_check(const struct flaws *f, char *msg, size_t len);

/** The thresholds' part of flaws_check, for offsets already checked (n
 *  particles, offset[n + 1], eps): the check of flaws_ragged. */
int flaws_check_values(size_t n, const int64_t *offset, const double *eps, char *msg, size_t len);

struct ragged_io_desc;

/** How files store the flaws (src/io/ragged_io.h): /PartType0/FlawThresholds
 *  (all thresholds, one flat double array, dimensionless strains) and
 *  /PartType0/FlawOffsets (N + 1 int64), in the particle order of the file,
 *  checked by flaws_check_values.  The io layer reads and writes them
 *  through this description without knowing the damage model. */
extern const struct ragged_io_desc flaws_ragged;

/** Read the flaws of the n particles of `path` (ragged_io_read of
 *  flaws_ragged).  Returns 1 and fills f when the file has them, 0 (f
 *  zeroed) when it has neither dataset.  A file with only one of them, a
 *  length other than n + 1 offsets, or a layout that fails flaws_check stops
 *  with one line naming the file. */
int flaws_io_read(const char *path, size_t n, struct flaws *f);

/** Add (or replace) the flaws f in the existing HDF5 file `path` (its
 *  /PartType0 must exist).  Stops with one line naming the file on failure. */
void flaws_io_write_file(const char *path, const struct flaws *f);

/** Bytes held by f (thresholds and offsets). */
size_t flaws_bytes(const struct flaws *f);

/** Free the arrays of f and zero it. */
void flaws_free(struct flaws *f);

#endif
