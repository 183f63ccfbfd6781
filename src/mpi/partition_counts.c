/* The domain decomposition from per-cell particle counts, without the
 * particles (src/mpi/partition.h, theory/mpi.md "Scaling on paper"): a
 * graph of the non-empty top-level cells only, for grids and particle
 * numbers that do not fit in one process. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "src/mpi/partition.h"

/** The direction bit of offset (oi, oj, ok), each in -1..1. */
static int counts_dir(int oi, int oj, int ok) {
  return 9 * (oi + 1) + 3 * (oj + 1) + (ok + 1);
}

struct counts_key {
  int64_t key;
  int cell;
};

static int counts_key_cmp(const void *a, const void *b) {
  const struct counts_key *x = a, *y = b;
  return x->key < y->key ? -1 : x->key > y->key;
}

static int64_t counts_linear(const int cdim[3], int i, int j, int k) {
  return ((int64_t)i * cdim[1] + j) * cdim[2] + k;
}

/** Read "WORD value..." where the file must have it. */
static void counts_expect(FILE *f, const char *file, const char *word) {
  char w[64];
  if (fscanf(f, " %63s", w) != 1 || strcmp(w, word) != 0)
    error_exit("%s: expected '%s' in a partition counts file (tools/bench/impact_counts.py)", file,
               word);
}

