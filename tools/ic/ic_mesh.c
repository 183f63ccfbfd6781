/* bolide-ic import-mesh: the nodes of a finite-element mesh as particles
 * (issue 24 item 4), so that a graded mesh becomes a graded particle body.
 *
 * Two inputs:
 *   nodes    a plain node file: one node a line, "id x y z [volume]",
 *            separated by blanks, tabs or commas; '#' starts a comment
 *            (whole line or trailing); either every line has a volume or
 *            none has.
 *   keyword  the *NODE sections of a keyword-format explicit-dynamics deck
 *            (LS-DYNA style): after a line "*NODE" (any case; "*NODE +" or
 *            "*NODE %" the long format), one node a line until the next line
 *            starting with '*'.  A line with a comma is free format
 *            (nid, x, y, z[, tc, rc]); otherwise fixed columns: nid in 8, x
 *            y z in 16 each (long format: 20 each), tc and rc ignored, a
 *            blank coordinate field is 0 as in the deck's own reader.  A
 *            line in neither layout that has 4 to 6 blank-separated numbers
 *            is read as those.  '$' starts a comment line.  Other keywords
 *            (elements, parts, materials) are skipped.
 *
 * Volumes: the node file's column, or, where there is none (always for a
 * keyword deck), the nodal spacing: V = s^3 with s the distance to the
 * nearest other node.  On a lattice of spacing s (a regular hexahedral
 * mesh) that is exact; across a jump in the spacing the coarse nodes next
 * to the fine ones get the fine side's spacing (smaller volumes on the
 * interface's first coarse layer); give a volume column (e.g. the lumped
 * element volumes) where the total mass matters to better than that.
 *
 * Each particle: mass = rho V (--rho, the material's density), density rho,
 * h = eta V^(1/3) (eta: SPH:resolution_eta's default, --eta), material
 * --mat, internal energy --u, at rest.  Coordinates times --scale (e.g.
 * 1e-3 for a deck in mm), then shifted, as import-miluphcuda does, so that
 * the nodes' centre is at the centre of the open box [0, L]^3 with L twice
 * their largest extent.  Particle ids are the node ids. */
#include <ctype.h>
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "tools/ic/ic_impact.h"
#include "tasks/hydro/kernel.h"
#include "src/part.h"
#include "src/io/snapshot.h"
#include "src/io/units.h"

/** The nodes read, before they become particles. */
struct mesh_nodes {
  size_t n, cap;
  long long *id;
  double *x; /* 3 n */
  double *V; /* NULL: no volume column */
  long *line;
};

static void mesh_push(struct mesh_nodes *m, long long id, const double x[3], double V, int has_V,
                      long line) {
  if (m->n == m->cap) {
    m->cap = m->cap ? 2 * m->cap : 1024;
    m->id = error_realloc(m->id, m->cap * sizeof *m->id, "mesh ids");
    m->x = error_realloc(m->x, 3 * m->cap * sizeof *m->x, "mesh positions");
    m->line = error_realloc(m->line, m->cap * sizeof *m->line, "mesh lines");
    if (has_V) m->V = error_realloc(m->V, m->cap * sizeof *m->V, "mesh volumes");
  }
  m->id[m->n] = id;
  for (int d = 0; d < 3; d++) m->x[3 * m->n + d] = x[d];
  if (has_V) m->V[m->n] = V;
  m->line[m->n] = line;
  m->n++;
}

/** A finite number from s (the whole of s but blanks); 0 on failure. */
static int mesh_number(const char *s, double *v) {
  char *end;
  while (*s == ' ' || *s == '\t') s++;
  if (!*s) return 0;
  *v = strtod(s, &end);
  if (end == s) return 0;
  while (*end == ' ' || *end == '\t' || *end == '\r' || *end == '\n') end++;
  return *end == '\0';
}

/** A node id from a number: a whole number in [-2^62, 2^62]. */
static int mesh_id(double v, long long *id) {
  if (!(fabs(v) <= 4.6e18) || v != floor(v)) return 0;
  *id = (long long)v;
  return 1;
}

/** Split s at blanks, tabs and commas into at most max numbers; returns how
 *  many, or -1 - k if token k is not a number (or not finite: -100 - k). */
static int mesh_split(char *s, double *v, int max) {
  int n = 0;
  for (char *t = strtok(s, " \t,\r\n"); t; t = strtok(NULL, " \t,\r\n")) {
    double x;
    if (!mesh_number(t, &x)) return -1 - n;
    if (!isfinite(x)) return -100 - n;
    if (n < max) v[n] = x;
    n++;
  }
  return n;
}

