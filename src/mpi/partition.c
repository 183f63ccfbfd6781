/* Domain decomposition of the top-level cells (src/mpi/partition.h,
 * theory/mpi.md). */
#include "src/mpi/partition.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "config.h"
#include "src/cell.h"
#include "src/error.h"
#include "src/scheduler.h"
#include "src/space.h"
#include "src/part.h"
#include "src/task.h"
#include "tasks/hydro/kernel.h"

#ifdef HAVE_METIS
#include <metis.h>
#endif

/* ------------------------------------------------------------------ graph */

/** The edges of one vertex while the graph is made. */
struct partition_elist {
  int n, cap;
  int *nb;
  double *w;
};

static void partition_edge_add1(struct partition_elist *l, int nb, double w) {
  for (int k = 0; k < l->n; k++)
    if (l->nb[k] == nb) {
      l->w[k] += w;
      return;
    }
  if (l->n == l->cap) {
    l->cap = l->cap ? 2 * l->cap : 8;
    l->nb = error_realloc(l->nb, (size_t)l->cap * sizeof(int), "partition edges");
    l->w = error_realloc(l->w, (size_t)l->cap * sizeof(double), "partition edges");
  }
  l->nb[l->n] = nb;
  l->w[l->n] = w;
  l->n++;
}

static void partition_edge_add(struct partition_elist *l, int a, int b, double w) {
  if (a == b) return;
  partition_edge_add1(&l[a], b, w);
  partition_edge_add1(&l[b], a, w);
}

/** Remember a pair of cells ca, cb (space.cells indices) on two top-level
 *  cells ta, tb: the halo counts the foreign cells a rank reads. */
static void partition_link_add(struct partition_graph *g, int ta, int tb, int ca, int cb,
                               int *cap) {
  if (g->nr_links == *cap) {
    *cap = *cap ? 2 * *cap : 1024;
    g->link_cell = error_realloc(g->link_cell, (size_t)*cap * 2 * sizeof(int), "partition links");
    g->link_top = error_realloc(g->link_top, (size_t)*cap * 2 * sizeof(int), "partition links");
  }
  g->link_top[2 * g->nr_links] = ta;
  g->link_top[2 * g->nr_links + 1] = tb;
  g->link_cell[2 * g->nr_links] = ca;
  g->link_cell[2 * g->nr_links + 1] = cb;
  g->nr_links++;
}

/** Particles of a that lie within r of the bounding box of b (b seen at
 *  shift from a): the ones a pair loop takes beyond its pruning. */
static double partition_near(const struct space *s, const struct cell *a, const struct cell *b,
                             const double shift[3], double r) {
  const struct parts *p = s->parts;
  size_t n = 0;
  for (size_t i = a->offset; i < a->offset + a->count; i++) {
    const double x[3] = {p->x[i], p->y[i], p->z[i]};
    n += cell_point_dist2(b, x, shift) <= r * r;
  }
  return (double)n;
}

/** The pair tests of a pair loop over ci and cj (cj seen at x + shift):
 *  every particle of both cells against the other's box, then the pairs of
 *  those within reach. */
static double partition_pair_estimate(const struct space *s, const struct cell *ci,
                                      const struct cell *cj, const double shift[3]) {
  const double back[3] = {-shift[0], -shift[1], -shift[2]};
  const double r = kernel_gamma * (ci->h_max > cj->h_max ? ci->h_max : cj->h_max);
  return (double)ci->count + (double)cj->count +
         partition_near(s, ci, cj, shift, r) * partition_near(s, cj, ci, back, r);
}

