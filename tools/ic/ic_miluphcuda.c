/* bolide-ic import-miluphcuda: miluphcuda's ASCII particle input files as
 * Bolide initial conditions (issue 23 item 7, in part).
 *
 * miluphcuda's input columns depend on the switches it was compiled with
 * (its parameter.h; `miluphcuda --format` prints them), so the switches are
 * given here as options.  One line per particle, 3-D, SI units:
 *   x y z  vx vy vz  m  [rho (INTEGRATE_DENSITY)]  [e (INTEGRATE_ENERGY)]
 *   [sml (READ_INITIAL_SML_FROM_PARTICLE_FILE)]  material_id
 *   [ep T (JC_PLASTICITY)]  [n_flaws d (FRAGMENTATION)]  [S: 9 values, row by row (SOLID)]
 *   [alpha_jutzi p (PALPHA_POROSITY)]  [alpha_epspor epsilon_v (EPSALPHA_POROSITY)]
 *   [n_flaws activation thresholds (FRAGMENTATION)]
 * (miluphcuda's io.cu, read_particles_from_file; d is the cube root of the
 * tensile damage).  The flaws become Bolide's FlawThresholds/FlawOffsets
 * (tasks/damage/flaws.h), sorted ascending per particle (miluphcuda counts
 * the thresholds below the strain, which does not depend on their order),
 * d its DamageCubeRoot and d^3 its Damage.  SIRONO_POROSITY is not read.
 * miluphcuda's sml is the
 * kernel's support radius: h = sml / kernel_gamma.  Without sml, h =
 * SPH:resolution_eta's default x (m/rho)^(1/3) (Bolide iterates h anyway).
 * Material ids are kept (miluphcuda's start at 0); theory/miluphcuda.md maps
 * the switches and material keys to Bolide's.
 *
 * An HDF5 input file (miluphcuda's HDF5IO; its output files too) names its
 * datasets, so no switch is needed: /x, /v (N x 3), /m, /material_type and,
 * where present, /rho, /e, /sml, /deviatoric_stress (N x 9), /alpha_jutzi or
 * /alpha_epspor, /ep, and FRAGMENTATION's /activation_thresholds (N x
 * maximum_number_of_flaws; a particle's flaws are its leading values > 0, as
 * miluphcuda reads them) with /DIM_root_of_damage_tensile. */
#include <errno.h>
#include <getopt.h>
#include <hdf5.h>
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
#include "tasks/damage/flaws.h"

/** The columns a set of miluphcuda switches gives. */
struct milu_format {
  int density, energy, sml, jc, solid, palpha, epsalpha, frag;
};

/** Number of columns of a line (without FRAGMENTATION's thresholds). */
static int milu_columns(const struct milu_format *f) {
  return 7 + f->density + f->energy + f->sml + 1 + 2 * f->jc + 2 * f->frag + 9 * f->solid +
         2 * f->palpha + 2 * f->epsalpha;
}

/** The switches as text, for messages. */
static void milu_describe(const struct milu_format *f, char *buf, size_t len) {
  snprintf(buf, len, "x y z vx vy vz m%s%s%s mat%s%s%s%s%s%s", f->density ? " rho" : "",
           f->energy ? " e" : "", f->sml ? " sml" : "", f->jc ? " ep T" : "",
           f->frag ? " n_flaws d" : "", f->solid ? " S(9)" : "", f->palpha ? " alpha_jutzi p" : "",
           f->epsalpha ? " alpha_epspor epsilon_v" : "", f->frag ? " flaws(n_flaws)" : "");
}

/** Append particle i's n thresholds t (sorted here) to fl (offsets of
 *  particles 0..i already set); in names the particle for errors. */
static void milu_add_flaws(struct flaws *fl, size_t *cap, size_t i, double *t, size_t n,
                           const char *where) {
  for (size_t k = 0; k < n; k++)
    if (!(t[k] >= 0.0) || !isfinite(t[k]))
      error_exit("%s: activation threshold %zu is %g (must be finite and >= 0)", where, k + 1,
                 t[k]);
  for (size_t k = 1; k < n; k++) /* insertion sort: a few tens per particle */
    for (size_t j = k; j > 0 && t[j - 1] > t[j]; j--) {
      const double x = t[j];
      t[j] = t[j - 1];
      t[j - 1] = x;
    }
  const size_t first = (size_t)fl->offset[i];
  if (first + n > *cap) {
    *cap = 2 * (first + n) + 1024;
    fl->eps = realloc(fl->eps, *cap * sizeof(double));
    if (!fl->eps) error_exit("out of memory for the flaws");
  }
  if (n > 0) memcpy(fl->eps + first, t, n * sizeof(double)); /* (t may be NULL when n is 0) */
  fl->offset[i + 1] = (int64_t)(first + n);
}