void partition_counts_read(struct partition_counts *pc, const char *file) {
  memset(pc, 0, sizeof *pc);
  FILE *f = fopen(file, "r");
  if (!f) error_exit("%s: cannot open the partition counts file", file);
  /* comments first */
  int ch;
  while ((ch = fgetc(f)) == '#' || ch == '\n')
    if (ch == '#')
      while ((ch = fgetc(f)) != EOF && ch != '\n') {
      }
  if (ch != EOF) ungetc(ch, f);
  double box[3], reach;
  long long npart, ncells, nmasks;
  counts_expect(f, file, "grid");
  if (fscanf(f, "%d %d %d", &pc->cdim[0], &pc->cdim[1], &pc->cdim[2]) != 3)
    error_exit("%s: bad grid line", file);
  counts_expect(f, file, "box");
  if (fscanf(f, "%lf %lf %lf", &box[0], &box[1], &box[2]) != 3) error_exit("%s: bad box", file);
  counts_expect(f, file, "support");
  if (fscanf(f, "%lf", &pc->support) != 1) error_exit("%s: bad support", file);
  counts_expect(f, file, "reach");
  if (fscanf(f, "%lf", &reach) != 1) error_exit("%s: bad reach", file);
  counts_expect(f, file, "loops");
  if (fscanf(f, "%d", &pc->loops) != 1 || pc->loops < 1) error_exit("%s: bad loops", file);
  counts_expect(f, file, "cell_tasks");
  if (fscanf(f, "%d", &pc->cell_tasks) != 1 || pc->cell_tasks < 0)
    error_exit("%s: bad cell_tasks", file);
  counts_expect(f, file, "particles");
  if (fscanf(f, "%lld", &npart) != 1 || npart < 0) error_exit("%s: bad particles", file);
  counts_expect(f, file, "cells");
  if (fscanf(f, "%lld", &ncells) != 1 || ncells < 1 || ncells > INT32_MAX / 27)
    error_exit("%s: bad number of cells", file);
  for (int k = 0; k < 3; k++)
    if (pc->cdim[k] < 1 || pc->cdim[k] > (1 << 20)) error_exit("%s: bad grid", file);
  pc->particles = (size_t)npart;
  const int n = (int)ncells;
  pc->nr_cells = n;
  pc->ijk = error_malloc((size_t)n * 3 * sizeof(int), "partition counts");
  pc->count = error_malloc((size_t)n * sizeof(size_t), "partition counts");
  pc->pairmask = error_malloc((size_t)n * sizeof(int), "partition counts");
  size_t sum = 0;
  for (int c = 0; c < n; c++) {
    long long cnt;
    int *q = &pc->ijk[3 * c];
    if (fscanf(f, "%d %d %d %lld %d", &q[0], &q[1], &q[2], &cnt, &pc->pairmask[c]) != 5 || cnt < 1)
      error_exit("%s: bad line %d of the cells", file, c + 1);
    for (int k = 0; k < 3; k++)
      if (q[k] < 0 || q[k] >= pc->cdim[k]) error_exit("%s: cell %d outside the grid", file, c + 1);
    pc->count[c] = (size_t)cnt;
    sum += (size_t)cnt;
  }
  if (sum != pc->particles)
    error_exit("%s: the cells hold %zu particles, the file says %zu", file, sum, pc->particles);
  counts_expect(f, file, "masks");
  if (fscanf(f, "%lld", &nmasks) != 1 || nmasks < 0) error_exit("%s: bad number of masks", file);
  pc->nr_masks = (size_t)nmasks;
  const size_t nm = pc->nr_masks ? pc->nr_masks : 1;
  pc->mask_cell = error_malloc(nm * sizeof(int), "partition counts");
  pc->mask_bits = error_malloc(nm * sizeof(int), "partition counts");
  pc->mask_count = error_malloc(nm * sizeof(size_t), "partition counts");
  size_t msum = 0;
  for (size_t m = 0; m < pc->nr_masks; m++) {
    long long cnt;
    if (fscanf(f, "%d %d %lld", &pc->mask_cell[m], &pc->mask_bits[m], &cnt) != 3 || cnt < 1 ||
        pc->mask_cell[m] < 0 || pc->mask_cell[m] >= n)
      error_exit("%s: bad line %zu of the masks", file, m + 1);
    pc->mask_count[m] = (size_t)cnt;
    msum += (size_t)cnt;
  }
  if (msum != pc->particles)
    error_exit("%s: the masks hold %zu particles, the file says %zu", file, msum, pc->particles);
  fclose(f);

  /* the neighbours, by binary search in the sorted keys */
  struct counts_key *keys = error_malloc((size_t)n * sizeof *keys, "partition counts");
  for (int c = 0; c < n; c++)
    keys[c] = (struct counts_key){
        counts_linear(pc->cdim, pc->ijk[3 * c], pc->ijk[3 * c + 1], pc->ijk[3 * c + 2]), c};
  qsort(keys, (size_t)n, sizeof *keys, counts_key_cmp);
  for (int c = 1; c < n; c++)
    if (keys[c].key == keys[c - 1].key) error_exit("%s: a cell listed twice", file);
  pc->nbr = error_malloc((size_t)n * 27 * sizeof(int), "partition counts");
  for (int c = 0; c < n; c++)
    for (int oi = -1; oi <= 1; oi++)
      for (int oj = -1; oj <= 1; oj++)
        for (int ok = -1; ok <= 1; ok++) {
          const int d = counts_dir(oi, oj, ok);
          pc->nbr[27 * c + d] = -1;
          if (d == 13 || !(pc->pairmask[c] >> d & 1)) continue;
          const int q[3] = {pc->ijk[3 * c] + oi, pc->ijk[3 * c + 1] + oj, pc->ijk[3 * c + 2] + ok};
          if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= pc->cdim[0] || q[1] >= pc->cdim[1] ||
              q[2] >= pc->cdim[2])
            error_exit("%s: a pair of cell %d leaves the grid", file, c + 1);
          const struct counts_key want = {counts_linear(pc->cdim, q[0], q[1], q[2]), 0};
          const struct counts_key *hit =
              bsearch(&want, keys, (size_t)n, sizeof *keys, counts_key_cmp);
          if (!hit) error_exit("%s: cell %d pairs with a cell that is not listed", file, c + 1);
          pc->nbr[27 * c + d] = hit->cell;
        }
  free(keys);
  for (int c = 0; c < n; c++)
    for (int d = 0; d < 27; d++) {
      const int b = pc->nbr[27 * c + d];
      if (b >= 0 && pc->nbr[27 * b + 26 - d] != c)
        error_exit("%s: the pairs of cells %d and %d do not agree", file, c + 1, b + 1);
    }
  /* b: the particles of each cell within the support of each neighbour */
  pc->near = error_calloc((size_t)n * 27, sizeof(double), "partition counts");
  for (size_t m = 0; m < pc->nr_masks; m++)
    for (int d = 0; d < 27; d++)
      if (pc->mask_bits[m] >> d & 1) pc->near[27 * pc->mask_cell[m] + d] += pc->mask_count[m];
}

void partition_counts_free(struct partition_counts *pc) {
  free(pc->ijk);
  free(pc->count);
  free(pc->pairmask);
  free(pc->nbr);
  free(pc->mask_cell);
  free(pc->mask_bits);
  free(pc->mask_count);
  free(pc->near);
  memset(pc, 0, sizeof *pc);
}