/** The estimated work of a task, in the pair tests of a self loop. */
static double partition_task_estimate(const struct space *s, const struct task *t,
                                      const struct cell *ci, const struct cell *cj) {
  const double ni = (double)ci->count;
  if (t->type == task_type_implicit) return 0.0;
  if (t->type == task_type_self) return 0.5 * ni * (ni - 1.0);
  /* gravity's near field: every pair of the two cells, directly */
  if (t->type == task_type_pair && cj && t->subtype == task_subtype_grav)
    return ni * (double)cj->count;
  if (t->type == task_type_pair && cj) {
    /* cj at the periodic image nearest ci */
    double shift[3] = {0.0, 0.0, 0.0};
    if (s->periodic)
      for (int k = 0; k < 3; k++) {
        const double d = cj->loc[k] - ci->loc[k];
        if (d > 0.5 * s->dim[k]) shift[k] = -s->dim[k];
        if (d < -0.5 * s->dim[k]) shift[k] = s->dim[k];
      }
    return partition_pair_estimate(s, ci, cj, shift);
  }
  return PARTITION_PER_PARTICLE * ni;
}

void partition_graph_make(struct partition_graph *g, const struct space *s,
                          const struct scheduler *sched, int measured) {
  memset(g, 0, sizeof *g);
  const int n = s->nr_top;
  g->nr_cells = n;
  for (int k = 0; k < 3; k++) g->cdim[k] = s->cdim[k];
  g->measured = sched && measured;
  g->cost = error_calloc((size_t)n, sizeof(double), "partition costs");
  g->count = error_calloc((size_t)n, sizeof(size_t), "partition counts");
  g->cell_count = error_calloc((size_t)s->nr_cells, sizeof(size_t), "partition counts");
  g->nr_space_cells = s->nr_cells;
  for (int c = 0; c < s->nr_cells; c++) g->cell_count[c] = s->cells[c].count;
  for (int c = 0; c < n; c++) g->count[c] = s->cells[c].count;
  struct partition_elist *el = error_calloc((size_t)n, sizeof *el, "partition edges");
  int link_cap = 0;

  if (sched) {
    for (int i = 0; i < sched->nr_tasks; i++) {
      const struct task *t = scheduler_task(sched, i);
      const struct cell *ci = t->ci, *cj = t->cj;
      if (!ci) continue;
      if (cj == ci) cj = NULL;
      const double w = g->measured ? (double)t->cost : partition_task_estimate(s, t, ci, cj);
      if (cj && cj->top != ci->top) {
        g->cost[ci->top] += 0.5 * w;
        g->cost[cj->top] += 0.5 * w;
        partition_edge_add(el, ci->top, cj->top, (double)(ci->count + cj->count));
        partition_link_add(g, ci->top, cj->top, ci->index, cj->index, &link_cap);
      } else {
        g->cost[ci->top] += w;
      }
    }
  } else {
    /* Before any task graph, the top-level cells alone: every particle
     * costs the same, as h adapts so that each has about the same number of
     * neighbours wherever it is and the loops recurse to leaves of about
     * the same size.  (The pair tests of a whole top-level cell, n(n-1)/2,
     * weighed a dense cell by its density once more: on the reference
     * impact at 1.1e5 particles and 16^3 cells two ranks measured an
     * imbalance of 1.18 where that estimate said 1.06; by particles 1.06.) */
    struct space_pair *pairs = NULL;
    const size_t np = space_top_pairs(s, &pairs);
    for (int c = 0; c < n; c++) g->cost[c] = (double)s->cells[c].count;
    for (size_t k = 0; k < np; k++) {
      const struct cell *ci = &s->cells[pairs[k].ci], *cj = &s->cells[pairs[k].cj];
      if (ci == cj) continue;
      partition_edge_add(el, pairs[k].ci, pairs[k].cj, (double)(ci->count + cj->count));
      partition_link_add(g, pairs[k].ci, pairs[k].cj, pairs[k].ci, pairs[k].cj, &link_cap);
    }
    free(pairs);
  }

  /* the grid's face neighbours: a connected graph, empty cells beside a rank */
  for (int i = 0; i < s->cdim[0]; i++)
    for (int j = 0; j < s->cdim[1]; j++)
      for (int k = 0; k < s->cdim[2]; k++) {
        const int c = space_top_index(s, i, j, k);
        const int ijk[3] = {i, j, k};
        for (int d = 0; d < 3; d++) {
          int q[3] = {ijk[0], ijk[1], ijk[2]};
          q[d]++;
          if (q[d] == s->cdim[d]) {
            if (!s->periodic) continue;
            q[d] = 0;
          }
          partition_edge_add(el, c, space_top_index(s, q[0], q[1], q[2]), 0.0);
        }
      }

  g->xadj = error_malloc((size_t)(n + 1) * sizeof(int), "partition graph");
  g->xadj[0] = 0;
  for (int c = 0; c < n; c++) g->xadj[c + 1] = g->xadj[c] + el[c].n;
  const int ne = g->xadj[n];
  g->adj = error_malloc((size_t)(ne ? ne : 1) * sizeof(int), "partition graph");
  g->comm = error_malloc((size_t)(ne ? ne : 1) * sizeof(double), "partition graph");
  for (int c = 0; c < n; c++) {
    memcpy(g->adj + g->xadj[c], el[c].nb, (size_t)el[c].n * sizeof(int));
    memcpy(g->comm + g->xadj[c], el[c].w, (size_t)el[c].n * sizeof(double));
    free(el[c].nb);
    free(el[c].w);
  }
  free(el);
  g->total_cost = 0.0;
  for (int c = 0; c < n; c++) g->total_cost += g->cost[c];
  g->total_comm = 0.0;
  for (int e = 0; e < ne; e++) g->total_comm += 0.5 * g->comm[e];
}

