/* The integer time line of individual time steps (issue 20; the scheme of
 * SWIFT, Schaller et al. 2024, MNRAS 530, 2378, section 2.3).
 *
 * The run [time_begin, time_end] is cut into 2^TIMELINE_NR_BINS ticks of
 * time_base = (time_end - time_begin) / 2^TIMELINE_NR_BINS.  A particle in
 * time bin b (1 <= b <= TIMELINE_NR_BINS) steps by 2^b ticks, from one
 * multiple of 2^b to the next, so that the steps of all bins meet exactly
 * (integer arithmetic) at every multiple of the longest step in use, and the
 * top bin is the whole run: time_end is on the time line.  Bin 0 holds no
 * particle (time step 0).
 *
 * A particle's bin is the longest whose step is at most its own limit and at
 * most TimeIntegration:dt_max (the power-of-two ladder is anchored at the run
 * length rather than at dt_max, so that time_end is reached exactly and the
 * number of dt_max in a run is not bounded by the 64 bits of the time line;
 * a particle's step is still within a factor 2 of its limit).  A particle
 * may move to a shorter bin at any of its steps' ends, to a longer one only
 * at a time that is a multiple of the longer step (timeline_bin_allowed).
 *
 * Pure functions only, usable on the host and the device. */
#ifndef BOLIDE_TIMELINE_H
#define BOLIDE_TIMELINE_H

#include <math.h>
#include <stdint.h>

#include "src/inline.h"

/** Number of time bins; the time line of the run has 2^TIMELINE_NR_BINS
 *  ticks (2^56: a ratio of 7e16 between the run and its shortest step). */
#define TIMELINE_NR_BINS 56

/** A point or a length on the integer time line, in ticks. */
typedef int64_t integertime_t;

/** The time line of a run. */
struct timeline {
  double time_begin; /**< TimeIntegration:time_begin: tick 0 */
  double time_base;  /**< physical length of one tick */
  int bin_max;       /**< longest bin allowed: its step <= TimeIntegration:dt_max */
};

/** What a cell's kick with time bins leaves for the engine
 *  (kick2_cell_bins_cpu). */
struct timeline_sums {
  integertime_t ti_end_min; /**< the earliest end of a step of its particles (INT64_MAX: none) */
  int64_t active;           /**< particles that ended their step at ti_new */
};

/** Steps of bin bin in ticks: 2^bin, 0 for bin <= 0 (no bin). */
BOLIDE_INLINE integertime_t timeline_step_of_bin(int bin) {
  if (bin <= 0) return 0;
  if (bin > TIMELINE_NR_BINS) bin = TIMELINE_NR_BINS;
  return (integertime_t)1 << bin;
}

/** Position of the lowest set bit of ti > 0 (0 for odd ti); 64 for 0. */
BOLIDE_INLINE int timeline_trailing_zeros(integertime_t ti) {
  if (ti == 0) return 64;
#if defined(__CUDA_ARCH__)
  return __ffsll((long long)ti) - 1;
#elif defined(__GNUC__)
  return __builtin_ctzll((unsigned long long)ti);
#else
  uint64_t u = (uint64_t)ti;
  int n = 0;
  while (!(u & 1u)) {
    u >>= 1;
    n++;
  }
  return n;
#endif
}

/** Position of the highest set bit of ti > 0 (floor(log2 ti)); -1 for 0. */
BOLIDE_INLINE int timeline_log2(integertime_t ti) {
  if (ti == 0) return -1;
#if defined(__CUDA_ARCH__)
  return 63 - __clzll((long long)ti);
#elif defined(__GNUC__)
  return 63 - __builtin_clzll((unsigned long long)ti);
#else
  int n = -1;
  uint64_t u = (uint64_t)ti;
  while (u) {
    u >>= 1;
    n++;
  }
  return n;
#endif
}

/** The time line of a run from time_begin to time_end (> time_begin) with
 *  the longest step dt_max (> 0). */
