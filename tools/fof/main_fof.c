/* bolide-fof: friends-of-friends fragments of a snapshot.
 *
 *   bolide-fof SNAPSHOT [--link-length L | --link-h F] [--min-damage-drop D]
 *              [--min-count C] [--out FRAGMENTS.txt] [--spectrum SPECTRUM.txt]
 *              [--plot SPECTRUM.png]
 *
 * Per fragment (sorted by mass, largest first): mass, particle count, centre
 * of mass and its velocity, mass-weighted mean damage (/PartType0/Damage, 0
 * if absent), the mass fraction of each material, and an escape test
 * against the barycentre of the whole snapshot (theory/damage.md, "Fragments"):
 * a fragment at distance r from the barycentre, moving at v relative to it,
 * is bound when v < v_esc(r) = sqrt(2 G M(<r) / r), M(<r) the mass of all
 * particles within r; a fragment whose own extent contains the barycentre
 * is the central body and bound.  Values in SI. */
#include <errno.h>
#include <getopt.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "src/error.h"
#include "tools/fof/fof.h"
#include "src/io/ic.h"
#include "src/paths.h"
#include "src/io/units.h"
#include "src/version.h"

/** Default of --link-local: F x max(h_i, h_j).  An intact planet of
 *  bolide-ic planet (SEA shells) holds together from F = 1.0 (0.9 splits it
 *  into 13 groups), one of 5000 particles from 1.1, one with a water layer
 *  from 1.2 (the median-h default of before, --link-h 1, cut that one into
 *  470); SEAGen's from 0.9; 1.5 leaves a margin. */
#define FOF_LINK_LOCAL_DEFAULT 1.5
#define FOF_LINK_LOCAL_DEFAULT_STR "1.5"

/** Most distinct materials reported as columns. */
#define FOF_MAX_MAT 64

/** Long options without a short form. */
enum {
  OPT_LINK_LENGTH = 256,
  OPT_LINK_H,
  OPT_LINK_LOCAL,
  OPT_DROP,
  OPT_MIN_COUNT,
  OPT_SPECTRUM,
  OPT_PLOT,
  OPT_VERSION
};

static const struct option fofmain_longopts[] = {
    {"link-length", required_argument, NULL, OPT_LINK_LENGTH},
    {"link-h", required_argument, NULL, OPT_LINK_H},
    {"link-local", required_argument, NULL, OPT_LINK_LOCAL},
    {"min-damage-drop", required_argument, NULL, OPT_DROP},
    {"min-count", required_argument, NULL, OPT_MIN_COUNT},
    {"out", required_argument, NULL, 'o'},
    {"spectrum", required_argument, NULL, OPT_SPECTRUM},
    {"plot", required_argument, NULL, OPT_PLOT},
    {"help", no_argument, NULL, 'h'},
    {"version", no_argument, NULL, OPT_VERSION},
    {NULL, 0, NULL, 0}};

/** Print the usage text to f. */
static void fofmain_usage(FILE *f) {
  fprintf(
      f,
      "Usage: bolide-fof SNAPSHOT.hdf5 [options]\n"
      "Friends-of-friends fragments: mass, count, position, velocity, damage,\n"
      "material fractions, boundness; cumulative mass spectrum.\n\n"
      "  --link-local F         two particles are friends when closer than F times\n"
      "                         the larger of their smoothing lengths: the linking\n"
      "                         length follows the particle spacing through the\n"
      "                         layers of a body (default: --link-local " FOF_LINK_LOCAL_DEFAULT_STR
      ",\n"
      "                         which keeps an intact SEA or woma/SEAGen planet,\n"
      "                         core to outer shell, in one fragment)\n"
      "  --link-length L        one linking length for every pair, in m\n"
      "  --link-h F             one linking length, F x the median smoothing length\n"
      "                         (the default of Bolide before 0.2: --link-h 1 split\n"
      "                         the sparser outer shells off a layered planet)\n"
      "  --min-damage-drop D    leave out particles with damage >= D (Nakamura\n"
      "                         analysis; default: keep all)\n"
      "  --min-count C          list fragments of at least C particles (default 1)\n"
      "  -o, --out FILE         fragment table (default: standard output)\n"
      "  --spectrum FILE        cumulative mass spectrum N(>=m) as text\n"
      "  --plot PNG             plot the spectrum (runs tools/plot_fragments.py with\n"
      "                         $PYTHON, default python3; needs --out)\n"
      "  -v                     log the phases and their times\n"
      "  -h, --help             this help\n"
      "  --version              version\n");
}