/** The cube root of the tensile damage d of FRAGMENTATION into p. */
static void milu_set_damage(struct parts *p, size_t i, double d, const char *where) {
  if (!(d >= 0.0 && d <= 1.0))
    error_exit("%s: the cube root of the tensile damage is %g (must be in [0, 1])", where, d);
  p->dcbrt[i] = d;
  p->dmg[i] = d * d * d;
}

static void milu_usage(FILE *f) {
  fprintf(f,
          "Usage: bolide-ic import-miluphcuda FILE [options]\n"
          "Convert a miluphcuda ASCII input file (one particle per line, 3-D, SI) into\n"
          "Bolide initial conditions.  Its columns follow miluphcuda's compile-time\n"
          "switches, given here (default: a hydro run with INTEGRATE_DENSITY and\n"
          "INTEGRATE_ENERGY: x y z vx vy vz m rho e mat):\n"
          "  -o, --output FILE   output (default: FILE with .hdf5)\n"
          "  --no-density        INTEGRATE_DENSITY 0: no rho column\n"
          "  --no-energy         INTEGRATE_ENERGY 0: no e column\n"
          "  --sml               READ_INITIAL_SML_FROM_PARTICLE_FILE 1: an sml column\n"
          "  --jc-plasticity     JC_PLASTICITY 1: ep and T columns\n"
          "  --solid             SOLID 1: the deviatoric stress, 9 columns\n"
          "  --palpha            PALPHA_POROSITY 1: alpha_jutzi and p columns\n"
          "  --epsalpha          EPSALPHA_POROSITY 1: alpha_epspor and epsilon_v columns\n"
          "  --fragmentation     FRAGMENTATION 1: n_flaws and d (the cube root of the\n"
          "                      tensile damage) after mat (and ep T), the n_flaws\n"
          "                      activation thresholds at the end of the line\n"
          "  -h, --help          this help\n"
          "The flaws become Bolide's FlawThresholds and FlawOffsets (sorted per particle).\n"
          "An HDF5 input file (miluphcuda's HDF5IO) needs no switches: its datasets /x, /v,\n"
          "/m, /material_type and, where present, /rho, /e, /sml, /deviatoric_stress,\n"
          "/alpha_jutzi or /alpha_epspor, /ep, /activation_thresholds (a particle's leading\n"
          "values > 0) and /DIM_root_of_damage_tensile are read.\n"
          "The switches and material keys in Bolide's terms: theory/miluphcuda.md.\n");
}