void partition_graph_counts(struct partition_graph *g, const struct partition_counts *pc) {
  memset(g, 0, sizeof *g);
  const int n = pc->nr_cells;
  g->nr_cells = n;
  for (int k = 0; k < 3; k++) g->cdim[k] = pc->cdim[k];
  g->ijk = error_malloc((size_t)n * 3 * sizeof(int), "partition graph");
  memcpy(g->ijk, pc->ijk, (size_t)n * 3 * sizeof(int));
  g->cost = error_calloc((size_t)n, sizeof(double), "partition costs");
  g->count = error_malloc((size_t)n * sizeof(size_t), "partition counts");
  g->cell_count = error_malloc((size_t)n * sizeof(size_t), "partition counts");
  memcpy(g->count, pc->count, (size_t)n * sizeof(size_t));
  memcpy(g->cell_count, pc->count, (size_t)n * sizeof(size_t));
  g->nr_space_cells = n;
  const double loops = pc->loops;
  int ne = 0;
  for (int c = 0; c < n; c++)
    for (int d = 0; d < 27; d++) ne += pc->nbr[27 * c + d] >= 0;
  g->xadj = error_malloc((size_t)(n + 1) * sizeof(int), "partition graph");
  g->adj = error_malloc((size_t)(ne ? ne : 1) * sizeof(int), "partition graph");
  g->comm = error_malloc((size_t)(ne ? ne : 1) * sizeof(double), "partition graph");
  g->nr_links = ne / 2;
  g->link_cell = error_malloc((size_t)(ne ? ne : 1) * sizeof(int), "partition links");
  g->link_top = error_malloc((size_t)(ne ? ne : 1) * sizeof(int), "partition links");
  int e = 0, l = 0;
  g->xadj[0] = 0;
  for (int c = 0; c < n; c++) {
    const double nc = (double)pc->count[c];
    g->cost[c] += loops * 0.5 * nc * (nc - 1.0) + pc->cell_tasks * PARTITION_PER_PARTICLE * nc;
    for (int d = 0; d < 27; d++) {
      const int b = pc->nbr[27 * c + d];
      if (b < 0) continue;
      const double nb = (double)pc->count[b];
      g->adj[e] = b;
      g->comm[e] = loops * (nc + nb);
      e++;
      if (d > 13) {
        /* each pair once: its tasks' estimate, half to each cell */
        const double w = loops * (nc + nb + pc->near[27 * c + d] * pc->near[27 * b + 26 - d]);
        g->cost[c] += 0.5 * w;
        g->cost[b] += 0.5 * w;
        g->link_cell[2 * l] = g->link_top[2 * l] = c;
        g->link_cell[2 * l + 1] = g->link_top[2 * l + 1] = b;
        l++;
      }
    }
    g->xadj[c + 1] = e;
  }
  g->total_cost = 0.0;
  for (int c = 0; c < n; c++) g->total_cost += g->cost[c];
  g->total_comm = 0.0;
  for (int k = 0; k < ne; k++) g->total_comm += 0.5 * g->comm[k];
}

void partition_exchange(const struct partition *p, const struct partition_counts *pc, double *layer,
                        double *sent, int *peers) {
  const int nr = p->nr_ranks;
  for (int r = 0; r < nr; r++) {
    layer[r] = 0.0;
    sent[r] = 0.0;
    peers[r] = 0;
  }
  int *to = error_malloc(27 * sizeof(int), "partition exchange");
  for (size_t m = 0; m < pc->nr_masks; m++) {
    const int c = pc->mask_cell[m], own = p->rank[c];
    int nto = 0;
    for (int d = 0; d < 27; d++) {
      if (!(pc->mask_bits[m] >> d & 1)) continue;
      const int b = pc->nbr[27 * c + d];
      if (b < 0) continue;
      const int r = p->rank[b];
      int dup = r == own;
      for (int q = 0; q < nto && !dup; q++) dup = to[q] == r;
      if (!dup) to[nto++] = r;
    }
    for (int q = 0; q < nto; q++) layer[to[q]] += (double)pc->mask_count[m];
    sent[own] += (double)nto * (double)pc->mask_count[m];
  }
  free(to);
  /* peers: ranks joined by a pair task, each once */
  unsigned char *link = error_calloc((size_t)nr * (size_t)nr, 1, "partition exchange");
  for (int c = 0; c < pc->nr_cells; c++)
    for (int d = 0; d < 27; d++) {
      const int b = pc->nbr[27 * c + d];
      if (b < 0) continue;
      const int r = p->rank[c], s = p->rank[b];
      if (r != s && !link[(size_t)r * nr + s]) {
        link[(size_t)r * nr + s] = 1;
        peers[r]++;
      }
    }
  free(link);
}