/** Parse a number for option `name`; positive unless zero_ok. */
static double fofmain_number(const char *name, const char *s, int zero_ok) {
  char *end;
  errno = 0;
  const double v = strtod(s, &end);
  if (end == s || *end || errno || !isfinite(v) || v < 0.0 || (!zero_ok && v == 0.0))
    error_exit("option --%s: '%s' is not a %s number", name, s,
               zero_ok ? "non-negative" : "positive");
  return v;
}

/** /PartType0/Damage of the snapshot (n values) into d; 0 if absent. */
static int fofmain_read_damage(const char *path, size_t n, double *d) {
  H5Eset_auto(H5E_DEFAULT, NULL, NULL);
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) error_exit("%s: cannot open as HDF5", path);
  int found = 0;
  if (H5Lexists(file, "PartType0", H5P_DEFAULT) > 0 &&
      H5Lexists(file, "PartType0/Damage", H5P_DEFAULT) > 0) {
    hid_t ds = H5Dopen2(file, "PartType0/Damage", H5P_DEFAULT);
    hid_t sp = ds >= 0 ? H5Dget_space(ds) : -1;
    if (sp < 0 || H5Sget_simple_extent_npoints(sp) != (hssize_t)n)
      error_exit("%s: /PartType0/Damage does not have one value per particle (%zu)", path, n);
    if (n > 0 && H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d) < 0)
      error_exit("%s: cannot read /PartType0/Damage", path);
    for (size_t i = 0; i < n; i++)
      if (!(d[i] >= 0.0 && d[i] <= 1.0))
        error_exit("%s: particle %zu: damage %g (must be in [0, 1])", path, i, d[i]);
    H5Sclose(sp);
    H5Dclose(ds);
    found = 1;
  }
  H5Fclose(file);
  return found;
}

/** Compare doubles (qsort). */
static int fofmain_cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/** One fragment. */
struct fofmain_frag {
  double mass;    /**< total mass */
  int64_t count;  /**< particles */
  double x[3];    /**< centre of mass */
  double v[3];    /**< centre-of-mass velocity */
  double damage;  /**< mass-weighted mean damage */
  double extent;  /**< largest distance of a member from the centre of mass */
  double r, vrel; /**< distance and speed relative to the barycentre */
  double vesc;    /**< escape speed at r from the enclosed mass */
  int bound;      /**< 1 if bound to the barycentre */
  int64_t index;  /**< group number before sorting */
};

/** Sort fragments by mass, largest first (ties: lower group number first). */
static int fofmain_cmp_frag(const void *a, const void *b) {
  const struct fofmain_frag *p = a, *q = b;
  if (p->mass != q->mass) return p->mass < q->mass ? 1 : -1;
  return (p->index > q->index) - (p->index < q->index);
}

/** Enclosed mass M(<r) from the sorted radii rs (n) and mass prefix sums. */
static double fofmain_enclosed(const double *rs, const double *mcum, size_t n, double r) {
  size_t lo = 0, hi = n; /* first index with rs >= r */
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    if (rs[mid] < r)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo ? mcum[lo - 1] : 0.0;
}