/** Read miluphcuda's ASCII input file (columns after the switches fmt). */
static void milu_read_ascii(const char *in, const struct milu_format *fmtp, struct parts *p,
                            struct flaws *fl, char *desc, size_t len) {
  const struct milu_format fmt = *fmtp;
  FILE *f = fopen(in, "r");
  if (!f) error_exit("%s: cannot open: %s", in, strerror(errno));
  const int ncol = milu_columns(&fmt);
  milu_describe(&fmt, desc, len);
  parts_alloc(p, 1024);
  p->count = 0;
  char *line = NULL;
  size_t cap = 0, vcap = 64, fcap = 0, ocap = 1024;
  long lineno = 0;
  double *v = malloc(vcap * sizeof *v);
  if (fmt.frag) {
    fl->offset = calloc(ocap, sizeof *fl->offset);
    if (!fl->offset) error_exit("out of memory for the flaws");
  }
  if (!v) error_exit("out of memory");
  while (getline(&line, &cap, f) > 0) {
    lineno++;
    char *s = line, *end;
    while (*s == ' ' || *s == '\t') s++;
    if (*s == '#' || *s == '\n' || *s == '\0') continue;
    int n = 0;
    for (;;) {
      while (*s == ' ' || *s == '\t') s++;
      if (*s == '\n' || *s == '\r' || *s == '\0') break;
      const double x = strtod(s, &end);
      if (end == s || !isfinite(x))
        error_exit("%s:%ld: column %d: not a finite number ('%.20s')", in, lineno, n + 1, s);
      if ((size_t)n == vcap) {
        v = realloc(v, (vcap *= 2) * sizeof *v);
        if (!v) error_exit("out of memory");
      }
      v[n++] = x;
      s = end;
    }
    /* FRAGMENTATION: n_flaws after the material (and ep T) */
    const int kf = 7 + fmt.density + fmt.energy + fmt.sml + 1 + 2 * fmt.jc;
    double nf = 0;
    if (fmt.frag && n > kf) {
      nf = v[kf];
      if (nf < 0 || nf != floor(nf) || nf > 1e6)
        error_exit("%s:%ld: number of flaws %g must be an integer >= 0", in, lineno, nf);
    }
    if (n != ncol + (int)nf)
      error_exit("%s:%ld: %d columns, expected %d for these switches (%s; see --help)", in, lineno,
                 n, ncol + (int)nf, desc);
    const size_t i = p->count;
    if (i + 1 > p->capacity) parts_reserve(p, 2 * p->capacity);
    p->count = i + 1;
    int k = 0;
    p->x[i] = v[k++], p->y[i] = v[k++], p->z[i] = v[k++];
    p->vx[i] = v[k++], p->vy[i] = v[k++], p->vz[i] = v[k++];
    p->m[i] = v[k++];
    if (!(p->m[i] > 0)) error_exit("%s:%ld: mass %g must be positive", in, lineno, p->m[i]);
    p->rho[i] = fmt.density ? v[k++] : 0.0;
    if (fmt.density && !(p->rho[i] > 0))
      error_exit("%s:%ld: density %g must be positive", in, lineno, p->rho[i]);
    p->u[i] = fmt.energy ? v[k++] : 0.0;
    if (fmt.sml) {
      if (!(v[k] > 0)) error_exit("%s:%ld: sml %g must be positive", in, lineno, v[k]);
      p->h[i] = v[k++] / kernel_gamma;
    } else {
      p->h[i] = KERNEL_ETA_DEFAULT * cbrt(p->m[i] / p->rho[i]);
    }
    const double mat = v[k++];
    if (mat < 0 || mat != floor(mat) || mat > 2147483647.0)
      error_exit("%s:%ld: material id %g must be an integer >= 0", in, lineno, mat);
    p->mat[i] = (int32_t)mat;
    if (fmt.jc) {
      p->eps_p[i] = v[k++];
      k++; /* T: Bolide's temperature follows from the EOS and u */
    }
    char where[4200];
    snprintf(where, sizeof where, "%s:%ld", in, lineno);
    if (fmt.frag) {
      k++; /* n_flaws, read above */
      milu_set_damage(p, i, v[k++], where);
      if (i + 2 > ocap) {
        fl->offset = realloc(fl->offset, (ocap *= 2) * sizeof *fl->offset);
        if (!fl->offset) error_exit("out of memory for the flaws");
      }
      milu_add_flaws(fl, &fcap, i, v + ncol, (size_t)nf, where);
    }
    if (fmt.solid) {
      const double *S = v + k; /* 3 x 3, row by row */
      p->Sxx[i] = S[0], p->Sxy[i] = 0.5 * (S[1] + S[3]), p->Sxz[i] = 0.5 * (S[2] + S[6]);
      p->Syy[i] = S[4], p->Syz[i] = 0.5 * (S[5] + S[7]), p->Szz[i] = S[8];
      k += 9;
    }
    p->alpha[i] = 1.0;
    if (fmt.palpha) {
      p->alpha[i] = v[k];
      k += 2; /* p: miluphcuda's previous pressure, recomputed by Bolide */
    }
    if (fmt.epsalpha) {
      p->alpha[i] = v[k];
      k += 2; /* epsilon_v: starts at 0 in Bolide */
    }
    if (!(p->alpha[i] >= 1.0))
      error_exit("%s:%ld: distention %g must be >= 1", in, lineno, p->alpha[i]);
    p->id[i] = (int64_t)i + 1;
  }
  free(line);
  free(v);
  fclose(f);
  if (p->count == 0) error_exit("%s: no particles", in);
  if (fmt.frag) fl->n_parts = p->count;
}

/** Dataset `name` of miluphcuda's HDF5 file as n x ncomp doubles (HDF5
 *  converts integer datasets); NULL when absent and not required. */