/** Fixed-column *NODE line: nid (8 wide) then x y z (w wide each). */
static int mesh_fixed(const char *line, int w, long long *id, double x[3], int *bad_field) {
  const size_t len = strcspn(line, "\r\n");
  char f[32];
  const int width[4] = {w == 20 ? 20 : 8, w, w, w};
  size_t at = 0;
  for (int k = 0; k < 4; k++) {
    size_t take = at < len ? len - at : 0;
    if (take > (size_t)width[k]) take = (size_t)width[k];
    memcpy(f, line + at, take);
    f[take] = '\0';
    at += (size_t)width[k];
    double v = 0.0;
    int blank = 1;
    for (size_t c = 0; c < take; c++) blank &= (f[c] == ' ' || f[c] == '\t');
    if (!blank && !mesh_number(f, &v)) return 0;
    if (!isfinite(v)) {
      *bad_field = k + 1;
      return -1;
    }
    if (k == 0) {
      if (blank || !mesh_id(v, id)) return 0;
    } else {
      x[k - 1] = v; /* blank: 0, as the deck's reader takes it */
    }
  }
  return 1;
}

static FILE *mesh_open(const char *in) {
  FILE *f = fopen(in, "r");
  if (!f) error_exit("%s: cannot open: %s", in, strerror(errno));
  return f;
}

/** A plain node file. */
static void mesh_read_nodes(const char *in, struct mesh_nodes *m) {
  FILE *f = mesh_open(in);
  char *line = NULL;
  size_t cap = 0;
  long lineno = 0;
  int ncol = 0;
  long first_line = 0;
  while (getline(&line, &cap, f) > 0) {
    lineno++;
    char *hash = strchr(line, '#');
    if (hash) *hash = '\0';
    double v[8];
    const int n = mesh_split(line, v, 8);
    if (n == 0) continue;
    if (n <= -100) error_exit("%s:%ld: column %d is not finite", in, lineno, -n - 99);
    if (n < 0) error_exit("%s:%ld: column %d is not a number", in, lineno, -n);
    if (n != 4 && n != 5)
      error_exit("%s:%ld: %d columns, expected 'id x y z' or 'id x y z volume'", in, lineno, n);
    if (!ncol) ncol = n, first_line = lineno;
    if (n != ncol)
      error_exit("%s:%ld: %d columns, but line %ld has %d (a volume on every line or on none)", in,
                 lineno, n, first_line, ncol);
    long long id;
    if (!mesh_id(v[0], &id))
      error_exit("%s:%ld: node id %g is not a whole number", in, lineno, v[0]);
    if (n == 5 && !(v[4] > 0.0)) error_exit("%s:%ld: volume %g must be positive", in, lineno, v[4]);
    mesh_push(m, id, v + 1, n == 5 ? v[4] : 0.0, n == 5, lineno);
  }
  free(line);
  fclose(f);
  if (m->n == 0) error_exit("%s: no nodes", in);
}

