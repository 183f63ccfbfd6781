/* bolide: run a simulation from a YAML parameter file. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "engine.h"
#include "error.h"
#include "params.h"
#include "version.h"

static void usage(FILE *f) {
  fprintf(f,
          "Usage: bolide [OPTIONS] PARAMS.yml\n"
          "Run a smoothed particle hydrodynamics simulation of colliding bodies.\n"
          "\n"
          "  -t, --threads N       CPU worker threads (default: every core this process may use)\n"
          "  -n, --steps N         stop after N steps (0: read the ICs, write the t = 0\n"
          "                        snapshot and exit)\n"
          "  -P, --param S:K:V     override parameter Section:key with value V (repeatable)\n"
          "      --check           validate the parameters, materials and initial conditions,\n"
          "                        then exit\n"
          "      --gpu, --no-gpu   use a GPU when one is present (default) / never\n"
          "      --restart         resume from the newest restart file\n"
          "      --param-reference print the documented reference parameter file and exit\n"
          "  -v, --verbose         more output (repeat for more)\n"
          "  -h, --help            this help\n"
          "  -V, --version         version and build configuration\n"
          "\n"
          "Every key of PARAMS.yml is documented in examples/parameters.yml.\n");
}

static void version(void) {
  printf("bolide %s (git %s)\n", PACKAGE_VERSION, BOLIDE_GIT_HASH);
  printf("configured with: %s\n", BOLIDE_CONFIGURE_ARGS);
  printf("compiler: %s\n", BOLIDE_CC_VERSION);
  printf("kernel: %s\n", BOLIDE_KERNEL_NAME);
#ifdef HAVE_CUDA
  printf("CUDA: yes\n");
#else
  printf("CUDA: no\n");
#endif
}

/** Parse a non-negative integer option or stop. */
static long parse_count(const char *opt, const char *s) {
  char *end;
  long v = strtol(s, &end, 10);
  if (*s == '\0' || *end != '\0' || v < 0) error_exit("option %s expects a non-negative integer, not '%s'", opt, s);
  return v;
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  struct engine_options opt;
  memset(&opt, 0, sizeof opt);
  opt.nr_threads = 0;
  opt.max_steps = -1;
  opt.use_gpu = 1;
  char **overrides = calloc((size_t)argc, sizeof(char *));
  int n_overrides = 0;

  enum { OPT_CHECK = 1000, OPT_GPU, OPT_NO_GPU, OPT_RESTART, OPT_REFERENCE };
  static const struct option longopts[] = {
      {"threads", required_argument, NULL, 't'}, {"steps", required_argument, NULL, 'n'},
      {"param", required_argument, NULL, 'P'},   {"check", no_argument, NULL, OPT_CHECK},
      {"gpu", no_argument, NULL, OPT_GPU},       {"no-gpu", no_argument, NULL, OPT_NO_GPU},
      {"restart", no_argument, NULL, OPT_RESTART},
      {"param-reference", no_argument, NULL, OPT_REFERENCE},
      {"verbose", no_argument, NULL, 'v'},       {"help", no_argument, NULL, 'h'},
      {"version", no_argument, NULL, 'V'},       {NULL, 0, NULL, 0}};
  int c;
  opterr = 0;
  while ((c = getopt_long(argc, argv, ":t:n:P:vhV", longopts, NULL)) != -1) {
    switch (c) {
      case 't':
        opt.nr_threads = (int)parse_count("--threads", optarg);
        if (opt.nr_threads < 1) error_exit("option --threads expects at least 1");
        break;
      case 'n': opt.max_steps = parse_count("--steps", optarg); break;
      case 'P': overrides[n_overrides++] = optarg; break;
      case 'v': error_verbosity++; break;
      case OPT_CHECK: opt.check_only = 1; break;
      case OPT_GPU: opt.use_gpu = 2; break;
      case OPT_NO_GPU: opt.use_gpu = 0; break;
      case OPT_RESTART: opt.restart = 1; break;
      case OPT_REFERENCE: params_write_reference(stdout); free(overrides); return 0;
      case 'h': usage(stdout); free(overrides); return 0;
      case 'V': version(); free(overrides); return 0;
      case ':': error_exit("option %s needs a value (see --help)", argv[optind - 1]);
      default: error_exit("unknown option '%s' (see --help)", argv[optind - 1]);
    }
  }
  if (optind >= argc) error_exit("no parameter file given (usage: bolide [OPTIONS] PARAMS.yml; see --help)");
  if (optind + 1 < argc) error_exit("unexpected argument '%s' after the parameter file", argv[optind + 1]);

  struct params *params = params_read(argv[optind], n_overrides, overrides);
  struct engine e;
  engine_init(&e, params, &opt);
  if (!opt.check_only) engine_run(&e);
  engine_clean(&e);
  params_free(params);
  free(overrides);
  return 0;
}