static double *milu_h5_read(hid_t f, const char *in, const char *name, size_t n, int ncomp,
                            int required) {
  if (H5Lexists(f, name, H5P_DEFAULT) <= 0) {
    if (required) error_exit("%s: no dataset %s (a miluphcuda HDF5 input file has it)", in, name);
    return NULL;
  }
  const hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  if (d < 0) error_exit("%s: cannot open dataset %s", in, name);
  const hid_t sp = H5Dget_space(d);
  hsize_t dims[2] = {0, 1};
  const int nd = H5Sget_simple_extent_ndims(sp);
  if (nd < 1 || nd > 2) error_exit("%s: %s has %d dimensions, expected 1 or 2", in, name, nd);
  H5Sget_simple_extent_dims(sp, dims, NULL);
  H5Sclose(sp);
  if (dims[0] != n || (nd == 2 ? dims[1] : 1) != (hsize_t)ncomp)
    error_exit("%s: %s has shape %llu x %llu, expected %zu x %d", in, name,
               (unsigned long long)dims[0], (unsigned long long)(nd == 2 ? dims[1] : 1), n, ncomp);
  double *buf = malloc(n * (size_t)ncomp * sizeof *buf + 1);
  if (!buf) error_exit("%s: out of memory for %s", in, name);
  if (H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0)
    error_exit("%s: cannot read %s as numbers", in, name);
  H5Dclose(d);
  for (size_t i = 0; i < n * (size_t)ncomp; i++)
    if (!isfinite(buf[i]))
      error_exit("%s: %s of particle %zu: not a finite number", in, name, i / (size_t)ncomp);
  return buf;
}