/** The *NODE sections of a keyword deck. */
static void mesh_read_keyword(const char *in, struct mesh_nodes *m) {
  FILE *f = mesh_open(in);
  char *line = NULL;
  size_t cap = 0;
  long lineno = 0;
  int in_node = 0, sections = 0, w = 16;
  while (getline(&line, &cap, f) > 0) {
    lineno++;
    if (line[0] == '$') continue;
    if (line[0] == '*') {
      char kw[32] = "";
      size_t k = 0;
      for (const char *c = line + 1; *c && !isspace((unsigned char)*c) && k < sizeof kw - 1; c++)
        kw[k++] = (char)toupper((unsigned char)*c);
      kw[k] = '\0';
      in_node = strcmp(kw, "NODE") == 0 || strcmp(kw, "NODE+") == 0 || strcmp(kw, "NODE%") == 0;
      if (in_node) {
        sections++;
        w = (strchr(line, '+') || strchr(line, '%')) ? 20 : 16;
      }
      if (strcmp(kw, "END") == 0) break;
      continue;
    }
    if (!in_node) continue;
    const size_t len = strcspn(line, "\r\n");
    size_t c = 0;
    while (c < len && (line[c] == ' ' || line[c] == '\t')) c++;
    if (c == len) continue; /* blank line */
    long long id = 0;
    double x[3] = {0, 0, 0};
    int ok = 0;
    if (memchr(line, ',', len)) {
      /* free format: nid, x, y, z[, tc, rc]; an empty field is 0 */
      char *s = line;
      s[len] = '\0';
      int k = 0;
      for (char *t = s;; k++) {
        char *comma = strchr(t, ',');
        if (comma) *comma = '\0';
        double v = 0.0;
        int blank = 1;
        for (const char *q = t; *q; q++) blank &= (*q == ' ' || *q == '\t');
        if (k < 4) {
          if (!blank && !mesh_number(t, &v))
            error_exit("%s:%ld: *NODE field %d is not a number ('%.20s')", in, lineno, k + 1, t);
          if (!isfinite(v)) error_exit("%s:%ld: *NODE field %d is not finite", in, lineno, k + 1);
          if (k == 0 && (blank || !mesh_id(v, &id)))
            error_exit("%s:%ld: *NODE id '%.20s' is not a whole number", in, lineno, t);
          if (k > 0) x[k - 1] = v;
        }
        if (!comma) break;
        t = comma + 1;
      }
      if (k < 3)
        error_exit("%s:%ld: *NODE line with %d fields, expected nid, x, y, z", in, lineno, k + 1);
      ok = 1;
    } else {
      int bad = 0;
      ok = mesh_fixed(line, w, &id, x, &bad);
      if (ok < 0) error_exit("%s:%ld: *NODE field %d is not finite", in, lineno, bad);
      if (!ok) {
        /* not in the columns: blank-separated numbers */
        double v[8];
        line[len] = '\0';
        const int n = mesh_split(line, v, 8);
        if (n <= -100) error_exit("%s:%ld: *NODE field %d is not finite", in, lineno, -n - 99);
        if (n < 4 || n > 6)
          error_exit(
              "%s:%ld: not a *NODE line (nid in columns 1-8, x y z in %d columns each, or "
              "nid, x, y, z separated by commas)",
              in, lineno, w);
        if (!mesh_id(v[0], &id))
          error_exit("%s:%ld: *NODE id %g is not a whole number", in, lineno, v[0]);
        for (int d = 0; d < 3; d++) x[d] = v[1 + d];
        ok = 1;
      }
    }
    mesh_push(m, id, x, 0.0, 0, lineno);
  }
  free(line);
  fclose(f);
  if (sections == 0) error_exit("%s: no *NODE section", in);
  if (m->n == 0) error_exit("%s: *NODE sections without nodes", in);
}

/** Is the file a keyword deck (a line starting with '*')? */
static int mesh_is_keyword(const char *in) {
  FILE *f = mesh_open(in);
  char *line = NULL;
  size_t cap = 0;
  int kw = 0;
  while (!kw && getline(&line, &cap, f) > 0) kw = line[0] == '*';
  free(line);
  fclose(f);
  return kw;
}

/* qsort has no context argument in C11: the ids through a file-scope pointer */
static const long long *mesh_sort_ids;
static int mesh_cmp(const void *a, const void *b) {
  const size_t i = *(const size_t *)a, j = *(const size_t *)b;
  const long long *id = mesh_sort_ids;
  return id[i] < id[j] ? -1 : id[i] > id[j] ? 1 : (i < j ? -1 : i > j);
}

/** Duplicate node ids: an error naming both lines. */
static void mesh_check_ids(const char *in, const struct mesh_nodes *m) {
  size_t *ord = error_malloc(m->n * sizeof *ord, "mesh order");
  for (size_t i = 0; i < m->n; i++) ord[i] = i;
  mesh_sort_ids = m->id;
  qsort(ord, m->n, sizeof *ord, mesh_cmp);
  for (size_t k = 1; k < m->n; k++)
    if (m->id[ord[k]] == m->id[ord[k - 1]])
      error_exit("%s:%ld: duplicate node id %lld (first on line %ld)", in, m->line[ord[k]],
                 m->id[ord[k]], m->line[ord[k - 1]]);
  free(ord);
}

/** s[i] = distance of node i to its nearest other node (grid of cells of
 *  about one node each, searched in growing shells). */
