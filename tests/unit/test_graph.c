/* The task graph's pairs of task cells (engine_make_graph, which finds
 * them by descending the octrees) against the test of every pair of task
 * cells that it replaced: the same pairs, with the same periodic shifts,
 * in the same order.  Task cells inside one top-level cell: a < b with
 * boxes closer than the reach; task cells of neighbouring top-level
 * cells (space_top_pairs, periodic images included): every (a, b) closer
 * than the reach.  Sets: uniform random and clustered (two Gaussian blobs:
 * dense top-level cells with hundreds of task cells), open and periodic
 * boxes, several task-cell sizes and top-level grids.  Exit 0 pass, 1 fail. */
#ifdef HAVE_CONFIG_H
#include "config.h"
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/engine.h"
#include "src/engine_tasks.h"
#include "src/error.h"
#include "src/part.h"
#include "src/space.h"

static int failures = 0;

static double urand(void) {
  return rand() / (RAND_MAX + 1.0);
}

static double nrand(void) {
  const double u = urand() + 1e-300, v = urand();
  return sqrt(-2.0 * log(u)) * cos(2.0 * M_PI * v);
}

/** One case: n particles (clustered or not) in a box of side 1, the
 *  graph with task cells of at most task_size particles. */
static void run(const char *name, size_t n, int clustered, int periodic, int task_size,
                int max_top) {
  struct parts p;
  parts_alloc(&p, n);
  for (size_t i = 0; i < n; i++) {
    double x[3];
    for (int k = 0; k < 3; k++) {
      x[k] = clustered ? (i % 2 ? 0.3 : 0.7) + 0.05 * nrand() : urand();
      if (x[k] < 0.0) x[k] = periodic ? x[k] + 1.0 : 0.0;
      if (x[k] >= 1.0) x[k] = periodic ? x[k] - 1.0 : 0.999999;
    }
    p.x[i] = x[0], p.y[i] = x[1], p.z[i] = x[2];
    p.h[i] = 0.6 * pow(1.0 / (double)n, 1.0 / 3.0) * (clustered ? 0.3 : 1.0);
    p.m[i] = 1.0;
    p.id[i] = (long long)i;
  }
  static struct engine e;
  memset(&e, 0, sizeof e);
  const double box[3] = {1.0, 1.0, 1.0};
  space_init(&e.space, &p, box, periodic, 16, max_top);
  space_rebuild(&e.space);
  scheduler_init(&e.sched, 1);
  e.hp.enabled = 1;
  e.cell_task_size = task_size;
  e.nr_threads = 1;
  engine_make_graph(&e);

  /* the pairs every-pair testing finds, in its order */
  const struct space *s = &e.space;
  const double reach2 = e.reach * e.reach;
  const int nt = e.nr_tcells;
  int *top_of = malloc((nt ? nt : 1) * sizeof(int));
  for (int t = 0; t < nt; t++) top_of[t] = e.tcells[t]->top;
  int *first = calloc((size_t)s->nr_top + 1, sizeof(int));
  for (int t = 0; t < nt; t++) first[top_of[t] + 1]++;
  for (int c = 0; c < s->nr_top; c++) first[c + 1] += first[c];
  size_t n_exp = 0, bad = 0;
  const double zero[3] = {0, 0, 0};
#define EXPECT(a_, b_, sh_)                                                           \
  do {                                                                                \
    const struct space_pair *q = n_exp < (size_t)e.nr_pairs ? &e.pairs[n_exp] : NULL; \
    if (!q || q->ci != (a_) || q->cj != (b_) || q->shift[0] != (sh_)[0] ||            \
        q->shift[1] != (sh_)[1] || q->shift[2] != (sh_)[2])                           \
      bad++;                                                                          \
    n_exp++;                                                                          \
  } while (0)
  for (int c = 0; c < s->nr_top; c++)
    for (int a = first[c]; a < first[c + 1]; a++)
      for (int b = a + 1; b < first[c + 1]; b++)
        if (cell_bbox_dist2(e.tcells[a], e.tcells[b], zero) < reach2) EXPECT(a, b, zero);
  struct space_pair *top = NULL;
  const size_t ntop = space_top_pairs(s, &top);
  for (size_t k = 0; k < ntop; k++)
    for (int a = first[top[k].ci]; a < first[top[k].ci + 1]; a++)
      for (int b = first[top[k].cj]; b < first[top[k].cj + 1]; b++)
        if (cell_bbox_dist2(e.tcells[a], e.tcells[b], top[k].shift) < reach2)
          EXPECT(a, b, top[k].shift);
#undef EXPECT
  int most = 0;
  for (int c = 0; c < s->nr_top; c++)
    if (first[c + 1] - first[c] > most) most = first[c + 1] - first[c];
  const int ok = bad == 0 && n_exp == (size_t)e.nr_pairs && n_exp > 0;
  printf(
      "  %-34s %6d task cells (up to %4d in a top-level cell), %7d pairs, all-pairs test %7zu: "
      "%s\n",
      name, nt, most, e.nr_pairs, n_exp, ok ? "same, same order" : "FAIL");
  failures += !ok;
  free(top), free(first), free(top_of);
  engine_graph_clean(&e);
  free(e.tcells);
  free(e.cell_dt_min);
  free(e.cell_bins);
  free(e.cell_kick);
  free(e.tcell_top);
  scheduler_free(&e.sched);
  space_free(&e.space);
  parts_free(&p);
}

int main(int argc, char **argv) {
  error_init(argc > 0 ? argv[0] : "test_graph");
  srand(7);
  printf("task graph pairs (octree descent) against every pair of task cells:\n");
  run("uniform, open, task cells of 64", 60000, 0, 0, 64, 8);
  run("uniform, periodic, task cells of 64", 60000, 0, 1, 64, 8);
  run("clustered, open, task cells of 32", 80000, 1, 0, 32, 4);
  run("clustered, periodic, task cells of 100", 80000, 1, 1, 100, 6);
  run("uniform, periodic, 2 top cells a side", 20000, 0, 1, 50, 2);
  printf(failures ? "FAIL\n" : "PASS\n");
  return failures ? 1 : 0;
}
