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
 *  - the fraction of updates time bins would do;
 *  - a new line begun at a time where every particle ends its step
 *    (timeline_rebase) puts a bin's edge at the limit it is given, begins
 *    at that time, holds the rest of the run and the run's end, and states
 *    how old bins compare with its own (the limiter's shift). */
#include <math.h>
#include <stdio.h>
#include <string.h>

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

static void test_rebase(void) {
  /* the line of a 2e4 s run: a limit of 9.06 s steps by 20000 / 2^12 =
   * 4.88 s (the planetary impact after contact) */
  const struct timeline tl = timeline_make(0.0, 2e4, 1e30);
  CHECK(tl.ti_end == (integertime_t)1 << TIMELINE_NR_BINS, "time_end is the last tick");
  CHECK(timeline_dt_of_bin(&tl, timeline_bin(&tl, 9.06)) == 2e4 / 4096.0, "old step %g",
        timeline_dt_of_bin(&tl, timeline_bin(&tl, 9.06)));
  const integertime_t ti = (integertime_t)1 << 47; /* 20000 / 512 = 39.06 s */
  const double t0 = timeline_time(&tl, ti), a = 0.9 * 9.06;
  struct timeline_next n;
  memset(&n, 0, sizeof n);
  const double gain = timeline_rebase(&tl, ti, a, 2e4, 1e30, &n);
  CHECK(n.ti == 0 && n.tl.time_begin == t0, "the new line begins at %g (%g)", n.tl.time_begin, t0);
  /* the anchor's bin steps by the anchor less at most 1/TIMELINE_REBASE_STEPS */
  const int b = timeline_bin(&n.tl, a);
  const double step = timeline_dt_of_bin(&n.tl, b);
  CHECK(step <= a && step > a * (1.0 - 1.0 / TIMELINE_REBASE_STEPS), "anchor %g steps by %.17g", a,
        step);
  CHECK(timeline_dt_of_bin(&n.tl, timeline_bin(&n.tl, 9.06)) == step, "9.06 s steps by it too");
  CHECK(fabs(gain - step / (2e4 / 4096.0)) < 1e-12 && gain > 1.5, "gain %g", gain);
  /* time_end: a tick that every bin's steps reach, whose time is time_end */
  CHECK(n.tl.ti_end > 0 && n.tl.ti_end <= (integertime_t)1 << TIMELINE_NR_BINS, "end tick %lld",
        (long long)n.tl.ti_end);
  CHECK(n.tl.ti_end % timeline_step_of_bin(n.tl.bin_max) == 0, "every bin ends at time_end");
  CHECK(fabs(timeline_time(&n.tl, n.tl.ti_end) - 2e4) <= 2e4 * 1e-15, "end time %.17g",
        timeline_time(&n.tl, n.tl.ti_end));
  const double nmax = (2e4 - t0) / timeline_dt_of_bin(&n.tl, n.tl.bin_max);
  CHECK(nmax >= TIMELINE_REBASE_STEPS - 1e-9 && nmax < 2 * TIMELINE_REBASE_STEPS + 1e-9,
        "the rest holds %g longest steps", nmax);
  /* the shift: an old bin is at least as long as the new bin b - shift, and
   * shorter than b - shift + 1 */
  for (int ob = 5; ob < 50; ob += 7) {
    const double old = timeline_dt_of_bin(&tl, ob);
    CHECK(timeline_dt_of_bin(&n.tl, ob - n.shift) <= old &&
              timeline_dt_of_bin(&n.tl, ob - n.shift + 1) > old,
          "old bin %d (%g s) against new bin %d", ob, old, ob - n.shift);
  }
  /* dt_max caps the anchor and the longest bin */
  const double g2 = timeline_rebase(&tl, ti, 50.0, 2e4, 30.0, &n);
  CHECK(g2 > 0.0 && timeline_dt_of_bin(&n.tl, n.tl.bin_max) <= 30.0 &&
            timeline_dt_of_bin(&n.tl, n.tl.bin_max) > 30.0 * (1.0 - 1.0 / TIMELINE_REBASE_STEPS),
        "dt_max 30: longest %g", timeline_dt_of_bin(&n.tl, n.tl.bin_max));
  /* near the end: the longest bin is the anchor's, a whole number of
   * them to time_end */
  const integertime_t late = tl.ti_end - ((integertime_t)1 << 44); /* 4.88 s before the end */
  CHECK(timeline_rebase(&tl, late, 1.0, 2e4, 1e30, &n) > 0.0 && n.tl.ti_end % 5 == 0 &&
            n.tl.ti_end / 5 == timeline_step_of_bin(n.tl.bin_max),
        "4.88 s before the end: 5 steps of %g s", timeline_dt_of_bin(&n.tl, n.tl.bin_max));
  /* no new line at the end of the run, or for a limit too short for it */
  CHECK(timeline_rebase(&tl, tl.ti_end, 1.0, 2e4, 1e30, &n) == 0.0, "none at the end");
  CHECK(timeline_rebase(&tl, 0, 1e-14, 2e4, 1e30, &n) == 0.0, "none for 2e4 / 1e-14 > 2^54");
  CHECK(timeline_rebase(&tl, 0, 0.0, 2e4, 1e30, &n) == 0.0, "none for a zero limit");
  /* timeline_same keeps the line */
  const struct timeline_next sm = timeline_same(&tl, ti);
  CHECK(sm.ti == ti && sm.shift == 0 && sm.tl.time_base == tl.time_base, "the same line");
}

int main(void) {
  test_round_trip();
  test_bins();
  test_sync();
  test_fraction();
  test_rebase();
  printf("test_timeline: %d checks, %d failed\n", checks, failures);
  return failures ? 1 : 0;
}