BOLIDE_INLINE struct timeline timeline_make(double time_begin, double time_end, double dt_max) {
  struct timeline tl;
  tl.time_begin = time_begin;
  tl.time_base = ldexp(time_end - time_begin, -TIMELINE_NR_BINS);
  tl.bin_max = TIMELINE_NR_BINS;
  while (tl.bin_max > 1 && ldexp(tl.time_base, tl.bin_max) > dt_max) tl.bin_max--;
  return tl;
}

/** Physical time of integer time ti. */
BOLIDE_INLINE double timeline_time(const struct timeline *tl, integertime_t ti) {
  return tl->time_begin + (double)ti * tl->time_base;
}

/** Integer time nearest to physical time t (within the run). */
BOLIDE_INLINE integertime_t timeline_integer_time(const struct timeline *tl, double t) {
  return (integertime_t)llround((t - tl->time_begin) / tl->time_base);
}

/** Physical length of the steps of bin bin. */
BOLIDE_INLINE double timeline_dt_of_bin(const struct timeline *tl, int bin) {
  return (double)timeline_step_of_bin(bin) * tl->time_base;
}

/** Bin of a particle whose time-step limit is dt: the longest bin whose
 *  step is at most dt and at most dt_max (tl->bin_max); 0 when even bin 1
 *  (two ticks) is longer than dt, or dt is not a positive number. */
BOLIDE_INLINE int timeline_bin(const struct timeline *tl, double dt) {
  if (!(dt > 0.0)) return 0;
  const double ticks = dt / tl->time_base;
  if (ticks >= ldexp(1.0, tl->bin_max)) return tl->bin_max;
  /* ticks < 2^bin_max <= 2^56: exact in an integer; the division by a power
   * of two times time_base is exact at the bins' edges */
  const int bin = timeline_log2((integertime_t)ticks);
  return bin >= 1 ? bin : 0;
}

/** Whether a particle of bin bin ends a step (and starts the next) at
 *  integer time ti: ti is a multiple of its step. */
BOLIDE_INLINE int timeline_is_active(int bin, integertime_t ti) {
  if (bin <= 0) return 0;
  return ti % timeline_step_of_bin(bin) == 0;
}

/** The longest bin active at ti (every bin up to it is active there). */
BOLIDE_INLINE int timeline_max_active_bin(integertime_t ti) {
  const int n = timeline_trailing_zeros(ti);
  return n < TIMELINE_NR_BINS ? n : TIMELINE_NR_BINS;
}

/** The first integer time after ti at which bin bin is active: the next
 *  synchronisation point of that bin (ti + its step when ti is one). */
BOLIDE_INLINE integertime_t timeline_next_sync(int bin, integertime_t ti) {
  const integertime_t s = timeline_step_of_bin(bin);
  if (s == 0) return ti;
  return (ti / s + 1) * s;
}

/** The bin that a particle of bin old_bin, at the end of its step at ti,
 *  takes when its limit asks for new_bin: any shorter bin at once, a longer
 *  one only as far as ti is a synchronisation point of it
 *  (min(new_bin, max(old_bin, timeline_max_active_bin(ti)))). */
BOLIDE_INLINE int timeline_bin_allowed(int old_bin, int new_bin, integertime_t ti) {
  if (new_bin <= old_bin) return new_bin;
  const int sync = timeline_max_active_bin(ti);
  const int b = sync > old_bin ? sync : old_bin;
  return new_bin < b ? new_bin : b;
}

/** Fraction of particle updates that time bins would do, over one step of
 *  the longest bin in use, against a global step at the shortest:
 *  sum_b n[b] 2^(b_min - b) / sum_b n[b], for counts n[0..TIMELINE_NR_BINS]
 *  of particles by bin (bin 0 counts as the shortest); 1 with no particle. */
BOLIDE_INLINE double timeline_active_fraction(const int64_t n[TIMELINE_NR_BINS + 1]) {
  int b_min = -1;
  double tot = 0.0, upd = 0.0;
  for (int b = 0; b <= TIMELINE_NR_BINS; b++)
    if (n[b] > 0) {
      if (b_min < 0) b_min = b;
      tot += (double)n[b];
      upd += ldexp((double)n[b], b_min - b);
    }
  return tot > 0.0 ? upd / tot : 1.0;
}

#endif