/** Run the plotting script on the fragment table. */
static void fofmain_plot(const char *table, const char *png) {
  const char *py = paths_python();
  /* $BOLIDE_TOOLS_DIR/plot_fragments.py, else the script beside an installed
   * bolide-fof, else the source tree's tools/ (paths.h) */
  char script[4096];
  const char *tools = getenv("BOLIDE_TOOLS_DIR");
  if (tools && *tools)
    snprintf(script, sizeof script, "%s/plot_fragments.py", tools);
  else if (!paths_find(script, sizeof script, NULL, "plot_fragments.py", "tools/plot_fragments.py"))
    error_exit("%s: cannot find the plotting script (%s; set BOLIDE_TOOLS_DIR)", png, script);
  fflush(NULL);
  const pid_t pid = fork();
  if (pid < 0) error_exit("cannot start %s: %s", py, strerror(errno));
  if (pid == 0) {
    execlp(py, py, script, table, "-o", png, (char *)NULL);
    fprintf(stderr, "%s: error: cannot run %s: %s\n", error_progname, py, strerror(errno));
    _exit(127);
  }
  int status;
  if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    error_exit("%s: plotting failed (%s %s)", png, py, script);
}

/** The command line. */
struct fofmain_opts {
  double link_length, link_h, link_local; /**< one of them set (--link-*) */
  double drop;                            /**< --min-damage-drop (INFINITY: none) */
  long long min_count;                    /**< --min-count */
  const char *out, *spectrum, *plot;      /**< --out, --spectrum, --plot (or NULL) */
  const char *path;                       /**< the snapshot */
};

/** Parse the command line into o; returns 1 when the program is done
 *  (--help, --version) and exits with a message on a bad option. */
static int fofmain_parse(int argc, char **argv, struct fofmain_opts *o) {
  *o = (struct fofmain_opts){.drop = INFINITY, .min_count = 1};
  int c;
  while ((c = getopt_long(argc, argv, "hvo:", fofmain_longopts, NULL)) != -1) {
    switch (c) {
      case OPT_LINK_LENGTH:
        o->link_length = fofmain_number("link-length", optarg, 0);
        break;
      case OPT_LINK_H:
        o->link_h = fofmain_number("link-h", optarg, 0);
        break;
      case OPT_LINK_LOCAL:
        o->link_local = fofmain_number("link-local", optarg, 0);
        break;
      case OPT_DROP:
        o->drop = fofmain_number("min-damage-drop", optarg, 1);
        break;
      case OPT_MIN_COUNT:
        o->min_count = (long long)fofmain_number("min-count", optarg, 0);
        break;
      case 'o':
        o->out = optarg;
        break;
      case OPT_SPECTRUM:
        o->spectrum = optarg;
        break;
      case OPT_PLOT:
        o->plot = optarg;
        break;
      case 'v':
        error_verbosity++;
        break;
      case 'h':
        fofmain_usage(stdout);
        return 1;
      case OPT_VERSION:
        bolide_version_print("bolide-fof");
        return 1;
      default:
        error_exit("unknown option (see --help)");
    }
  }
  if (argc - optind != 1) error_exit("expected one SNAPSHOT.hdf5 (see --help)");
  if ((o->link_length > 0.0) + (o->link_h > 0.0) + (o->link_local > 0.0) > 1)
    error_exit("give one of --link-local, --link-length and --link-h");
  if (o->plot && !o->out) error_exit("--plot needs --out FILE (the table it plots)");
  if (o->link_length == 0.0 && o->link_h == 0.0 && o->link_local == 0.0)
    o->link_local = FOF_LINK_LOCAL_DEFAULT;
  o->path = argv[optind];
  return 0;
}

/** The median smoothing length of the kept particles (0 without --link-h
 *  or --link-local); sets o->link_length for --link-h and returns in *ell
 *  each particle's linking length for --link-local (else NULL). */