static void mesh_nearest(const char *in, const struct mesh_nodes *m, double *s) {
  const size_t n = m->n;
  double lo[3], hi[3], ext[3], L = 0.0;
  for (int d = 0; d < 3; d++) lo[d] = INFINITY, hi[d] = -INFINITY;
  for (size_t i = 0; i < n; i++)
    for (int d = 0; d < 3; d++)
      lo[d] = fmin(lo[d], m->x[3 * i + d]), hi[d] = fmax(hi[d], m->x[3 * i + d]);
  for (int d = 0; d < 3; d++) L = fmax(L, hi[d] - lo[d]);
  if (n < 2 || !(L > 0.0))
    error_exit("%s: volumes from the node spacing need two distinct nodes", in);
  double vol = 1.0;
  for (int d = 0; d < 3; d++) ext[d] = fmax(hi[d] - lo[d], 1e-3 * L), vol *= ext[d];
  const double cs = cbrt(vol / (double)n);
  long nc[3];
  size_t ncell = 1;
  for (int d = 0; d < 3; d++) {
    nc[d] = (long)(ext[d] / cs) + 1;
    if (nc[d] > 4096) nc[d] = 4096;
    ncell *= (size_t)nc[d];
  }
  double inv[3];
  for (int d = 0; d < 3; d++) inv[d] = (double)nc[d] / (ext[d] * (1.0 + 1e-12));
  size_t *start = error_calloc(ncell + 1, sizeof *start, "mesh cells");
  size_t *cell = error_malloc(n * sizeof *cell, "mesh cell of node");
  size_t *sorted = error_malloc(n * sizeof *sorted, "mesh sorted nodes");
  long *ci = error_malloc(3 * n * sizeof *ci, "mesh cell coordinates");
  for (size_t i = 0; i < n; i++) {
    for (int d = 0; d < 3; d++) {
      long c = (long)((m->x[3 * i + d] - lo[d]) * inv[d]);
      ci[3 * i + d] = c < 0 ? 0 : c >= nc[d] ? nc[d] - 1 : c;
    }
    cell[i] = ((size_t)ci[3 * i] * (size_t)nc[1] + (size_t)ci[3 * i + 1]) * (size_t)nc[2] +
              (size_t)ci[3 * i + 2];
    start[cell[i] + 1]++;
  }
  for (size_t c = 0; c < ncell; c++) start[c + 1] += start[c];
  size_t *fill = error_malloc(ncell * sizeof *fill, "mesh fill");
  memcpy(fill, start, ncell * sizeof *fill);
  for (size_t i = 0; i < n; i++) sorted[fill[cell[i]]++] = i;
  free(fill);
  double cw = INFINITY; /* the narrowest cell width: a shell k away is >= (k-1) cw away */
  for (int d = 0; d < 3; d++) cw = fmin(cw, ext[d] / (double)nc[d]);
  const long kmax =
      nc[0] > nc[1] ? (nc[0] > nc[2] ? nc[0] : nc[2]) : (nc[1] > nc[2] ? nc[1] : nc[2]);
  for (size_t i = 0; i < n; i++) {
    const double *xi = m->x + 3 * i;
    double best2 = INFINITY;
    size_t bj = i;
    for (long k = 0; k <= kmax; k++) {
      /* the cells at Chebyshev distance k from i's */
      for (long a = -k; a <= k; a++) {
        const long c0 = ci[3 * i] + a;
        if (c0 < 0 || c0 >= nc[0]) continue;
        for (long b = -k; b <= k; b++) {
          const long c1 = ci[3 * i + 1] + b;
          if (c1 < 0 || c1 >= nc[1]) continue;
          const int face = (a == -k || a == k || b == -k || b == k);
          for (long c = -k; c <= k; c += (face ? 1 : (2 * k > 0 ? 2 * k : 1))) {
            const long c2 = ci[3 * i + 2] + c;
            if (c2 >= 0 && c2 < nc[2]) {
              const size_t cc =
                  ((size_t)c0 * (size_t)nc[1] + (size_t)c1) * (size_t)nc[2] + (size_t)c2;
              for (size_t q = start[cc]; q < start[cc + 1]; q++) {
                const size_t j = sorted[q];
                if (j == i) continue;
                const double *xj = m->x + 3 * j;
                const double r2 = (xi[0] - xj[0]) * (xi[0] - xj[0]) +
                                  (xi[1] - xj[1]) * (xi[1] - xj[1]) +
                                  (xi[2] - xj[2]) * (xi[2] - xj[2]);
                if (r2 < best2) best2 = r2, bj = j;
              }
            }
            if (k == 0) break;
          }
        }
      }
      /* every node not yet seen is at least k cw away */
      if (best2 <= (double)k * cw * (double)k * cw) break;
    }
    if (!(best2 > 0.0)) {
      const size_t a = m->line[bj] > m->line[i] ? bj : i, b = a == i ? bj : i; /* the later line */
      free(start), free(cell), free(sorted), free(ci); /* (the leak checker of the ASan tests) */
      error_exit("%s:%ld: node %lld at the same position as node %lld (line %ld)", in, m->line[a],
                 m->id[a], m->id[b], m->line[b]);
    }
    s[i] = sqrt(best2);
  }
  free(start);
  free(cell);
  free(sorted);
  free(ci);
}