/** Whether file `in` starts with HDF5's signature. */
static int milu_is_hdf5(const char *in) {
  static const unsigned char sig[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  unsigned char b[8];
  FILE *f = fopen(in, "rb");
  if (!f) return 0; /* the ASCII reader says why */
  const int yes = fread(b, 1, 8, f) == 8 && memcmp(b, sig, 8) == 0;
  fclose(f);
  return yes;
}

/** Read miluphcuda's HDF5 input file into p; desc gets the datasets read. */
static void milu_read_hdf5(const char *in, struct parts *p, struct flaws *fl, char *desc,
                           size_t len) {
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  const hid_t f = H5Fopen(in, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) error_exit("%s: cannot open as HDF5", in);
  if (H5Lexists(f, "/x", H5P_DEFAULT) <= 0)
    error_exit("%s: an HDF5 file without /x: not a miluphcuda input file", in);
  const hid_t d = H5Dopen2(f, "/x", H5P_DEFAULT);
  const hid_t sp = H5Dget_space(d);
  hsize_t dims[2] = {0, 0};
  if (H5Sget_simple_extent_ndims(sp) != 2) error_exit("%s: /x is not N x 3", in);
  H5Sget_simple_extent_dims(sp, dims, NULL);
  H5Sclose(sp);
  H5Dclose(d);
  if (dims[1] != 3)
    error_exit("%s: /x is N x %llu: only 3-D files (DIM 3)", in, (unsigned long long)dims[1]);
  const size_t n = dims[0];
  if (n == 0) error_exit("%s: no particles", in);
  double *x = milu_h5_read(f, in, "/x", n, 3, 1), *v = milu_h5_read(f, in, "/v", n, 3, 1);
  double *m = milu_h5_read(f, in, "/m", n, 1, 1);
  double *mat = milu_h5_read(f, in, "/material_type", n, 1, 1);
  double *rho = milu_h5_read(f, in, "/rho", n, 1, 0), *e = milu_h5_read(f, in, "/e", n, 1, 0);
  double *sml = milu_h5_read(f, in, "/sml", n, 1, 0);
  double *S = milu_h5_read(f, in, "/deviatoric_stress", n, 9, 0);
  double *aj = milu_h5_read(f, in, "/alpha_jutzi", n, 1, 0);
  double *ae = aj ? NULL : milu_h5_read(f, in, "/alpha_epspor", n, 1, 0);
  double *ep = milu_h5_read(f, in, "/ep", n, 1, 0);
  if (!rho && !sml) error_exit("%s: neither /rho nor /sml: h cannot be set", in);
  /* FRAGMENTATION: N x maxnof thresholds, zero-padded */
  double *at = NULL, *dr = NULL;
  int maxnof = 0;
  if (H5Lexists(f, "/activation_thresholds", H5P_DEFAULT) > 0) {
    const hid_t da = H5Dopen2(f, "/activation_thresholds", H5P_DEFAULT);
    const hid_t sa = H5Dget_space(da);
    hsize_t ad[2] = {0, 0};
    if (H5Sget_simple_extent_ndims(sa) != 2)
      error_exit("%s: /activation_thresholds is not N x M", in);
    H5Sget_simple_extent_dims(sa, ad, NULL);
    H5Sclose(sa);
    H5Dclose(da);
    if (ad[1] > 1000000)
      error_exit("%s: /activation_thresholds has %llu columns", in, (unsigned long long)ad[1]);
    maxnof = (int)ad[1];
    at = milu_h5_read(f, in, "/activation_thresholds", n, maxnof, 1);
    dr = milu_h5_read(f, in, "/DIM_root_of_damage_tensile", n, 1, 0);
  }
  H5Fclose(f);
  snprintf(desc, len, "HDF5: x v m material_type%s%s%s%s%s%s%s%s", rho ? " rho" : "", e ? " e" : "",
           sml ? " sml" : "", S ? " deviatoric_stress" : "",
           aj   ? " alpha_jutzi"
           : ae ? " alpha_epspor"
                : "",
           ep ? " ep" : "", at ? " activation_thresholds" : "",
           dr ? " DIM_root_of_damage_tensile" : "");
  if (at) {
    fl->n_parts = n;
    fl->offset = calloc(n + 1, sizeof *fl->offset);
    if (!fl->offset) error_exit("out of memory for the flaws");
  }
  size_t fcap = 0;
  parts_alloc(p, n);
  p->count = n;
  for (size_t i = 0; i < n; i++) {
    p->x[i] = x[3 * i], p->y[i] = x[3 * i + 1], p->z[i] = x[3 * i + 2];
    p->vx[i] = v[3 * i], p->vy[i] = v[3 * i + 1], p->vz[i] = v[3 * i + 2];
    p->m[i] = m[i];
    if (!(m[i] > 0)) error_exit("%s: particle %zu: mass %g must be positive", in, i, m[i]);
    p->rho[i] = rho ? rho[i] : 0.0;
    if (rho && !(rho[i] > 0))
      error_exit("%s: particle %zu: density %g must be positive", in, i, rho[i]);
    p->u[i] = e ? e[i] : 0.0;
    if (sml) {
      if (!(sml[i] > 0)) error_exit("%s: particle %zu: sml %g must be positive", in, i, sml[i]);
      p->h[i] = sml[i] / kernel_gamma;
    } else {
      p->h[i] = KERNEL_ETA_DEFAULT * cbrt(m[i] / rho[i]);
    }
    if (mat[i] < 0 || mat[i] != floor(mat[i]) || mat[i] > 2147483647.0)
      error_exit(
          "%s: particle %zu: material_type %g must be an integer >= 0 (miluphcuda's "
          "ignored (-1) and accreted (-2) particles are not imported)",
          in, i, mat[i]);
    p->mat[i] = (int32_t)mat[i];
    if (ep) p->eps_p[i] = ep[i];
    if (S) {
      const double *s9 = S + 9 * i; /* 3 x 3, row by row */
      p->Sxx[i] = s9[0], p->Sxy[i] = 0.5 * (s9[1] + s9[3]), p->Sxz[i] = 0.5 * (s9[2] + s9[6]);
      p->Syy[i] = s9[4], p->Syz[i] = 0.5 * (s9[5] + s9[7]), p->Szz[i] = s9[8];
    }
    p->alpha[i] = aj ? aj[i] : ae ? ae[i] : 1.0;
    if (!(p->alpha[i] >= 1.0))
      error_exit("%s: particle %zu: distention %g must be >= 1", in, i, p->alpha[i]);
    p->id[i] = (int64_t)i + 1;
    if (at) {
      char where[4200];
      snprintf(where, sizeof where, "%s: particle %zu", in, i);
      double *row = at + (size_t)maxnof * i;
      size_t nof = 0; /* miluphcuda: the leading values > 0 */
      while ((int)nof < maxnof && row[nof] > 0) nof++;
      milu_add_flaws(fl, &fcap, i, row, nof, where);
      if (dr) milu_set_damage(p, i, dr[i], where);
    }
  }
  free(x), free(v), free(m), free(mat), free(rho), free(e), free(sml), free(S), free(aj), free(ae),
      free(ep), free(at), free(dr);
}

int icgen_miluphcuda_main(int argc, char **argv) {
  struct milu_format fmt = {1, 1, 0, 0, 0, 0, 0, 0};
  const char *out = NULL;
  enum { O_NODENS = 300, O_NOENER, O_SML, O_JC, O_SOLID, O_PALPHA, O_EPSALPHA, O_FRAG };
  static const struct option opts[] = {{"output", required_argument, NULL, 'o'},
                                       {"no-density", no_argument, NULL, O_NODENS},
                                       {"no-energy", no_argument, NULL, O_NOENER},
                                       {"sml", no_argument, NULL, O_SML},
                                       {"jc-plasticity", no_argument, NULL, O_JC},
                                       {"solid", no_argument, NULL, O_SOLID},
                                       {"palpha", no_argument, NULL, O_PALPHA},
                                       {"epsalpha", no_argument, NULL, O_EPSALPHA},
                                       {"fragmentation", no_argument, NULL, O_FRAG},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  int c;
  opterr = 0;
  optind = 1;
  while ((c = getopt_long(argc, argv, "o:h", opts, NULL)) != -1) {
    switch (c) {
      case 'o':
        out = optarg;
        break;
      case O_NODENS:
        fmt.density = 0;
        break;
      case O_NOENER:
        fmt.energy = 0;
        break;
      case O_SML:
        fmt.sml = 1;
        break;
      case O_JC:
        fmt.jc = 1;
        break;
      case O_SOLID:
        fmt.solid = 1;
        break;
      case O_PALPHA:
        fmt.palpha = 1;
        break;
      case O_EPSALPHA:
        fmt.epsalpha = 1;
        break;
      case O_FRAG:
        fmt.frag = 1;
        break;
      case 'h':
        milu_usage(stdout);
        return 0;
      default:
        error_exit("import-miluphcuda: unknown option '%s' (see --help)", argv[optind - 1]);
    }
  }
  if (optind != argc - 1) error_exit("import-miluphcuda: expected one input FILE (see --help)");
  if (!fmt.sml && !fmt.density)
    error_exit("import-miluphcuda: without an sml or a rho column h cannot be set: give --sml");
  const char *in = argv[optind];
  char outbuf[4096];
  if (!out) {
    const char *dot = strrchr(in, '.'), *slash = strrchr(in, '/');
    const size_t stem = dot && (!slash || dot > slash) ? (size_t)(dot - in) : strlen(in);
    snprintf(outbuf, sizeof outbuf, "%.*s.hdf5", (int)stem, in);
    out = outbuf;
  }
  char desc[256];
  struct parts p;
  struct flaws fl;
  memset(&fl, 0, sizeof fl);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  if (milu_is_hdf5(in)) {
    milu_read_hdf5(in, &p, &fl, desc, sizeof desc);
  } else {
    milu_read_ascii(in, &fmt, &p, &fl, desc, sizeof desc);
  }

  /* the engine's open box is [0, L]^3: the particles' centre at its centre */
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < p.count; i++) {
    const double x[3] = {p.x[i], p.y[i], p.z[i]};
    for (int d = 0; d < 3; d++) lo[d] = fmin(lo[d], x[d]), hi[d] = fmax(hi[d], x[d]);
  }
  double ext = 0;
  for (int d = 0; d < 3; d++) ext = fmax(ext, hi[d] - lo[d]);
  const double L = fmax(2.0 * ext, 1e-300);
  for (size_t i = 0; i < p.count; i++) {
    p.x[i] += 0.5 * L - 0.5 * (lo[0] + hi[0]);
    p.y[i] += 0.5 * L - 0.5 * (lo[1] + hi[1]);
    p.z[i] += 0.5 * L - 0.5 * (lo[2] + hi[2]);
  }
  char command[4096] = "bolide-ic";
  for (int a = 0; a < argc; a++) {
    strncat(command, " ", sizeof command - strlen(command) - 1);
    strncat(command, argv[a], sizeof command - strlen(command) - 1);
  }
  struct unit_system si;
  units_init_si(&si);
  struct snapshot_meta meta = {.time = 0,
                               .periodic = 0,
                               .ic = 1,
                               .run_name = "import-miluphcuda",
                               .command = command,
                               .hydro = 1};
  for (int d = 0; d < 3; d++) meta.box_size[d] = L;
  snapshot_write(out, &meta, &p, &si, 0);
  if (fl.offset) {
    flaws_io_write_file(out, &fl);
    printf("bolide-ic import-miluphcuda: %lld flaws (FlawThresholds, FlawOffsets)\n",
           (long long)fl.offset[p.count]);
    flaws_free(&fl);
  }
  printf("bolide-ic import-miluphcuda: %zu particles of %s (%s) written to %s\n", p.count, in, desc,
         out);
  parts_free(&p);
  return 0;
}