static double fofmain_link_lengths(struct fofmain_opts *o, const struct parts *p,
                                   struct ic_info *info, const unsigned char *keep, double **ell) {
  *ell = NULL;
  if (!(o->link_h > 0.0 || o->link_local > 0.0)) return 0.0;
  const size_t n = p->count;
  int kh = -1;
  for (int k = 0; k < part_nr_fields; k++)
    if (strcmp(part_fields[k].name, "h") == 0) kh = k;
  if (kh < 0 || !ic_field_read(info, kh))
    error_exit("%s: no SmoothingLengths: give --link-length", o->path);
  double *hs = error_malloc(n * sizeof *hs, "smoothing lengths");
  size_t m = 0;
  for (size_t i = 0; i < n; i++)
    if (keep[i]) hs[m++] = p->h[i];
  if (m == 0) error_exit("%s: every particle is dropped (damage >= %g)", o->path, o->drop);
  qsort(hs, m, sizeof *hs, fofmain_cmp_double);
  const double median_h = hs[m / 2];
  if (o->link_h > 0.0) o->link_length = o->link_h * median_h;
  free(hs);
  if (o->link_local > 0.0) {
    double *l = error_malloc(n * sizeof *l, "linking lengths");
    for (size_t i = 0; i < n; i++) {
      l[i] = o->link_local * p->h[i];
      if (keep[i] && !(l[i] > 0.0 && isfinite(l[i])))
        error_exit("%s: particle %zu has smoothing length %g: give --link-length", o->path, i,
                   p->h[i]);
    }
    *ell = l;
  }
  return median_h;
}

/** The fragments of a snapshot and what the table says of the whole. */
struct fofmain_result {
  int64_t ng;                /**< fragments */
  struct fofmain_frag *fr;   /**< ng fragments, largest first */
  double *mmat;              /**< mass of material k in group g: mmat[g * nmat + k] */
  int32_t mats[FOF_MAX_MAT]; /**< the materials present */
  int nmat;
  double M, xb[3], vb[3];      /**< total mass, barycentre and its velocity */
  double bound_mass;           /**< mass of the fragments bound to the barycentre */
  double bound_mass_particles; /**< mass of the particles bound to it */
};

/** The materials present in p (at most FOF_MAX_MAT). */
static void fofmain_materials(const struct parts *p, const char *path, struct fofmain_result *r) {
  r->nmat = 0;
  for (size_t i = 0; i < p->count; i++) {
    int k = 0;
    while (k < r->nmat && r->mats[k] != p->mat[i]) k++;
    if (k == r->nmat) {
      if (r->nmat == FOF_MAX_MAT) error_exit("%s: more than %d materials", path, FOF_MAX_MAT);
      r->mats[r->nmat++] = p->mat[i];
    }
  }
}

/** Barycentre, particles sorted by distance from it (radix sort of the bit
 *  patterns of r >= 0: *rord the order, *rsort the radii) and the enclosed
 *  mass up to each (*mcum). */
static void fofmain_radial(const struct parts *p, struct fofmain_result *r, int64_t **rord,
                           double **rsort, double **mcum) {
  const size_t n = p->count;
  double M = 0.0, xb[3] = {0, 0, 0}, vb[3] = {0, 0, 0};
  for (size_t i = 0; i < n; i++) {
    M += p->m[i];
    xb[0] += p->m[i] * p->x[i], xb[1] += p->m[i] * p->y[i], xb[2] += p->m[i] * p->z[i];
    vb[0] += p->m[i] * p->vx[i], vb[1] += p->m[i] * p->vy[i], vb[2] += p->m[i] * p->vz[i];
  }
  for (int d = 0; d < 3; d++) xb[d] /= M, vb[d] /= M;
  r->M = M;
  memcpy(r->xb, xb, sizeof xb);
  memcpy(r->vb, vb, sizeof vb);
  int64_t *rkey = error_malloc(n * sizeof *rkey, "radii");
  int64_t *ord = error_malloc(n * sizeof *ord, "radii");
  for (size_t i = 0; i < n; i++) {
    const double dx = p->x[i] - xb[0], dy = p->y[i] - xb[1], dz = p->z[i] - xb[2];
    const double rr = sqrt(dx * dx + dy * dy + dz * dz);
    memcpy(&rkey[i], &rr, sizeof rr);
    ord[i] = (int64_t)i;
  }
  fof_radix_sort(n, rkey, ord);
  double *rs = error_malloc(n * sizeof *rs, "radii");
  double *mc = error_malloc(n * sizeof *mc, "masses");
  for (size_t i = 0; i < n; i++) {
    memcpy(&rs[i], &rkey[i], sizeof rs[i]);
    mc[i] = (i ? mc[i - 1] : 0.0) + p->m[ord[i]];
  }
  free(rkey);
  *rord = ord, *rsort = rs, *mcum = mc;
}