static void mesh_usage(FILE *f) {
  fprintf(f,
          "Usage: bolide-ic import-mesh FILE --rho RHO [options]\n"
          "Particles at the nodes of a finite-element mesh, with the nodes' volumes:\n"
          "mass = RHO x volume, h = ETA x volume^(1/3), at rest.  FILE is\n"
          "  a node file: 'id x y z [volume]' a line ('#' comments; a volume on every\n"
          "    line or on none), or\n"
          "  a keyword deck (LS-DYNA style): the nodes of its *NODE sections, fixed\n"
          "    columns (I8, 3E16; *NODE + : I20, 3E20) or comma-separated.\n"
          "Without a volume column the volume is s^3, s the distance to the nearest\n"
          "other node (exact on a regular hexahedral mesh).\n"
          "  -o, --output FILE   output (default: FILE with .hdf5)\n"
          "  --format F          auto (default: keyword if a line starts with '*'),\n"
          "                      nodes or keyword\n"
          "  --rho RHO           density of the material (required)\n"
          "  --mat ID            material id (default 0)\n"
          "  --u U               specific internal energy (default 0)\n"
          "  --eta ETA           h = ETA x volume^(1/3) (default: "
          "SPH:resolution_eta's, " KERNEL_ETA_DEFAULT_STR
          ")\n"
          "  --scale F           multiply the coordinates (and volumes by F^3), e.g. 1e-3\n"
          "                      for a mesh in mm (default 1)\n"
          "  -h, --help          this help\n"
          "The nodes are shifted so that their centre is at the centre of the box\n"
          "[0, L]^3, L twice their largest extent; particle ids are the node ids.\n");
}

static double mesh_opt_real(const char *opt, const char *s, double min_excl) {
  char *end;
  const double v = strtod(s, &end);
  if (end == s || *end || !isfinite(v) || !(v > min_excl))
    error_exit("import-mesh: --%s: expected a number > %g, got '%s'", opt, min_excl, s);
  return v;
}

