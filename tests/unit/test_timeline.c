/* The integer time line of individual time steps (src/timeline.h, issue 20):
 *  - integer time to physical time and back is exact at the bins' edges and
 *    within half a tick elsewhere; time_end is on the time line;
 *  - a time-step limit goes to the longest bin whose step is at most the
 *    limit and at most dt_max (so the step is within a factor 2 of the
 *    limit), 0 below the shortest bin;
 *  - the bins active at a time are those whose step divides it, and every
 *    bin's steps meet at the synchronisation points of the longer bins;
 *  - a particle moves to a shorter bin at once, to a longer one only at a
 *    synchronisation point of the longer one;
 *  - the fraction of updates time bins would do. */
#include <math.h>
#include <stdio.h>

#include "src/timeline.h"

#include "tests/helpers/check.h"

static void test_round_trip(void) {
  const struct timeline tl = timeline_make(-3.0, 2e4, 1e30);
  CHECK(tl.bin_max == TIMELINE_NR_BINS, "dt_max above the run: bin_max %d", tl.bin_max);
  const integertime_t end = timeline_step_of_bin(TIMELINE_NR_BINS);
  CHECK(timeline_time(&tl, 0) == -3.0, "tick 0 is time_begin");
  CHECK(timeline_time(&tl, end) == 2e4, "the last tick is time_end: %.17g",
        timeline_time(&tl, end));
  CHECK(timeline_integer_time(&tl, 2e4) == end, "time_end to the last tick");
  CHECK(timeline_dt_of_bin(&tl, TIMELINE_NR_BINS) == 2e4 + 3.0, "the top bin is the run");
  /* multiples of a bin's step round-trip exactly, here those of bin 30 */
  const integertime_t s30 = timeline_step_of_bin(30);
  for (integertime_t k = 0; k <= end / s30; k += 4099) {
    const integertime_t ti = k * s30;
    CHECK(timeline_integer_time(&tl, timeline_time(&tl, ti)) == ti, "round trip of %lld",
          (long long)ti);
  }
  /* any time maps to the nearest tick at small bins, within rounding */
  const integertime_t ti = 123456789LL;
  const double t = timeline_time(&tl, ti);
  const integertime_t back = timeline_integer_time(&tl, t);
  CHECK(back >= ti - 1 && back <= ti + 1, "round trip near tick %lld: %lld", (long long)ti,
        (long long)back);
}

static void test_bins(void) {
  /* a run of 1024 s with dt_max 10 s: bin_max's step 8 s */
  const struct timeline tl = timeline_make(0.0, 1024.0, 10.0);
  CHECK(timeline_dt_of_bin(&tl, tl.bin_max) == 8.0, "longest step %g (8 s)",
        timeline_dt_of_bin(&tl, tl.bin_max));
  CHECK(timeline_bin(&tl, 1e9) == tl.bin_max, "a long limit takes bin_max");
  CHECK(timeline_bin(&tl, 8.0) == tl.bin_max, "8 s takes bin_max exactly");
  CHECK(timeline_dt_of_bin(&tl, timeline_bin(&tl, 7.999)) == 4.0, "7.999 s steps by 4 s");
  CHECK(timeline_dt_of_bin(&tl, timeline_bin(&tl, 4.0)) == 4.0, "4 s steps by 4 s");
  CHECK(timeline_dt_of_bin(&tl, timeline_bin(&tl, 0.3)) == 0.25, "0.3 s steps by 0.25 s");
  /* the bin's step is within a factor 2 of any limit */
  for (double dt = 1e-12; dt < 8.0; dt *= 1.37) {
    const double s = timeline_dt_of_bin(&tl, timeline_bin(&tl, dt));
    CHECK(s <= dt && 2.0 * s > dt, "limit %g: step %g", dt, s);
  }
  CHECK(timeline_bin(&tl, 0.0) == 0 && timeline_bin(&tl, -1.0) == 0 && timeline_bin(&tl, NAN) == 0,
        "no bin for a limit that is not positive");
  CHECK(timeline_bin(&tl, 1.5 * tl.time_base) == 0, "no bin below two ticks");
  CHECK(timeline_bin(&tl, 2.0 * tl.time_base) == 1, "bin 1 at two ticks");
  const struct timeline small = timeline_make(0.0, 1.0, 1e-30);
  CHECK(small.bin_max == 1, "dt_max below the shortest bin: bin_max 1");
}

static void test_sync(void) {
  CHECK(timeline_step_of_bin(0) == 0 && timeline_step_of_bin(3) == 8, "steps of bins 0 and 3");
  CHECK(timeline_is_active(3, 0) && timeline_is_active(3, 24) && !timeline_is_active(3, 20),
        "bin 3 active at multiples of 8");
  CHECK(!timeline_is_active(0, 0), "bin 0 never active");
  CHECK(timeline_max_active_bin(24) == 3 && timeline_max_active_bin(1) == 0, "longest active bin");
  CHECK(timeline_max_active_bin(0) == TIMELINE_NR_BINS, "every bin active at the start");
  CHECK(timeline_next_sync(3, 20) == 24 && timeline_next_sync(3, 24) == 32, "next sync of bin 3");
  /* a particle of each bin 1..6 stepped from 0: at every multiple of the
   * step of bin 6 all of them end a step together, and in between bin b is
   * active exactly where the time is a multiple of 2^b */
  integertime_t t_end[7] = {0};
  for (int b = 1; b <= 6; b++) t_end[b] = timeline_step_of_bin(b);
  for (integertime_t ti = 1; ti <= 4 * 64; ti++) {
    int n = 0;
    for (int b = 1; b <= 6; b++) {
      const int ends = t_end[b] == ti;
      CHECK(ends == timeline_is_active(b, ti), "bin %d at %lld", b, (long long)ti);
      if (ends) {
        t_end[b] = timeline_next_sync(b, ti);
        n++;
      }
    }
    if (ti % 64 == 0) CHECK(n == 6, "all six bins meet at %lld", (long long)ti);
    CHECK(n == (timeline_max_active_bin(ti) < 6 ? timeline_max_active_bin(ti) : 6),
          "%d bins active at %lld", n, (long long)ti);
  }
  /* moving between bins */
  CHECK(timeline_bin_allowed(5, 2, 8) == 2, "shorter at once");
  CHECK(timeline_bin_allowed(2, 5, 4) == 2, "4 is no sync point of bin 3: stays in bin 2");
  CHECK(timeline_bin_allowed(2, 5, 8) == 3, "8 is one of bin 3: moves up to 3");
  CHECK(timeline_bin_allowed(2, 5, 64) == 5, "64 syncs bin 5: moves to 5");
}

static void test_fraction(void) {
  int64_t n[TIMELINE_NR_BINS + 1] = {0};
  CHECK(timeline_active_fraction(n) == 1.0, "no particle: 1");
  n[10] = 100;
  CHECK(timeline_active_fraction(n) == 1.0, "one bin: every particle every step");
  n[12] = 300; /* a quarter as often */
  CHECK(fabs(timeline_active_fraction(n) - (100 + 75) / 400.0) < 1e-15, "fraction %g",
        timeline_active_fraction(n));
}

int main(void) {
  test_round_trip();
  test_bins();
  test_sync();
  test_fraction();
  printf("test_timeline: %d checks, %d failed\n", checks, failures);
  return failures ? 1 : 0;
}
