/* bolide-eos: pressure, sound speed (and temperature) of one material of a
 * material library over a grid of density and specific internal energy, or
 * at (density, energy) pairs read from standard input.  SI units. */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "src/error.h"
#include "src/materials/material.h"
#include "src/paths.h"
#include "src/version.h"

static void usage(FILE *f) {
  fprintf(f,
          "Usage: bolide-eos [options] MATERIALS.yml NAME\n"
          "Print density, specific internal energy, pressure, sound speed (and temperature\n"
          "where the EOS defines one) of material NAME of the library MATERIALS.yml, SI units,\n"
          "under one header line.\n"
          "  --rho-min X, --rho-max X  density range (default 0.5 and 2 times rho0)\n"
          "  --nrho N                  number of densities (default 16)\n"
          "  --u-min X, --u-max X      energy range in J/kg (default 0 and 2e7)\n"
          "  --nu N                    number of energies (default 5)\n"
          "  --log                     log-spaced grids (minima must then be positive)\n"
          "  --stdin                   read 'density energy' pairs from standard input instead\n"
          "  --plot FILE.png           also draw P and c_s against density (plot_eos.py beside\n"
          "                            the program, or tools/ of the source tree; run with\n"
          "                            $PYTHON, the build's .venv python or python3)\n"
          "  --keys                    list every EOS and material key and exit\n"
          "  -h, --help, --version\n");
}

/** A positive integer option. */
static int arg_int(const char *opt, const char *s) {
  char *end;
  errno = 0;
  const long v = strtol(s, &end, 10);
  if (errno || end == s || *end || v < 1 || v > 100000000)
    error_exit("option %s: '%s' is not a positive integer", opt, s);
  return (int)v;
}

/** A real option. */
static double arg_real(const char *opt, const char *s) {
  char *end;
  errno = 0;
  const double v = strtod(s, &end);
  if (errno || end == s || *end || !isfinite(v))
    error_exit("option %s: '%s' is not a number", opt, s);
  return v;
}

/** Node k of n between lo and hi (linear or logarithmic). */
static double grid(double lo, double hi, int k, int n, int lg) {
  if (n == 1) return lo;
  const double t = (double)k / (n - 1);
  return lg ? lo * pow(hi / lo, t) : lo + t * (hi - lo);
}

/** One output row. */
static void row(FILE *f, const struct material *mat, double rho, double u, int with_T) {
  double P, cs;
  material_eos(mat, rho, u, &P, &cs);
  if (with_T)
    fprintf(f, "%.10g %.10g %.10g %.10g %.10g\n", rho, u, P, cs, material_temperature(mat, rho, u));
  else
    fprintf(f, "%.10g %.10g %.10g %.10g\n", rho, u, P, cs);
}

/** Stop with one line unless a PNG can be written at path (plot_eos.py
 *  writes PATH.tmp.png and renames it). */
static void plot_check_target(const char *path) {
  char dir[4096];
  snprintf(dir, sizeof dir, "%s", path);
  char *slash = strrchr(dir, '/');
  if (!slash)
    snprintf(dir, sizeof dir, ".");
  else if (slash == dir)
    dir[1] = '\0';
  else
    *slash = '\0';
  struct stat st;
  if (!path[0] || path[strlen(path) - 1] == '/') error_exit("--plot %s: not a file name", path);
  if (stat(dir, &st) != 0) error_exit("--plot %s: %s: %s", path, dir, strerror(errno));
  if (!S_ISDIR(st.st_mode)) error_exit("--plot %s: %s: %s", path, dir, strerror(ENOTDIR));
  if (access(dir, W_OK) != 0) error_exit("--plot %s: %s: %s", path, dir, strerror(errno));
  if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
    error_exit("--plot %s: %s", path, strerror(EISDIR));
}