void partition_graph_free(struct partition_graph *g) {
  free(g->cost);
  free(g->count);
  free(g->cell_count);
  free(g->xadj);
  free(g->adj);
  free(g->comm);
  free(g->link_cell);
  free(g->link_top);
  free(g->ijk);
  memset(g, 0, sizeof *g);
}

/* ------------------------------------------------------------------ methods */

int partition_have_metis(void) {
#ifdef HAVE_METIS
  return 1;
#else
  return 0;
#endif
}

const char *partition_method_name(enum partition_method m) {
  switch (m) {
    case partition_method_metis:
      return "metis";
    case partition_method_morton:
      return "morton";
    case partition_method_slabs:
      return "slabs";
  }
  return "?";
}

int partition_method_parse(const char *name) {
  for (int m = 0; m <= (int)partition_method_slabs; m++)
    if (strcmp(name, partition_method_name((enum partition_method)m)) == 0) return m;
  return -1;
}

/** Interleave the bits of (i, j, k): the Morton key of a top-level cell. */
static uint64_t partition_morton(int i, int j, int k) {
  uint64_t key = 0;
  for (int b = 0; b < 21; b++) {
    key |= (uint64_t)((i >> b) & 1) << (3 * b + 2);
    key |= (uint64_t)((j >> b) & 1) << (3 * b + 1);
    key |= (uint64_t)((k >> b) & 1) << (3 * b);
  }
  return key;
}

struct partition_key {
  uint64_t key;
  int cell;
};

static int partition_key_cmp(const void *a, const void *b) {
  const struct partition_key *x = a, *y = b;
  return x->key < y->key ? -1 : x->key > y->key;
}