/** Fragment properties: mass, centre of mass, velocity, damage, material
 *  fractions, extent, and whether each (and each particle) is bound to the
 *  barycentre; the fragments sorted by mass. */
static void fofmain_fragments(const struct parts *p, const int64_t *group, int64_t ng,
                              const double *dmg, const char *path, struct fofmain_result *r) {
  const size_t n = p->count;
  r->ng = ng;
  fofmain_materials(p, path, r);
  int64_t *rord;
  double *rsort, *mcum;
  fofmain_radial(p, r, &rord, &rsort, &mcum);
  struct unit_system si;
  units_init_si(&si);
  const double G = units_G(&si);
  const int nmat = r->nmat;
  struct fofmain_frag *fr = error_calloc(ng ? (size_t)ng : 1, sizeof *fr, "fragments");
  double *mmat = error_calloc((ng ? (size_t)ng : 1) * (size_t)nmat, sizeof *mmat, "fractions");
  for (size_t i = 0; i < n; i++) {
    const int64_t g = group[i];
    if (g < 0) continue;
    struct fofmain_frag *f = &fr[g];
    const double mi = p->m[i];
    f->mass += mi;
    f->count++;
    f->x[0] += mi * p->x[i], f->x[1] += mi * p->y[i], f->x[2] += mi * p->z[i];
    f->v[0] += mi * p->vx[i], f->v[1] += mi * p->vy[i], f->v[2] += mi * p->vz[i];
    f->damage += mi * dmg[i];
    int k = 0;
    while (r->mats[k] != p->mat[i]) k++;
    mmat[(size_t)g * nmat + k] += mi;
  }
  for (int64_t g = 0; g < ng; g++) {
    struct fofmain_frag *f = &fr[g];
    f->index = g;
    for (int d = 0; d < 3; d++) f->x[d] /= f->mass, f->v[d] /= f->mass;
    f->damage /= f->mass;
  }
  /* particles in order of r: M(<r) is the mass before them (ties in r
   * counted as enclosed in sorted order, a negligible difference) */
  r->bound_mass_particles = 0.0;
  for (size_t k = 0; k < n; k++) {
    const size_t i = (size_t)rord[k];
    const double rk = rsort[k];
    const double dvx = p->vx[i] - r->vb[0], dvy = p->vy[i] - r->vb[1], dvz = p->vz[i] - r->vb[2];
    const double v2 = dvx * dvx + dvy * dvy + dvz * dvz;
    if (rk == 0.0 || v2 < 2.0 * G * (k ? mcum[k - 1] : 0.0) / rk)
      r->bound_mass_particles += p->m[i];
  }
  for (size_t i = 0; i < n; i++) {
    const int64_t g = group[i];
    if (g < 0) continue;
    const double ex = p->x[i] - fr[g].x[0], ey = p->y[i] - fr[g].x[1], ez = p->z[i] - fr[g].x[2];
    const double e = sqrt(ex * ex + ey * ey + ez * ez);
    if (e > fr[g].extent) fr[g].extent = e;
  }
  r->bound_mass = 0.0;
  for (int64_t g = 0; g < ng; g++) {
    struct fofmain_frag *f = &fr[g];
    double dx[3], dv[3];
    for (int d = 0; d < 3; d++) dx[d] = f->x[d] - r->xb[d], dv[d] = f->v[d] - r->vb[d];
    f->r = sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
    f->vrel = sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]);
    f->vesc = f->r > 0.0 ? sqrt(2.0 * G * fofmain_enclosed(rsort, mcum, n, f->r) / f->r) : INFINITY;
    f->bound = f->r <= f->extent || f->vrel < f->vesc;
    if (f->bound) r->bound_mass += f->mass;
  }
  qsort(fr, (size_t)ng, sizeof *fr, fofmain_cmp_frag);
  free(rsort);
  free(rord);
  free(mcum);
  r->fr = fr;
  r->mmat = mmat;
}