/** Run PYTHON tools/plot_eos.py TABLE PNG NAME and wait for it. */
static void plot(const char *table, const char *png, const char *name) {
  const char *py = paths_python();
  /* $BOLIDE_PLOT_EOS, else plot_eos.py beside an installed bolide-eos, else
   * the source tree's tools/ (paths.h) */
  char script[4096];
  if (!paths_find(script, sizeof script, "BOLIDE_PLOT_EOS", "plot_eos.py", "tools/plot_eos.py"))
    error_exit("--plot: cannot find the plotting script (%s; set BOLIDE_PLOT_EOS)", script);
  fflush(stdout);
  const pid_t pid = fork();
  if (pid < 0) error_exit("cannot start %s: %s", py, strerror(errno));
  if (pid == 0) {
    execlp(py, py, script, table, png, name, (char *)NULL);
    fprintf(stderr, "bolide-eos: error: cannot run %s: %s\n", py, strerror(errno));
    _exit(127);
  }
  int status;
  if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    error_exit("plotting with %s %s failed", py, script);
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  double rho_min = NAN, rho_max = NAN, u_min = 0.0, u_max = 2e7;
  int nrho = 16, nu = 5, lg = 0, from_stdin = 0;
  const char *png = NULL;
  enum {
    O_RHOMIN = 256,
    O_RHOMAX,
    O_NRHO,
    O_UMIN,
    O_UMAX,
    O_NU,
    O_LOG,
    O_STDIN,
    O_PLOT,
    O_KEYS,
    O_VERSION
  };
  static const struct option opts[] = {{"rho-min", required_argument, 0, O_RHOMIN},
                                       {"rho-max", required_argument, 0, O_RHOMAX},
                                       {"nrho", required_argument, 0, O_NRHO},
                                       {"u-min", required_argument, 0, O_UMIN},
                                       {"u-max", required_argument, 0, O_UMAX},
                                       {"nu", required_argument, 0, O_NU},
                                       {"log", no_argument, 0, O_LOG},
                                       {"stdin", no_argument, 0, O_STDIN},
                                       {"plot", required_argument, 0, O_PLOT},
                                       {"keys", no_argument, 0, O_KEYS},
                                       {"help", no_argument, 0, 'h'},
                                       {"version", no_argument, 0, O_VERSION},
                                       {0, 0, 0, 0}};
  opterr = 0;
  int c;
  while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
    switch (c) {
      case O_RHOMIN:
        rho_min = arg_real("--rho-min", optarg);
        break;
      case O_RHOMAX:
        rho_max = arg_real("--rho-max", optarg);
        break;
      case O_NRHO:
        nrho = arg_int("--nrho", optarg);
        break;
      case O_UMIN:
        u_min = arg_real("--u-min", optarg);
        break;
      case O_UMAX:
        u_max = arg_real("--u-max", optarg);
        break;
      case O_NU:
        nu = arg_int("--nu", optarg);
        break;
      case O_LOG:
        lg = 1;
        break;
      case O_STDIN:
        from_stdin = 1;
        break;
      case O_PLOT:
        png = optarg;
        break;
      case O_KEYS:
        material_write_keys(stdout);
        return 0;
      case 'h':
        usage(stdout);
        return 0;
      case O_VERSION:
        bolide_version_print("bolide-eos");
        return 0;
      default:
        error_exit("unknown or incomplete option '%s' (see --help)", argv[optind - 1]);
    }
  }
  if (argc - optind != 2) error_exit("expected MATERIALS.yml and a material NAME (see --help)");
  struct material mat;
  material_from_library(&mat, argv[optind], argv[optind + 1], 0);
  if (isnan(rho_min)) rho_min = mat.rho0 > 0.0 ? 0.5 * mat.rho0 : 0.1;
  if (isnan(rho_max)) rho_max = mat.rho0 > 0.0 ? 2.0 * mat.rho0 : 10.0;
  if (!(rho_min > 0.0) || !(rho_max >= rho_min))
    error_exit("the density range must satisfy 0 < rho-min <= rho-max (got %g, %g)", rho_min,
               rho_max);
  if (!(u_max >= u_min) || (lg && !(u_min > 0.0)))
    error_exit(
        "the energy range must satisfy u-min <= u-max, with u-min > 0 for --log (got %g, %g)",
        u_min, u_max);
  const int with_T = material_has_temperature(&mat);

  /* with --plot the table goes to a temporary file as well; the PNG's folder
   * is checked first (the plotting script would fail at the end) */
  if (png) plot_check_target(png);
  FILE *tmp = NULL;
  char tmpname[] = "/tmp/bolide-eos-XXXXXX";
  if (png) {
    const int fd = mkstemp(tmpname);
    if (fd < 0 || !(tmp = fdopen(fd, "w"))) error_exit("cannot create a temporary file");
    error_register_tmpfile(tmpname);
  }
  FILE *outs[2] = {stdout, tmp};
  for (int o = 0; o < (tmp ? 2 : 1); o++)
    fprintf(outs[o], "density specific_internal_energy pressure sound_speed%s\n",
            with_T ? " temperature" : "");
  if (from_stdin) {
    char *line = NULL;
    size_t cap = 0;
    ssize_t len;
    int lineno = 0;
    while ((len = getline(&line, &cap, stdin)) >= 0) {
      lineno++;
      double rho, u;
      char extra;
      /* a NUL would end the text early: the line would be skipped or cut */
      if (memchr(line, '\0', (size_t)len))
        error_exit("stdin:%d: a NUL byte in the line (not text)", lineno);
      if (line[strspn(line, " \t\r\n")] == 0 || line[strspn(line, " \t")] == '#') continue;
      if (sscanf(line, "%lf %lf %c", &rho, &u, &extra) != 2 || !isfinite(rho) || !isfinite(u) ||
          !(rho > 0.0))
        error_exit("stdin:%d: expected 'density energy' with density > 0", lineno);
      for (int o = 0; o < (tmp ? 2 : 1); o++) row(outs[o], &mat, rho, u, with_T);
    }
    if (ferror(stdin)) error_exit("stdin:%d: cannot read: %s", lineno + 1, strerror(errno));
    free(line);
  } else {
    for (int j = 0; j < nu; j++)
      for (int i = 0; i < nrho; i++) {
        const double rho = grid(rho_min, rho_max, i, nrho, lg), u = grid(u_min, u_max, j, nu, lg);
        for (int o = 0; o < (tmp ? 2 : 1); o++) row(outs[o], &mat, rho, u, with_T);
      }
  }
  if (fflush(stdout) != 0) error_exit("cannot write the table: %s", strerror(errno));
  if (tmp) {
    if (fclose(tmp) != 0) error_exit("cannot write %s", tmpname);
    plot(tmpname, png, mat.name);
    unlink(tmpname);
    error_unregister_tmpfile(tmpname);
  }
  if (mat.eos_type == EOS_TABLE) {
    struct material_table t;
    material_table_init(&t);
    material_table_add(&t, &mat);
    material_table_free(&t);
  }
  return 0;
}