/** Contiguous ranges of the Morton order, each about total / N of the work. */
static void partition_split_morton(struct partition *p, const struct partition_graph *g) {
  const int n = g->nr_cells;
  struct partition_key *keys = error_malloc((size_t)(n ? n : 1) * sizeof *keys, "partition keys");
  if (g->ijk)
    for (int c = 0; c < n; c++)
      keys[c] = (struct partition_key){
          partition_morton(g->ijk[3 * c], g->ijk[3 * c + 1], g->ijk[3 * c + 2]), c};
  else
    for (int i = 0; i < g->cdim[0]; i++)
      for (int j = 0; j < g->cdim[1]; j++)
        for (int k = 0; k < g->cdim[2]; k++) {
          const int c = (i * g->cdim[1] + j) * g->cdim[2] + k;
          keys[c] = (struct partition_key){partition_morton(i, j, k), c};
        }
  qsort(keys, (size_t)n, sizeof *keys, partition_key_cmp);
  const double total = g->total_cost > 0.0 ? g->total_cost : 1.0;
  double before = 0.0;
  for (int q = 0; q < n; q++) {
    const int c = keys[q].cell;
    int r = (int)((before + 0.5 * g->cost[c]) / total * p->nr_ranks);
    if (r >= p->nr_ranks) r = p->nr_ranks - 1;
    p->rank[c] = r;
    before += g->cost[c];
  }
  free(keys);
}

/** Slabs of equal width along x: the naive split. */
static void partition_split_slabs(struct partition *p, const struct partition_graph *g) {
  if (g->ijk) {
    for (int c = 0; c < g->nr_cells; c++)
      p->rank[c] = (int)((long)g->ijk[3 * c] * p->nr_ranks / g->cdim[0]);
    return;
  }
  for (int i = 0; i < g->cdim[0]; i++)
    for (int j = 0; j < g->cdim[1]; j++)
      for (int k = 0; k < g->cdim[2]; k++)
        p->rank[(i * g->cdim[1] + j) * g->cdim[2] + k] = (int)((long)i * p->nr_ranks / g->cdim[0]);
}

#ifdef HAVE_METIS
/** Give every cell without particles the rank of the nearest cell with one
 *  (breadth first over the graph's edges, the grid's face neighbours among
 *  them, so that every cell is reached); rank[c] < 0 marks the ones to fill.
 *  No cell with particles: all on rank 0. */
static void partition_fill_empty(int *rank, const struct partition_graph *g) {
  const int n = g->nr_cells;
  int *queue = error_malloc((size_t)(n ? n : 1) * sizeof(int), "partition fill");
  int head = 0, tail = 0;
  for (int c = 0; c < n; c++)
    if (rank[c] >= 0) queue[tail++] = c;
  if (tail == 0)
    for (int c = 0; c < n; c++) rank[c] = 0;
  while (head < tail) {
    const int v = queue[head++];
    for (int e = g->xadj[v]; e < g->xadj[v + 1]; e++)
      if (rank[g->adj[e]] < 0) {
        rank[g->adj[e]] = rank[v];
        queue[tail++] = g->adj[e];
      }
  }
  for (int c = 0; c < n; c++)
    if (rank[c] < 0) rank[c] = 0; /* unreachable: the grid is connected */
  free(queue);
}

/** METIS on the graph of the cells with particles (the empty ones, most of
 *  an impact's box, then take a neighbour's rank): vertex weights the costs,
 *  edge weights the communication (at least 1: the grid edges), both scaled
 *  to integers that cannot overflow METIS's sums.  k-way first; on a coarse
 *  graph (a few heavy cells) it can miss the balance by far, where recursive
 *  bisection does better: the better balanced of the two is kept (the
 *  smaller cut when within 1%). */