/** The fragment table, to o->out (through a temporary file) or stdout. */
static void fofmain_write_table(const struct fofmain_opts *o, const struct parts *p,
                                const struct ic_info *info, const unsigned char *keep, size_t nkeep,
                                int has_damage, double median_h, int64_t ng,
                                const struct fofmain_result *r) {
  const size_t n = p->count;
  char tmp[4096] = "";
  FILE *fo = stdout;
  if (o->out) {
    snprintf(tmp, sizeof tmp, "%s.tmp", o->out);
    fo = fopen(tmp, "w");
    if (!fo) error_exit("%s: cannot create: %s", tmp, strerror(errno));
    error_register_tmpfile(tmp);
  }
  double kept_mass = 0.0;
  for (size_t i = 0; i < n; i++)
    if (keep[i]) kept_mass += p->m[i];
  fprintf(fo, "# bolide-fof %s: %s\n", PACKAGE_VERSION, o->path);
  fprintf(fo, "# time %.9g s; %zu particles, %zu kept", info->time, n, nkeep);
  if (isfinite(o->drop)) fprintf(fo, " (damage < %g)", o->drop);
  fprintf(fo, "; damage %s\n", has_damage ? "from /PartType0/Damage" : "absent (0)");
  if (o->link_local > 0.0)
    fprintf(fo,
            "# linking length %.9g x max(h_i, h_j) (--link-local; %.9g m at the median h); %lld "
            "fragments\n",
            o->link_local, o->link_local * median_h, (long long)ng);
  else
    fprintf(fo, "# linking length %.9g m%s; %lld fragments\n", o->link_length,
            o->link_h > 0.0 ? " (from --link-h x median h)" : "", (long long)ng);
  fprintf(fo,
          "# total mass %.9g kg, kept %.9g kg; barycentre %.9g %.9g %.9g m, %.9g %.9g %.9g m/s\n",
          r->M, kept_mass, r->xb[0], r->xb[1], r->xb[2], r->vb[0], r->vb[1], r->vb[2]);
  fprintf(fo, "# bound to the barycentre: %.9g kg in fragments, %.9g kg of all particles\n",
          r->bound_mass, r->bound_mass_particles);
  fprintf(fo, "# rank mass count x y z vx vy vz damage r v_rel v_esc bound");
  for (int k = 0; k < r->nmat; k++) fprintf(fo, " frac_mat%d", (int)r->mats[k]);
  fprintf(fo, "\n");
  for (int64_t g = 0; g < ng; g++) {
    const struct fofmain_frag *f = &r->fr[g];
    if (f->count < o->min_count) continue;
    fprintf(fo, "%lld %.9e %lld %.9e %.9e %.9e %.9e %.9e %.9e %.6f %.6e %.6e %.6e %d",
            (long long)g + 1, f->mass, (long long)f->count, f->x[0], f->x[1], f->x[2], f->v[0],
            f->v[1], f->v[2], f->damage, f->r, f->vrel, f->vesc, f->bound);
    for (int k = 0; k < r->nmat; k++)
      fprintf(fo, " %.6f", r->mmat[(size_t)f->index * r->nmat + k] / f->mass);
    fprintf(fo, "\n");
  }
  if (o->out) {
    if (fflush(fo) != 0 || ferror(fo) || fclose(fo) != 0)
      error_exit("%s: write failed: %s", tmp, strerror(errno));
    if (rename(tmp, o->out) != 0)
      error_exit("%s: cannot rename %s: %s", o->out, tmp, strerror(errno));
    error_unregister_tmpfile(tmp);
  }
}

