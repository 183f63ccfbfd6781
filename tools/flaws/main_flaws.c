/* bolide-flaws: Weibull flaws for the brittle particles of an initial
 * condition file (Benz & Asphaug 1995; tasks/damage/flaws.h).
 *
 *   bolide-flaws IN.hdf5 OUT.hdf5 --mat ID --k K --m M [--seed S] [--volume V]
 *
 * OUT is IN plus /PartType0/FlawThresholds and /PartType0/FlawOffsets.
 * Particles of other materials keep the flaws IN already has, so a body of
 * several brittle materials takes one call per material (a different seed
 * each).  k is in m^-3 (SI), the volume of the body is the sum of m/rho of
 * its particles (IN must hold Densities) unless --volume gives it in m^3. */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "src/error.h"
#include "tasks/damage/flaws.h"
#include "src/io/ic.h"
#include "src/io/units.h"
#include "src/version.h"

/** Long options without a short form. */
enum { OPT_MAT = 256, OPT_K, OPT_M, OPT_SEED, OPT_VOLUME, OPT_VERSION };

static const struct option flawsgen_longopts[] = {
    {"mat", required_argument, NULL, OPT_MAT},       {"k", required_argument, NULL, OPT_K},
    {"m", required_argument, NULL, OPT_M},           {"seed", required_argument, NULL, OPT_SEED},
    {"volume", required_argument, NULL, OPT_VOLUME}, {"help", no_argument, NULL, 'h'},
    {"version", no_argument, NULL, OPT_VERSION},     {NULL, 0, NULL, 0}};

/** Print the usage text to f. */
static void flawsgen_usage(FILE *f) {
  fprintf(f,
          "Usage: bolide-flaws IN.hdf5 OUT.hdf5 --mat ID --k K --m M [options]\n"
          "Weibull flaws (Benz & Asphaug 1995) for the particles of material ID.\n\n"
          "  --mat ID       material id (MaterialIDs) of the brittle particles\n"
          "  --k K          Weibull k, flaws per m^3 (e.g. 5e34 for basalt)\n"
          "  --m M          Weibull m (e.g. 8)\n"
          "  --seed S       random seed (default 1)\n"
          "  --volume V     volume of the body in m^3 (default: sum of m/rho)\n"
          "  -v             more output\n"
          "  -h, --help     this help\n"
          "  --version      version\n");
}

/** Parse a positive finite number for option `name`. */
static double flawsgen_positive(const char *name, const char *s) {
  char *end;
  errno = 0;
  const double v = strtod(s, &end);
  if (end == s || *end || errno || !(v > 0.0) || !isfinite(v))
    error_exit("option --%s: '%s' is not a positive number", name, s);
  return v;
}

/** Copy file src to dst (byte for byte). */
static void flawsgen_copy(const char *src, const char *dst) {
  FILE *in = fopen(src, "rb");
  if (!in) error_exit("%s: cannot open: %s", src, strerror(errno));
  FILE *out = fopen(dst, "wb");
  if (!out) error_exit("%s: cannot create: %s", dst, strerror(errno));
  char buf[1 << 16];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, in)) > 0)
    if (fwrite(buf, 1, n, out) != n) error_exit("%s: write failed: %s", dst, strerror(errno));
  if (ferror(in)) error_exit("%s: read failed", src);
  fclose(in);
  if (fflush(out) != 0 || fsync(fileno(out)) != 0 || fclose(out) != 0)
    error_exit("%s: write failed: %s", dst, strerror(errno));
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  long long mat = -1;
  double k = NAN, m = NAN, volume = 0.0;
  unsigned long long seed = 1;
  int c;
  while ((c = getopt_long(argc, argv, "hv", flawsgen_longopts, NULL)) != -1) {
    switch (c) {
      case OPT_MAT: {
        char *end;
        mat = strtoll(optarg, &end, 10);
        if (end == optarg || *end || mat < 0 || mat > INT32_MAX)
          error_exit("option --mat: '%s' is not a material id (integer >= 0)", optarg);
        break;
      }
      case OPT_K:
        k = flawsgen_positive("k", optarg);
        break;
      case OPT_M:
        m = flawsgen_positive("m", optarg);
        break;
      case OPT_VOLUME:
        volume = flawsgen_positive("volume", optarg);
        break;
      case OPT_SEED: {
        char *end;
        errno = 0;
        seed = strtoull(optarg, &end, 0);
        if (end == optarg || *end || errno || optarg[0] == '-')
          error_exit("option --seed: '%s' is not a non-negative integer", optarg);
        break;
      }
      case 'v':
        error_verbosity++;
        break;
      case 'h':
        flawsgen_usage(stdout);
        return 0;
      case OPT_VERSION:
        bolide_version_print("bolide-flaws");
        return 0;
      default:
        error_exit("unknown option (see --help)");
    }
  }
  if (argc - optind != 2) error_exit("expected IN.hdf5 OUT.hdf5 (see --help)");
  if (mat < 0) error_exit("missing --mat ID");
  if (isnan(k)) error_exit("missing --k K (Weibull k in m^-3)");
  if (isnan(m)) error_exit("missing --m M (Weibull m)");
  const char *in = argv[optind], *outpath = argv[optind + 1];

  struct unit_system si;
  units_init_si(&si);
  struct parts p;
  ic_read(in, &si, NULL, 0, &p, NULL);
  struct flaws old;
  const int had = flaws_io_read(in, p.count, &old);

  unsigned char *brittle = error_calloc(p.count ? p.count : 1, 1, "brittle flags");
  size_t nb = 0;
  for (size_t i = 0; i < p.count; i++)
    if (p.mat[i] == mat) {
      brittle[i] = 1;
      nb++;
      if (volume == 0.0 && !(p.rho[i] > 0.0))
        error_exit("%s: particle %zu (id %lld) has no density: give --volume", in, i,
                   (long long)p.id[i]);
    }
  if (nb == 0) error_exit("%s: no particle has material id %lld", in, mat);
  const double V = volume > 0.0 ? volume : flaws_volume(p.count, p.m, p.rho, brittle);

  struct flaws f;
  const int64_t drawn = flaws_generate(p.count, brittle, k, m, V, seed, had ? &old : NULL, &f);

  char tmp[4096];
  if (snprintf(tmp, sizeof tmp, "%s.tmp", outpath) >= (int)sizeof tmp)
    error_exit("%s: file name too long", outpath);
  error_register_tmpfile(tmp);
  flawsgen_copy(in, tmp);
  flaws_io_write_file(tmp, &f);
  if (rename(tmp, outpath) != 0)
    error_exit("%s: cannot rename %s: %s", outpath, tmp, strerror(errno));
  error_unregister_tmpfile(tmp);

  const double eps_min = flaws_threshold(1, k, m, V), eps_max = flaws_threshold(drawn, k, m, V);
  printf(
      "material %lld: %zu brittle particles, volume %.6g m^3, %lld flaws (%.3f per particle; "
      "ln N = %.3f), thresholds %.4g to %.4g\n",
      mat, nb, V, (long long)drawn, (double)drawn / (double)nb, log((double)nb), eps_min, eps_max);
  printf("flaws in %s: %lld in all, %.1f MB (%.1f bytes per particle)\n", outpath,
         (long long)f.offset[f.n_parts], flaws_bytes(&f) / 1e6,
         (double)flaws_bytes(&f) / (double)(p.count ? p.count : 1));
  flaws_free(&f);
  if (had) flaws_free(&old);
  free(brittle);
  parts_free(&p);
  return 0;
}