static void partition_split_metis(struct partition *p, const struct partition_graph *g) {
  const int n = g->nr_cells;
  int *local = error_malloc((size_t)(n ? n : 1) * sizeof(int), "METIS graph");
  int nv_ = 0, ne = 0;
  for (int c = 0; c < n; c++) local[c] = g->count[c] > 0 ? nv_++ : -1;
  for (int c = 0; c < n; c++)
    if (local[c] >= 0)
      for (int e = g->xadj[c]; e < g->xadj[c + 1]; e++) ne += local[g->adj[e]] >= 0;
  for (int c = 0; c < n; c++) p->rank[c] = -1;
  if (nv_ == 0) {
    partition_fill_empty(p->rank, g);
    free(local);
    return;
  }
  idx_t nv = nv_, ncon = 1, nparts = p->nr_ranks, objval = 0;
  idx_t *xadj = error_malloc((size_t)(nv_ + 1) * sizeof(idx_t), "METIS graph");
  idx_t *adj = error_malloc((size_t)(ne ? ne : 1) * sizeof(idx_t), "METIS graph");
  idx_t *vwgt = error_malloc((size_t)nv_ * sizeof(idx_t), "METIS graph");
  idx_t *adjwgt = error_malloc((size_t)(ne ? ne : 1) * sizeof(idx_t), "METIS graph");
  idx_t *part = error_malloc((size_t)nv_ * sizeof(idx_t), "METIS graph");
  idx_t *alt = error_malloc((size_t)nv_ * sizeof(idx_t), "METIS graph");
  double *vcost = error_malloc((size_t)nv_ * sizeof(double), "METIS graph");
  /* weights: sums up to about 1e8, far from idx_t's limit */
  const double vscale = g->total_cost > 0.0 ? 1e8 / g->total_cost : 1.0;
  double cmax = 0.0;
  for (int e = 0; e < g->xadj[n]; e++)
    if (g->comm[e] > cmax) cmax = g->comm[e];
  const double cscale = cmax > 0.0 ? 1e5 / cmax : 1.0;
  int k = 0;
  xadj[0] = 0;
  for (int c = 0; c < n; c++) {
    if (local[c] < 0) continue;
    const int v = local[c];
    vcost[v] = g->cost[c];
    vwgt[v] = (idx_t)llround(g->cost[c] * vscale);
    for (int e = g->xadj[c]; e < g->xadj[c + 1]; e++)
      if (local[g->adj[e]] >= 0) {
        adj[k] = local[g->adj[e]];
        adjwgt[k] = 1 + (idx_t)llround(g->comm[e] * cscale);
        k++;
      }
    xadj[v + 1] = k;
  }
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_SEED] = 1;     /* the same partition every run */
  options[METIS_OPTION_UFACTOR] = 10; /* 1.01: the cells are coarse enough as it is */
  options[METIS_OPTION_NCUTS] = 4;    /* the best of four tries */
  double *load = error_malloc((size_t)p->nr_ranks * sizeof(double), "METIS graph");
  double best_max = 0.0, best_cut = 0.0;
  for (int method = 0; method < 2; method++) {
    idx_t *out = method == 0 ? part : alt;
    const int rc = method == 0
                       ? METIS_PartGraphKway(&nv, &ncon, xadj, adj, vwgt, NULL, adjwgt, &nparts,
                                             NULL, NULL, options, &objval, out)
                       : METIS_PartGraphRecursive(&nv, &ncon, xadj, adj, vwgt, NULL, adjwgt,
                                                  &nparts, NULL, NULL, options, &objval, out);
    if (rc != METIS_OK)
      error_exit("METIS_PartGraph%s failed (code %d) on %d top-level cells over %d ranks",
                 method == 0 ? "Kway" : "Recursive", rc, nv_, p->nr_ranks);
    for (int r = 0; r < p->nr_ranks; r++) load[r] = 0.0;
    for (int v = 0; v < nv_; v++) load[out[v]] += vcost[v];
    double mx = 0.0;
    for (int r = 0; r < p->nr_ranks; r++)
      if (load[r] > mx) mx = load[r];
    const double cut = (double)objval;
    if (method == 0) {
      best_max = mx;
      best_cut = cut;
    } else if (mx < best_max * 0.99 || (mx <= best_max * 1.01 && cut < best_cut)) {
      memcpy(part, alt, (size_t)nv_ * sizeof(idx_t));
      best_max = mx;
      best_cut = cut;
    }
  }
  for (int c = 0; c < n; c++)
    if (local[c] >= 0) p->rank[c] = (int)part[local[c]];
  partition_fill_empty(p->rank, g);
  free(load);
  free(alt);
  free(vcost);
  free(local);
  free(xadj);
  free(adj);
  free(vwgt);
  free(adjwgt);
  free(part);
}
#endif