/** The cumulative mass spectrum, to o->spectrum (through a temporary file). */
static void fofmain_write_spectrum(const struct fofmain_opts *o, const struct fofmain_result *r) {
  char stmp[4096];
  snprintf(stmp, sizeof stmp, "%s.tmp", o->spectrum);
  FILE *fs = fopen(stmp, "w");
  if (!fs) error_exit("%s: cannot create: %s", stmp, strerror(errno));
  error_register_tmpfile(stmp);
  fprintf(fs, "# cumulative mass spectrum of %s: N(>=m), mass in fragments >= m\n", o->path);
  fprintf(fs, "# mass m/M_total N_ge cum_mass_fraction\n");
  double cum = 0.0;
  for (int64_t g = 0; g < r->ng; g++) {
    cum += r->fr[g].mass;
    /* one line per distinct mass: the count of all fragments >= m */
    if (g + 1 < r->ng && r->fr[g + 1].mass == r->fr[g].mass) continue;
    fprintf(fs, "%.9e %.9e %lld %.9e\n", r->fr[g].mass, r->fr[g].mass / r->M, (long long)g + 1,
            cum / r->M);
  }
  if (fflush(fs) != 0 || ferror(fs) || fclose(fs) != 0)
    error_exit("%s: write failed: %s", stmp, strerror(errno));
  if (rename(stmp, o->spectrum) != 0)
    error_exit("%s: cannot rename: %s", o->spectrum, strerror(errno));
  error_unregister_tmpfile(stmp);
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  struct fofmain_opts o;
  if (fofmain_parse(argc, argv, &o)) return 0;
  const char *path = o.path;

  struct unit_system si;
  units_init_si(&si);
  struct parts p;
  struct ic_info info;
  ic_read(path, &si, NULL, 0, &p, &info);
  const size_t n = p.count;
  if (n == 0) error_exit("%s: no particles", path);
  double *dmg = error_calloc(n, sizeof *dmg, "damage");
  const int has_damage = fofmain_read_damage(path, n, dmg);
  if (!has_damage && isfinite(o.drop))
    error_warning("%s: no /PartType0/Damage: --min-damage-drop keeps every particle", path);

  unsigned char *keep = error_malloc(n, "kept particles");
  size_t nkeep = 0;
  for (size_t i = 0; i < n; i++) {
    keep[i] = !(dmg[i] >= o.drop);
    nkeep += keep[i];
  }
  double *ell; /* --link-local: each particle's linking length */
  const double median_h = fofmain_link_lengths(&o, &p, &info, keep, &ell);

  int64_t *group = error_malloc(n * sizeof *group, "groups");
  error_log(1, "linking %zu particles, L = %g", nkeep,
            ell ? o.link_local * median_h : o.link_length);
  const int64_t ng = ell ? fof_groups_local(n, p.x, p.y, p.z, keep, ell, group)
                         : fof_groups(n, p.x, p.y, p.z, keep, o.link_length, group);
  free(ell);
  error_log(1, "%lld groups", (long long)ng);

  struct fofmain_result r;
  fofmain_fragments(&p, group, ng, dmg, path, &r);
  error_log(1, "fragment properties and escape test done");
  fofmain_write_table(&o, &p, &info, keep, nkeep, has_damage, median_h, ng, &r);
  if (o.spectrum) fofmain_write_spectrum(&o, &r);
  if (o.plot) fofmain_plot(o.out, o.plot);

  free(r.fr);
  free(r.mmat);
  free(group);
  free(keep);
  free(dmg);
  parts_free(&p);
  return 0;
}
