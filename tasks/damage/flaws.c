/* Weibull flaws: see flaws.h and theory/damage.md. */
#include "tasks/damage/flaws.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "src/materials/material.h"
#include "src/io/ragged_io.h"
#include "tasks/task_families.h" /* declares flaws_check_values too (an entry point) */

/** splitmix64 step (Steele, Lea & Flood 2014): seeds xoshiro's state. */
static uint64_t flaws_splitmix64(uint64_t *x) {
  uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/** Rotate left by k bits. */
static inline uint64_t flaws_rotl(uint64_t x, int k) {
  return (x << k) | (x >> (64 - k));
}

void flaws_rng_seed(struct flaws_rng *r, uint64_t seed) {
  uint64_t x = seed;
  for (int i = 0; i < 4; i++) r->s[i] = flaws_splitmix64(&x);
}

uint64_t flaws_rng_next(struct flaws_rng *r) {
  /* xoshiro256** (Blackman & Vigna 2021, Fig. 1 there) */
  uint64_t *s = r->s;
  const uint64_t result = flaws_rotl(s[1] * 5, 7) * 9;
  const uint64_t t = s[1] << 17;
  s[2] ^= s[0];
  s[3] ^= s[1];
  s[1] ^= s[2];
  s[0] ^= s[3];
  s[2] ^= t;
  s[3] = flaws_rotl(s[3], 45);
  return result;
}

uint64_t flaws_rng_below(struct flaws_rng *r, uint64_t n) {
  /* multiply-shift with rejection of the biased low products (Lemire 2019,
   * Algorithm 5) */
  unsigned __int128 p = (unsigned __int128)flaws_rng_next(r) * n;
  uint64_t lo = (uint64_t)p;
  if (lo < n) {
    const uint64_t t = (0 - n) % n;
    while (lo < t) {
      p = (unsigned __int128)flaws_rng_next(r) * n;
      lo = (uint64_t)p;
    }
  }
  return (uint64_t)(p >> 64);
}

double flaws_threshold(int64_t j, double k, double m, double V) {
  return pow((double)j / (k * V), 1.0 / m);
}

double flaws_volume(size_t n, const double *mass, const double *rho, const unsigned char *select) {
  double V = 0.0;
  for (size_t i = 0; i < n; i++)
    if (select[i] && rho[i] > 0.0) V += mass[i] / rho[i];
  return V;
}

int64_t flaws_generate(size_t n, const unsigned char *brittle, double k, double m, double V,
                       uint64_t seed, const struct flaws *keep, struct flaws *out) {
  if (keep && keep->n_parts != n)
    error_bug("flaws_generate: keep has %zu particles, not %zu", keep->n_parts, n);
  if (!(k > 0.0) || !(m > 0.0) || !(V > 0.0))
    error_bug("flaws_generate: k = %g, m = %g, V = %g must be positive", k, m, V);
  /* the brittle particles, numbered 0 .. nb-1 */
  size_t nb = 0;
  for (size_t i = 0; i < n; i++) nb += brittle[i] != 0;
  size_t *which = error_malloc((nb ? nb : 1) * sizeof *which, "flaws: brittle list");
  nb = 0;
  for (size_t i = 0; i < n; i++)
    if (brittle[i]) which[nb++] = i;

  /* pass 1: draw until every brittle particle has a flaw, counting */
  int64_t *count = error_calloc(n ? n : 1, sizeof *count, "flaws: counts");
  struct flaws_rng rng;
  flaws_rng_seed(&rng, seed);
  int64_t drawn = 0;
  size_t covered = 0;
  while (covered < nb) {
    const size_t i = which[flaws_rng_below(&rng, nb)];
    if (count[i]++ == 0) covered++;
    drawn++;
  }

  /* offsets: new counts for brittle particles, kept ones for the others */
  out->n_parts = n;
  out->offset = error_malloc((n + 1) * sizeof *out->offset, "flaws: offsets");
  out->offset[0] = 0;
  for (size_t i = 0; i < n; i++) {
    int64_t c = count[i];
    if (!brittle[i]) c = keep ? keep->offset[i + 1] - keep->offset[i] : 0;
    out->offset[i + 1] = out->offset[i] + c;
  }
  const int64_t total = out->offset[n];
  out->eps = error_malloc((size_t)(total ? total : 1) * sizeof *out->eps, "flaws: thresholds");
  for (size_t i = 0; i < n; i++)
    if (!brittle[i] && keep && out->offset[i + 1] > out->offset[i])
      memcpy(out->eps + out->offset[i], keep->eps + keep->offset[i],
             (size_t)(out->offset[i + 1] - out->offset[i]) * sizeof *out->eps);

  /* pass 2: replay the same draws; the j-th goes to the next free slot of
   * its particle, so each slice is ascending */
  for (size_t i = 0; i < n; i++) count[i] = out->offset[i];
  flaws_rng_seed(&rng, seed);
  const double inv_m = 1.0 / m, log_kV = log(k * V);
  for (int64_t j = 1; j <= drawn; j++) {
    const size_t i = which[flaws_rng_below(&rng, nb)];
    out->eps[count[i]++] = exp(inv_m * (log((double)j) - log_kV)); /* D1 */
  }
  free(count);
  free(which);
  return drawn;
}

int64_t flaws_generate_materials(size_t n, const int32_t *mat, const double *mass,
                                 const double *rho, const struct material_table *t, uint64_t seed,
                                 struct flaws *out) {
  out->n_parts = n;
  out->offset = error_calloc(n + 1, sizeof *out->offset, "flaws: offsets");
  out->eps = error_malloc(sizeof *out->eps, "flaws: thresholds");
  unsigned char *sel = error_malloc(n ? n : 1, "flaws: selection");
  for (int k = 0; k < t->n; k++) {
    const struct material *m = &t->mats[k];
    if (!(m->weibull_k > 0.0)) continue;
    double V = 0.0;
    size_t nb = 0;
    for (size_t i = 0; i < n; i++) {
      sel[i] = mat[i] == m->id;
      if (!sel[i]) continue;
      nb++;
      V += mass[i] / (rho[i] > 0.0 ? rho[i] : m->rho0);
    }
    if (nb == 0) continue;
    struct flaws next;
    flaws_generate(n, sel, m->weibull_k, m->weibull_m, V, seed + (uint64_t)m->id, out, &next);
    flaws_free(out);
    *out = next;
  }
  free(sel);
  return out->offset[n];
}

int flaws_check_values(size_t n, const int64_t *offset, const double *eps, char *msg, size_t len) {
  for (size_t i = 0; i < n; i++) {
    const int64_t a = offset[i], b = offset[i + 1];
    for (int64_t j = a; j < b; j++) {
      if (!isfinite(eps[j]) || eps[j] < 0.0) {
        snprintf(msg, len, "particle %zu: flaw threshold %g (must be finite and >= 0)", i, eps[j]);
        return -1;
      }
      if (j > a && eps[j] < eps[j - 1]) {
        snprintf(msg, len, "particle %zu: flaw thresholds not in ascending order", i);
        return -1;
      }
    }
  }
  return 0;
}

int flaws_check(const struct flaws *f, char *msg, size_t len) {
  /* offsets first, so that the threshold loop stays inside the array */
  if (ragged_io_check_offsets(flaws_ragged.offsets_name, f->n_parts, f->offset,
                              (size_t)f->offset[f->n_parts], msg, len))
    return -1;
  return flaws_check_values(f->n_parts, f->offset, f->eps, msg, len);
}

/** The flaws in HDF5 files, in the particle order of the file. */
const struct ragged_io_desc flaws_ragged = {
    "FlawThresholds", "FlawOffsets",
    "Weibull flaw activation strains of all particles, ascending per particle (slices given by "
    "FlawOffsets)",
    "N+1 offsets: particle i owns FlawThresholds[off[i]:off[i+1]]", flaws_check_values};

int flaws_io_read(const char *path, size_t n, struct flaws *f) {
  memset(f, 0, sizeof *f);
  if (!ragged_io_read(path, &flaws_ragged, n, &f->offset, &f->eps)) return 0;
  f->n_parts = n;
  return 1;
}

void flaws_io_write_file(const char *path, const struct flaws *f) {
  ragged_io_write_file(path, &flaws_ragged, f->n_parts, f->offset, f->eps);
}

size_t flaws_bytes(const struct flaws *f) {
  if (!f->offset) return 0;
  return (f->n_parts + 1) * sizeof(int64_t) + (size_t)f->offset[f->n_parts] * sizeof(double);
}

void flaws_free(struct flaws *f) {
  free(f->offset);
  free(f->eps);
  memset(f, 0, sizeof *f);
}