void partition_make(struct partition *p, const struct partition_graph *g, int nr_ranks,
                    enum partition_method method) {
  memset(p, 0, sizeof *p);
  if (nr_ranks < 1) error_exit("a partition needs at least one rank, not %d", nr_ranks);
  p->nr_ranks = nr_ranks;
  p->method = method;
  p->rank = error_calloc((size_t)(g->nr_cells ? g->nr_cells : 1), sizeof(int), "partition");
  if (nr_ranks > 1) switch (method) {
      case partition_method_metis:
#ifdef HAVE_METIS
        partition_split_metis(p, g);
        {
          /* on a graph of few heavy cells METIS can miss the balance by far
           * (14 non-empty cells over 8 ranks: 1.78, where Morton ranges give
           * 1.25): take the Morton ranges when they balance 5% better */
          struct partition m;
          memset(&m, 0, sizeof m);
          m.nr_ranks = nr_ranks;
          m.method = partition_method_morton;
          m.rank = error_malloc((size_t)(g->nr_cells ? g->nr_cells : 1) * sizeof(int), "partition");
          partition_split_morton(&m, g);
          partition_stats(&m, g);
          partition_stats(p, g);
          if (m.imbalance < 0.95 * p->imbalance) {
            memcpy(p->rank, m.rank, (size_t)g->nr_cells * sizeof(int));
            p->fallback = 1;
          }
          partition_free(&m);
        }
#else
        error_exit(
            "this build has no METIS (configure found no libmetis-dev): partition with "
            "'morton' or 'slabs', or rebuild with METIS");
#endif
        break;
      case partition_method_morton:
        partition_split_morton(p, g);
        break;
      case partition_method_slabs:
        partition_split_slabs(p, g);
        break;
    }
  partition_stats(p, g);
}

/* ------------------------------------------------------------------ stats */