int icgen_mesh_main(int argc, char **argv) {
  const char *out = NULL;
  int format = 0; /* 0 auto, 1 nodes, 2 keyword */
  double rho = 0.0, u = 0.0, eta = KERNEL_ETA_DEFAULT, scale = 1.0;
  long mat = 0;
  enum { O_FORMAT = 300, O_RHO, O_MAT, O_U, O_ETA, O_SCALE };
  static const struct option opts[] = {{"output", required_argument, NULL, 'o'},
                                       {"format", required_argument, NULL, O_FORMAT},
                                       {"rho", required_argument, NULL, O_RHO},
                                       {"mat", required_argument, NULL, O_MAT},
                                       {"u", required_argument, NULL, O_U},
                                       {"eta", required_argument, NULL, O_ETA},
                                       {"scale", required_argument, NULL, O_SCALE},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  int c;
  opterr = 0;
  optind = 1;
  while ((c = getopt_long(argc, argv, ":o:h", opts, NULL)) != -1) {
    switch (c) {
      case 'o':
        out = optarg;
        break;
      case O_FORMAT:
        if (strcmp(optarg, "auto") == 0)
          format = 0;
        else if (strcmp(optarg, "nodes") == 0)
          format = 1;
        else if (strcmp(optarg, "keyword") == 0)
          format = 2;
        else
          error_exit("import-mesh: --format: expected auto, nodes or keyword, got '%s'", optarg);
        break;
      case O_RHO:
        rho = mesh_opt_real("rho", optarg, 0.0);
        break;
      case O_MAT: {
        char *end;
        mat = strtol(optarg, &end, 10);
        if (end == optarg || *end || mat < 0 || mat > 2147483647L)
          error_exit("import-mesh: --mat: expected an integer >= 0, got '%s'", optarg);
        break;
      }
      case O_U: {
        char *end;
        u = strtod(optarg, &end);
        if (end == optarg || *end || !isfinite(u) || u < 0.0)
          error_exit("import-mesh: --u: expected a number >= 0, got '%s'", optarg);
        break;
      }
      case O_ETA:
        eta = mesh_opt_real("eta", optarg, 1e-3);
        break;
      case O_SCALE:
        scale = mesh_opt_real("scale", optarg, 0.0);
        break;
      case 'h':
        mesh_usage(stdout);
        return 0;
      case ':':
        error_exit("import-mesh: option '%s' needs a value", argv[optind - 1]);
      default:
        error_exit("import-mesh: unknown option '%s' (see --help)", argv[optind - 1]);
    }
  }
  if (optind != argc - 1) error_exit("import-mesh: expected one input FILE (see --help)");
  if (!(rho > 0.0)) error_exit("import-mesh: --rho RHO is required (the material's density)");
  const char *in = argv[optind];
  char outbuf[4096];
  if (!out) {
    const char *dot = strrchr(in, '.'), *slash = strrchr(in, '/');
    const size_t stem = dot && (!slash || dot > slash) ? (size_t)(dot - in) : strlen(in);
    snprintf(outbuf, sizeof outbuf, "%.*s.hdf5", (int)stem, in);
    out = outbuf;
  }
  if (format == 0) format = mesh_is_keyword(in) ? 2 : 1;

  struct mesh_nodes m = {0};
  if (format == 2)
    mesh_read_keyword(in, &m);
  else
    mesh_read_nodes(in, &m);
  mesh_check_ids(in, &m);
  for (size_t i = 0; i < 3 * m.n; i++) m.x[i] *= scale;
  double *V = error_malloc(m.n * sizeof *V, "mesh volumes");
  if (m.V) {
    for (size_t i = 0; i < m.n; i++) V[i] = m.V[i] * scale * scale * scale;
  } else {
    mesh_nearest(in, &m, V);
    for (size_t i = 0; i < m.n; i++) V[i] = V[i] * V[i] * V[i];
  }

  struct parts p;
  parts_alloc(&p, m.n);
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < m.n; i++)
    for (int d = 0; d < 3; d++)
      lo[d] = fmin(lo[d], m.x[3 * i + d]), hi[d] = fmax(hi[d], m.x[3 * i + d]);
  double ext = 0.0, vmin = INFINITY, vmax = 0.0, mtot = 0.0;
  for (int d = 0; d < 3; d++) ext = fmax(ext, hi[d] - lo[d]);
  const double L = fmax(2.0 * ext, 2.0 * cbrt(V[0]));
  for (size_t i = 0; i < m.n; i++) {
    p.x[i] = m.x[3 * i] + 0.5 * L - 0.5 * (lo[0] + hi[0]);
    p.y[i] = m.x[3 * i + 1] + 0.5 * L - 0.5 * (lo[1] + hi[1]);
    p.z[i] = m.x[3 * i + 2] + 0.5 * L - 0.5 * (lo[2] + hi[2]);
    p.m[i] = rho * V[i];
    p.rho[i] = rho;
    p.h[i] = eta * cbrt(V[i]);
    p.u[i] = u;
    p.mat[i] = (int32_t)mat;
    p.alpha[i] = 1.0; /* not porous */
    p.id[i] = (int64_t)m.id[i];
    vmin = fmin(vmin, V[i]), vmax = fmax(vmax, V[i]), mtot += p.m[i];
  }
  char command[4096] = "bolide-ic";
  for (int a = 0; a < argc; a++) {
    strncat(command, " ", sizeof command - strlen(command) - 1);
    strncat(command, argv[a], sizeof command - strlen(command) - 1);
  }
  struct unit_system si;
  units_init_si(&si);
  struct snapshot_meta meta = {
      .time = 0, .periodic = 0, .ic = 1, .run_name = "import-mesh", .command = command, .hydro = 1};
  for (int d = 0; d < 3; d++) meta.box_size[d] = L;
  snapshot_write(out, &meta, &p, &si, 0);
  printf(
      "bolide-ic import-mesh: %zu nodes of %s (%s, volumes %s: %.4g to %.4g, total mass %.6g) "
      "written to %s\n",
      m.n, in, format == 2 ? "keyword deck" : "node file", m.V ? "given" : "from the spacing", vmin,
      vmax, mtot, out);
  parts_free(&p);
  free(V);
  free(m.id), free(m.x), free(m.V), free(m.line);
  return 0;
}
