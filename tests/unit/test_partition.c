/* The domain decomposition (src/mpi/partition.h, issue 22) on a space like
 * the planetary impact's: 20,000 particles in a ball of radius 0.1 in a box
 * of side 1 (nearly all the box empty), a 16^3 top-level grid.
 *  - every method assigns every top-level cell to a rank in [0, N);
 *  - the costs add up: the ranks' costs sum to the graph's, the ranks'
 *    particles to the space's;
 *  - slabs of equal width put the whole ball on one or two ranks
 *    (imbalance near N / 2 or worse), Morton ranges of equal cost and
 *    METIS balance it within the granularity of the cells;
 *  - METIS cuts less communication than the Morton ranges (its purpose) and
 *    keeps each rank's non-empty cells in few pieces;
 *  - one rank: imbalance 1, no cut, no halo;
 *  - the graph from the task-less estimate and from the space's pairs is
 *    symmetric (each edge both ways, with the same weight). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "src/mpi/partition.h"
#include "src/part.h"
#include "src/space.h"

#include "tests/helpers/check.h"

static double urand(void) {
  return (rand() + 0.5) / ((double)RAND_MAX + 1.0);
}

static void check_partition(const struct partition *p, const struct partition_graph *g, size_t n) {
  CHECK(p->unassigned == 0, "%s: %d cells unassigned", partition_method_name(p->method),
        p->unassigned);
  double cost = 0.0;
  size_t parts = 0;
  int cells = 0;
  for (int r = 0; r < p->nr_ranks; r++) {
    cost += p->rank_cost[r];
    parts += p->rank_parts[r];
    cells += p->rank_cells[r];
  }
  CHECK(fabs(cost - g->total_cost) <= 1e-9 * g->total_cost, "%s: ranks' cost %g, graph's %g",
        partition_method_name(p->method), cost, g->total_cost);
  CHECK(parts == n, "%s: ranks hold %zu particles of %zu", partition_method_name(p->method), parts,
        n);
  CHECK(cells == g->nr_cells, "%s: ranks hold %d cells of %d", partition_method_name(p->method),
        cells, g->nr_cells);
}

int main(void) {
  const size_t n = 20000;
  struct parts p;
  parts_alloc(&p, n);
  srand(7);
  for (size_t i = 0; i < n; i++) {
    double x[3], r2;
    do {
      for (int k = 0; k < 3; k++) x[k] = 2.0 * urand() - 1.0;
      r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    } while (r2 > 1.0);
    p.x[i] = 0.45 + 0.1 * x[0];
    p.y[i] = 0.52 + 0.1 * x[1];
    p.z[i] = 0.47 + 0.1 * x[2];
    p.m[i] = 1.0;
    p.h[i] = 0.004;
    p.id[i] = (int64_t)i;
  }
  const double L[3] = {1.0, 1.0, 1.0};
  struct space s;
  space_init(&s, &p, L, 0, 100, 16);
  space_rebuild(&s);
  struct partition_graph g;
  partition_graph_make(&g, &s, NULL, 0);
  printf("grid %d x %d x %d, %d top-level cells, %d links\n", g.cdim[0], g.cdim[1], g.cdim[2],
         g.nr_cells, g.nr_links);
  CHECK(g.nr_cells == s.nr_top && g.nr_cells == 16 * 16 * 16, "top-level cells %d", g.nr_cells);
  /* symmetric edges */
  for (int c = 0; c < g.nr_cells; c++)
    for (int e = g.xadj[c]; e < g.xadj[c + 1]; e++) {
      const int d = g.adj[e];
      int back = -1;
      for (int f = g.xadj[d]; f < g.xadj[d + 1]; f++)
        if (g.adj[f] == c) back = f;
      CHECK(back >= 0 && g.comm[back] == g.comm[e], "edge %d-%d not symmetric", c, d);
    }

  for (int nr = 1; nr <= 8; nr *= 2) {
    struct partition pm[3];
    for (int m = 0; m < 3; m++) {
      if (m == partition_method_metis && !partition_have_metis()) continue;
      partition_make(&pm[m], &g, nr, (enum partition_method)m);
      partition_print(&pm[m], &g, 0, stdout);
      check_partition(&pm[m], &g, n);
      if (nr == 1)
        CHECK(pm[m].imbalance == 1.0 && pm[m].edge_cut == 0.0 && pm[m].rank_halo[0] == 0.0,
              "one rank: imbalance %g, cut %g", pm[m].imbalance, pm[m].edge_cut);
    }
    if (nr > 1) {
      /* the ball spans 4 of the 16 slabs: the naive split is far off */
      CHECK(pm[partition_method_slabs].imbalance > 0.3 * nr, "slabs at %d ranks: imbalance %g", nr,
            pm[partition_method_slabs].imbalance);
      CHECK(pm[partition_method_morton].imbalance < 1.3, "morton at %d ranks: imbalance %g", nr,
            pm[partition_method_morton].imbalance);
      if (partition_have_metis()) {
        const struct partition *q = &pm[partition_method_metis];
        CHECK(q->imbalance < 1.3, "metis at %d ranks: imbalance %g", nr, q->imbalance);
        /* METIS balances as well as the Morton ranges (within 1%, its
         * tolerance) and cuts about as little or less */
        CHECK(q->imbalance <= pm[partition_method_morton].imbalance + 0.01,
              "metis at %d ranks: imbalance %g, morton %g", nr, q->imbalance,
              pm[partition_method_morton].imbalance);
        CHECK(q->edge_cut <= 1.1 * pm[partition_method_morton].edge_cut,
              "metis at %d ranks cuts %g, morton %g", nr, q->edge_cut,
              pm[partition_method_morton].edge_cut);
        CHECK(q->max_pieces <= 2, "metis at %d ranks: a rank in %d pieces", nr, q->max_pieces);
        /* the halo: the particles of the foreign top-level cells beside a
         * rank's (whole cells here: no task below them), at most all */
        for (int r = 0; r < nr; r++)
          CHECK(q->rank_halo[r] > 0.0 && q->rank_halo[r] < (double)n,
                "metis at %d ranks: rank %d halo %g", nr, r, q->rank_halo[r]);
      }
    }
    for (int m = 0; m < 3; m++)
      if (m != partition_method_metis || partition_have_metis()) partition_free(&pm[m]);
  }
  partition_graph_free(&g);
  space_free(&s);
  parts_free(&p);
  printf("test_partition: %d checks, %d failed\n", checks, failures);
  return failures ? 1 : 0;
}