void partition_stats(struct partition *p, const struct partition_graph *g) {
  const int n = g->nr_cells, nr = p->nr_ranks;
  free(p->rank_cost);
  free(p->rank_parts);
  free(p->rank_cells);
  free(p->rank_halo);
  free(p->rank_pieces);
  p->rank_cost = error_calloc((size_t)nr, sizeof(double), "partition");
  p->rank_parts = error_calloc((size_t)nr, sizeof(size_t), "partition");
  p->rank_cells = error_calloc((size_t)nr, sizeof(int), "partition");
  p->rank_halo = error_calloc((size_t)nr, sizeof(double), "partition");
  p->rank_pieces = error_calloc((size_t)nr, sizeof(int), "partition");
  p->unassigned = 0;
  for (int c = 0; c < n; c++) {
    const int r = p->rank[c];
    if (r < 0 || r >= nr) {
      p->unassigned++;
      continue;
    }
    p->rank_cost[r] += g->cost[c];
    p->rank_parts[r] += g->count[c];
    p->rank_cells[r]++;
  }
  double cmax = 0.0;
  for (int r = 0; r < nr; r++)
    if (p->rank_cost[r] > cmax) cmax = p->rank_cost[r];
  const double mean = g->total_cost / nr;
  p->imbalance = mean > 0.0 ? cmax / mean : 1.0;

  /* the edge cut: communication between cells of two ranks */
  p->edge_cut = 0.0;
  for (int c = 0; c < n; c++)
    for (int e = g->xadj[c]; e < g->xadj[c + 1]; e++)
      if (p->rank[c] != p->rank[g->adj[e]]) p->edge_cut += 0.5 * g->comm[e];

  /* the halo: particles of the foreign cells the rank's pair tasks read,
   * each cell once per rank */
  if (g->nr_links > 0 && nr > 1) {
    int *seen = error_malloc((size_t)g->nr_space_cells * sizeof(int), "partition halo");
    for (int c = 0; c < g->nr_space_cells; c++) seen[c] = -1;
    for (int r = 0; r < nr; r++) {
      double halo = 0.0;
      for (int l = 0; l < g->nr_links; l++) {
        const int a = g->link_top[2 * l], b = g->link_top[2 * l + 1];
        if (p->rank[a] == p->rank[b]) continue;
        int need = -1;
        if (p->rank[a] == r) need = g->link_cell[2 * l + 1];
        if (p->rank[b] == r) need = g->link_cell[2 * l];
        if (need < 0 || seen[need] == r) continue;
        seen[need] = r;
        halo += (double)g->cell_count[need];
      }
      p->rank_halo[r] = halo;
    }
    free(seen);
  }

  /* connected pieces of each rank's non-empty cells (breadth first) */
  int *mark = error_malloc((size_t)(n ? n : 1) * sizeof(int), "partition pieces");
  int *queue = error_malloc((size_t)(n ? n : 1) * sizeof(int), "partition pieces");
  for (int c = 0; c < n; c++) mark[c] = 0;
  p->max_pieces = 0;
  for (int c = 0; c < n; c++) {
    const int r = p->rank[c];
    if (mark[c] || g->count[c] == 0 || r < 0 || r >= nr) continue;
    p->rank_pieces[r]++;
    int head = 0, tail = 0;
    queue[tail++] = c;
    mark[c] = 1;
    while (head < tail) {
      const int v = queue[head++];
      for (int e = g->xadj[v]; e < g->xadj[v + 1]; e++) {
        const int w = g->adj[e];
        if (!mark[w] && g->count[w] > 0 && p->rank[w] == r) {
          mark[w] = 1;
          queue[tail++] = w;
        }
      }
    }
  }
  for (int r = 0; r < nr; r++)
    if (p->rank_pieces[r] > p->max_pieces) p->max_pieces = p->rank_pieces[r];
  free(mark);
  free(queue);
}

void partition_free(struct partition *p) {
  free(p->rank);
  free(p->rank_cost);
  free(p->rank_parts);
  free(p->rank_cells);
  free(p->rank_halo);
  free(p->rank_pieces);
  memset(p, 0, sizeof *p);
}

void partition_print(const struct partition *p, const struct partition_graph *g, int per_rank,
                     FILE *f) {
  double hmax = 0.0, hsum = 0.0;
  for (int r = 0; r < p->nr_ranks; r++) {
    hsum += p->rank_halo[r];
    if (p->rank_halo[r] > hmax) hmax = p->rank_halo[r];
  }
  fprintf(f,
          "partition: method %s ranks %d cells %d grid %dx%dx%d costs %s imbalance %.4f "
          "edge_cut %.0f cut_fraction %.4f halo_mean %.0f halo_max %.0f max_pieces %d "
          "unassigned %d%s\n",
          partition_method_name(p->method), p->nr_ranks, g->nr_cells, g->cdim[0], g->cdim[1],
          g->cdim[2], g->measured ? "measured" : "estimated", p->imbalance, p->edge_cut,
          g->total_comm > 0.0 ? p->edge_cut / g->total_comm : 0.0, hsum / p->nr_ranks, hmax,
          p->max_pieces, p->unassigned, p->fallback ? " fallback morton" : "");
  if (!per_rank) return;
  const double mean = g->total_cost / p->nr_ranks;
  fprintf(f, "#  rank  cells  particles    cost/mean       halo  pieces\n");
  for (int r = 0; r < p->nr_ranks; r++)
    fprintf(f, "  %5d %6d %10zu %12.4f %10.0f %7d\n", r, p->rank_cells[r], p->rank_parts[r],
            mean > 0.0 ? p->rank_cost[r] / mean : 0.0, p->rank_halo[r], p->rank_pieces[r]);
}
