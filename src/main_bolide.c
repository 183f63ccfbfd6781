/* bolide: run a simulation from a YAML parameter file.
 *
 * The command line takes SWIFT's flags where Bolide has the same thing
 * (-s/--hydro, -G/--self-gravity, -t/--threads, -n/--steps, -P/--param,
 * -r/--restart, -v/--verbose N, -y/--task-dumps N, -e/--fpe, -d/--dry-run),
 * so that a SWIFT user's run scripts carry over; SWIFT's flags for physics
 * Bolide does not have stop with a line that says so (main_swift_options). */
#define _GNU_SOURCE /* feenableexcept */
#include <fenv.h>
#include <getopt.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "src/engine.h"
#include "src/engine_tasks.h" /* engine_rebuild: the cells and tasks of --partition */
#include "src/error.h"
#include "src/io/params.h"
#include "src/mpi/partition.h"
#include "src/mpi/ranks.h"
#include "src/runner.h"
#include "src/space.h"
#include "src/version.h"

static void usage(FILE *f) {
  fprintf(f,
          "Usage: bolide [OPTIONS] PARAMS.yml\n"
          "Run a smoothed particle hydrodynamics simulation of colliding bodies.\n"
          "\n"
          "Physics (SWIFT's flags; without them the parameter file decides, through\n"
          "SPH:hydro (default on) and Gravity:enabled (default off)):\n"
          "  -s, --hydro           run with hydrodynamics\n"
          "  -G, --self-gravity    run with self-gravity; as in SWIFT, once -s or -G is\n"
          "                        given the physics not named is off (-G alone: a\n"
          "                        gravity-only run; -s -G: both)\n"
          "\n"
          "Control:\n"
          "  -t, --threads N       CPU worker threads (default: every core this process may use)\n"
          "  -n, --steps N         stop after N steps (0: read the ICs, write the t = 0\n"
          "                        snapshot and exit)\n"
          "  -P, --param S:K:V     override parameter Section:key with value V (repeatable)\n"
          "  -r, --restart         resume from the newest restart file\n"
          "  -y, --task-dumps N    write a task timeline every N steps (Scheduler:dump_tasks)\n"
          "  -e, --fpe             stop at the first floating-point exception (division by\n"
          "                        zero, invalid operation, overflow): for debugging\n"
          "  -d, --dry-run, --check\n"
          "                        validate the parameters, materials and initial conditions,\n"
          "                        then exit\n"
          "      --gpu, --no-gpu   use a GPU when one is present (default) / never\n"
          "      --param-reference print the documented reference parameter file and exit\n"
          "      --partition N     report the domain decomposition of the top-level cells over\n"
          "                        N ranks (0: the ranks of mpirun) and exit: imbalance, edge\n"
          "                        cut, halo; costs estimated from the particles, or measured\n"
          "                        over the steps of -n N > 0 (theory/mpi.md)\n"
          "      --partition-counts FILE\n"
          "                        with --partition N: partition the top-level cells listed\n"
          "                        in FILE (per-cell particle counts, tools/bench/\n"
          "                        impact_counts.py) instead of a run's, no PARAMS.yml;\n"
          "                        adds the particles each rank receives per exchange\n"
          "      --partition-method M\n"
          "                        metis (default when built with METIS), morton, slabs, or\n"
          "                        all (the three, one line each)\n"
          "  -v, --verbose [N]     more output: -v, -vv, or a level (-v 2, --verbose=2)\n"
          "  -h, --help            this help\n"
          "  -V, --version         version and build configuration\n"
          "\n"
          "Accepted for SWIFT's run scripts, without effect: -a/--pin (workers are always\n"
          "pinned), -D/--drift-all (every particle is drifted every step), --limiter,\n"
          "--sync (the time-step limiter and the wake-up of the particles it shortens are\n"
          "always on with TimeIntegration:global_step: false, set by\n"
          "TimeIntegration:max_bin_ratio; the global step needs neither),\n"
          "-M/--multipole-reconstruction (multipoles are rebuilt every\n"
          "step unless Gravity:reuse_steps > 0), --temperature, --interleave,\n"
          "--nointerleave, --pool-threads N, -T/--timers N (timers are printed at the end).\n"
          "SWIFT's options for physics or outputs Bolide does not have (cosmology, cooling,\n"
          "stars, black holes, external potentials, ...) stop with an error naming them.\n"
          "\n"
          "Every key of PARAMS.yml is documented in examples/parameters.yml; a SWIFT\n"
          "parameter file runs as it is (keys without an effect in Bolide get a note).\n");
}

/** Top-level cells with particles. */
static int main_nonempty(const struct partition_graph *g) {
  int n = 0;
  for (int c = 0; c < g->nr_cells; c++) n += g->count[c] > 0;
  return n;
}

static void version(void) {
  bolide_version_print("bolide");
}

/** Parse a non-negative integer option or stop. */
static long parse_count(const char *opt, const char *s) {
  char *end;
  long v = strtol(s, &end, 10);
  if (*s == '\0' || *end != '\0' || v < 0)
    error_exit("option %s expects a non-negative integer, not '%s'", opt, s);
  return v;
}

/** 1 if s is a non-empty string of decimal digits. */
static int all_digits(const char *s) {
  return s[0] && strspn(s, "0123456789") == strlen(s);
}

/** The message of a SIGFPE under -e (async-signal-safe: write and _exit). */
static void main_fpe_handler(int sig, siginfo_t *info, void *ctx) {
  (void)sig;
  (void)ctx;
  const char *what = info->si_code == FPE_FLTDIV   ? "division by zero"
                     : info->si_code == FPE_FLTINV ? "invalid operation (a NaN was made)"
                     : info->si_code == FPE_FLTOVF ? "overflow"
                     : info->si_code == FPE_INTDIV ? "integer division by zero"
                                                   : "arithmetic error";
  static const char head[] = "bolide: error: floating-point exception under -e/--fpe: ";
  static const char tail[] = " (run it under gdb to see where)\n";
  ssize_t rc = write(STDERR_FILENO, head, sizeof head - 1);
  rc = write(STDERR_FILENO, what, strlen(what));
  rc = write(STDERR_FILENO, tail, sizeof tail - 1);
  (void)rc;
  _exit(1);
}

/** Trap division by zero, invalid operations and overflow (SWIFT's -e). The
 *  floating-point environment is inherited by the worker threads. */
static void main_enable_fpe(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_sigaction = main_fpe_handler;
  sa.sa_flags = SA_SIGINFO;
  sigaction(SIGFPE, &sa, NULL);
  if (feenableexcept(FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW) == -1)
    error_warning(
        "-e/--fpe: this machine cannot trap floating-point exceptions; carrying on without");
}

/** Long options of SWIFT's that select physics or outputs Bolide does not
 *  have, with what they are; and those accepted without effect. */
static const struct {
  const char *name; /**< long option */
  int has_arg;      /**< takes a value */
  int accepted;     /**< 1: accepted with a note; 0: stop with an error */
  const char *what; /**< meaning in SWIFT, or why it has no effect here */
} main_swift_options[] = {
    {"feedback", 0, 0, "stellar feedback"},
    {"cosmology", 0, 0, "cosmological time integration"},
    {"cooling", 0, 0, "radiative cooling"},
    {"star-formation", 0, 0, "star formation"},
    {"external-gravity", 0, 0, "an external gravitational potential"},
    {"stars", 0, 0, "star particles"},
    {"black-holes", 0, 0, "black holes"},
    {"sinks", 0, 0, "sink particles"},
    {"fof", 0, 0, "on-the-fly friends-of-friends (use bolide-fof on the snapshots)"},
    {"lightcone", 0, 0, "lightcone outputs"},
    {"velociraptor", 0, 0, "structure finding"},
    {"line-of-sight", 0, 0, "line-of-sight outputs"},
    {"csds", 0, 0, "the continuous simulation data stream"},
    {"radiation", 0, 0, "radiative transfer"},
    {"power", 0, 0, "power spectra"},
    {"quick-lyman-alpha", 0, 0, "the quick Lyman-alpha model"},
    {"eagle", 0, 0, "the EAGLE model"},
    {"flamingo", 0, 0, "the FLAMINGO model"},
    {"gear", 0, 0, "the GEAR model"},
    {"agora", 0, 0, "the AGORA model"},
    {"no-io", 0, 0, "runs without outputs"},
    {"output-params", 1, 0, "output selection files"},
    {"cpu-frequency", 1, 0, "a given CPU frequency (Bolide's clock is in seconds)"},
    {"cell-dumps", 1, 0, "cell dumps"},
    {"threadpool-dumps", 1, 0, "thread-pool dumps"},
    {"dump-tasks-threshold", 1, 0, "task dumps triggered by a time threshold (use -y N)"},
    {"pin", 0, 1, "the workers are always pinned to cores"},
    {"drift-all", 0, 1, "every particle is drifted every step"},
    {"limiter", 0, 1,
     "the time-step limiter is always on with individual time steps "
     "(TimeIntegration:max_bin_ratio); the global step needs none"},
    {"sync", 0, 1,
     "particles whose step the limiter shortens are always woken with individual time steps "
     "(TimeIntegration:max_bin_ratio); the global step needs no wake-up"},
    {"multipole-reconstruction", 0, 1,
     "the multipoles are rebuilt every step unless Gravity:reuse_steps > 0"},
    {"temperature", 0, 1, "temperatures are computed where the equation of state has one"},
    {"interleave", 0, 1, "memory placement is left to the system"},
    {"nointerleave", 0, 1, "memory placement is left to the system"},
    {"pool-threads", 1, 1, "Bolide has no separate thread pool"},
    {"timers", 1, 1, "the timers are printed at the end of the run"},
};
#define MAIN_NR_SWIFT ((int)(sizeof main_swift_options / sizeof main_swift_options[0]))
/** First getopt value of the entries of main_swift_options. */
#define MAIN_OPT_SWIFT 2000

/** SWIFT's one-letter forms of main_swift_options, in that list's names. */
static const struct {
  char letter;
  const char *name;
} main_swift_letters[] = {{'b', "feedback"},
                          {'c', "cosmology"},
                          {'C', "cooling"},
                          {'F', "star-formation"},
                          {'g', "external-gravity"},
                          {'S', "stars"},
                          {'B', "black-holes"},
                          {'k', "sinks"},
                          {'u', "fof"},
                          {'x', "velociraptor"},
                          {'R', "radiation"},
                          {'o', "output-params"},
                          {'f', "cpu-frequency"},
                          {'Y', "threadpool-dumps"},
                          {'a', "pin"},
                          {'D', "drift-all"},
                          {'M', "multipole-reconstruction"},
                          {'T', "timers"}};

/** A SWIFT option of main_swift_options (index k): a note or an error. */
static void main_swift_option(int k) {
  if (main_swift_options[k].accepted) {
    error_note("option --%s (SWIFT's) has no effect in Bolide: %s", main_swift_options[k].name,
               main_swift_options[k].what);
    return;
  }
  error_exit("option --%s is SWIFT's option for %s, which Bolide does not have (see --help)",
             main_swift_options[k].name, main_swift_options[k].what);
}

/** SWIFT writes "-v 1", "-y 4": an option letter whose value is the next
 *  word.  -v also counts when repeated (-vv), so it takes an optional value
 *  and "-v N" is joined into "-vN" here (likewise "--verbose N"). */
static void main_join_verbose(int *argc, char **argv) {
  int out = 1;
  for (int i = 1; i < *argc; i++) {
    if ((strcmp(argv[i], "-v") == 0 || strcmp(argv[i], "--verbose") == 0) && i + 1 < *argc &&
        all_digits(argv[i + 1])) {
      const size_t len = strlen(argv[i]) + strlen(argv[i + 1]) + 2;
      char *joined = error_malloc(len, "argument");
      snprintf(joined, len, "%s%s%s", argv[i], argv[i][1] == '-' ? "=" : "", argv[i + 1]);
      argv[out++] = joined; /* lives until exit */
      i++;
    } else {
      argv[out++] = argv[i];
    }
    if (strcmp(argv[i], "--") == 0)
      while (i + 1 < *argc) argv[out++] = argv[++i];
  }
  *argc = out;
  argv[out] = NULL;
}

/** --partition N: the domain decomposition of the top-level cells over N
 *  ranks (0: the ranks of mpirun), with the costs estimated after the first
 *  rebuild or measured over the steps of -n.  Rank 0 reads the initial
 *  conditions and partitions; every rank gets the assignment and says how
 *  many cells it holds. */
static int main_partition(int nr, const char *method, const struct params *params,
                          const struct engine_options *opt) {
  if (nr == 0) nr = ranks_size();
  int ncells = 0;
  int *assign = NULL;
  if (ranks_rank() == 0) {
    struct engine e;
    struct engine_options o = *opt;
    o.check_only = 0;
    o.one_rank = 1;
    const int measured = o.max_steps > 0;
    engine_init(&e, params, &o);
    if (measured)
      engine_run(&e);
    else
      engine_rebuild(&e);
    struct partition_graph g;
    partition_graph_make(&g, &e.space, &e.sched, measured);
    printf("partition: %zu particles in %d top-level cells (%d non-empty), %s costs\n",
           e.parts.count, g.nr_cells, main_nonempty(&g), measured ? "measured" : "estimated");
    const int all = strcmp(method, "all") == 0;
    for (int m = 0; m <= (int)partition_method_slabs; m++) {
      if (all ? (m == partition_method_metis && !partition_have_metis())
              : m != partition_method_parse(method))
        continue;
      struct partition p;
      partition_make(&p, &g, nr, (enum partition_method)m);
      partition_print(&p, &g, !all || error_verbosity > 0, stdout);
      if (measured) {
        /* how good the estimate is: its partition, judged by the measured costs */
        struct partition_graph ge;
        struct partition pe;
        partition_graph_make(&ge, &e.space, &e.sched, 0);
        partition_make(&pe, &ge, nr, (enum partition_method)m);
        partition_stats(&pe, &g);
        printf("partition: (the partition of the estimated costs, with the measured ones)\n");
        partition_print(&pe, &g, 0, stdout);
        partition_free(&pe);
        partition_graph_free(&ge);
      }
      if (!assign) {
        assign = p.rank;
        p.rank = NULL;
      }
      partition_free(&p);
    }
    ncells = g.nr_cells;
    partition_graph_free(&g);
    engine_clean(&e);
    fflush(stdout);
  }
  if (ranks_size() > 1) {
    /* the assignment to every rank, which counts its cells */
    ranks_bcast_ints(&ncells, 1);
    if (ranks_rank() != 0) assign = error_malloc((size_t)ncells * sizeof(int), "partition");
    ranks_bcast_ints(assign, ncells);
    int mine = 0;
    for (int c = 0; c < ncells; c++) mine += assign[c] == ranks_rank();
    int *all = error_malloc((size_t)ranks_size() * sizeof(int), "partition");
    ranks_gather_int(mine, all);
    if (ranks_rank() == 0 && nr == ranks_size())
      for (int r = 0; r < ranks_size(); r++)
        printf("partition: rank %d of %d holds %d top-level cells\n", r, ranks_size(), all[r]);
    free(all);
  }
  free(assign);
  return 0;
}

/** --partition N --partition-counts FILE: the partition of the cells a
 *  counts file lists (theory/mpi.md, "Scaling on paper"), with what each
 *  rank receives per exchange. */
static int main_partition_counts(int nr, const char *method, const char *file) {
  if (nr == 0) nr = ranks_size();
  if (ranks_rank() != 0) return 0;
  struct partition_counts pc;
  partition_counts_read(&pc, file);
  struct partition_graph g;
  partition_graph_counts(&g, &pc);
  printf(
      "partition: %zu particles in %d non-empty top-level cells of %dx%dx%d, %s: estimated "
      "costs (%d pair loops, %d cell tasks)\n",
      pc.particles, g.nr_cells, g.cdim[0], g.cdim[1], g.cdim[2], file, pc.loops, pc.cell_tasks);
  const int all = strcmp(method, "all") == 0;
  for (int m = 0; m <= (int)partition_method_slabs; m++) {
    if (all ? (m == partition_method_metis && !partition_have_metis())
            : m != partition_method_parse(method))
      continue;
    struct partition p;
    partition_make(&p, &g, nr, (enum partition_method)m);
    partition_print(&p, &g, 0, stdout);
    double *layer = error_malloc((size_t)nr * sizeof(double), "exchange");
    double *sent = error_malloc((size_t)nr * sizeof(double), "exchange");
    int *peers = error_malloc((size_t)nr * sizeof(int), "exchange");
    partition_exchange(&p, &pc, layer, sent, peers);
    double lsum = 0, lmax = 0, smax = 0, psum = 0, pmax = 0, nmax = 0;
    for (int r = 0; r < nr; r++) {
      lsum += layer[r];
      psum += peers[r];
      if (layer[r] > lmax) lmax = layer[r];
      if (sent[r] > smax) smax = sent[r];
      if (peers[r] > pmax) pmax = peers[r];
      if ((double)p.rank_parts[r] > nmax) nmax = (double)p.rank_parts[r];
    }
    printf(
        "exchange: method %s ranks %d particles_max %.0f layer_mean %.0f layer_max %.0f "
        "sent_max %.0f peers_mean %.2f peers_max %.0f multipoles %d\n",
        partition_method_name(p.method), nr, nmax, lsum / nr, lmax, smax, psum / nr, pmax,
        g.nr_cells);
    if (!all) {
      const double mean = g.total_cost / nr;
      printf("#  rank  cells  particles    cost/mean       halo      layer       sent  peers\n");
      for (int r = 0; r < nr; r++)
        printf("  %5d %6d %10zu %12.4f %10.0f %10.0f %10.0f %6d\n", r, p.rank_cells[r],
               p.rank_parts[r], mean > 0.0 ? p.rank_cost[r] / mean : 0.0, p.rank_halo[r], layer[r],
               sent[r], peers[r]);
    }
    free(layer);
    free(sent);
    free(peers);
    partition_free(&p);
  }
  partition_graph_free(&g);
  partition_counts_free(&pc);
  fflush(stdout);
  return 0;
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  struct engine_options opt;
  memset(&opt, 0, sizeof opt);
  opt.nr_threads = 0;
  opt.max_steps = -1;
  opt.use_gpu = 1;
  main_join_verbose(&argc, argv);
  /* -P values, and the ones the physics flags and -y stand for */
  char **overrides = calloc((size_t)argc + 4, sizeof(char *));
  char **user = calloc((size_t)argc + 1, sizeof(char *));
  int n_user = 0, with_hydro = 0, with_gravity = 0, fpe = 0;
  char dump_tasks[64] = "";

  enum {
    OPT_CHECK = 1000,
    OPT_GPU,
    OPT_NO_GPU,
    OPT_REFERENCE,
    OPT_PARTITION,
    OPT_PART_METHOD,
    OPT_PART_COUNTS
  };
  int partition = -1;
  const char *partition_method = partition_have_metis() ? "metis" : "morton";
  const char *partition_counts = NULL;
  ranks_init(&argc, &argv);
  struct option longopts[64 + MAIN_NR_SWIFT];
  static const struct option own[] = {
      {"threads", required_argument, NULL, 't'},
      {"steps", required_argument, NULL, 'n'},
      {"param", required_argument, NULL, 'P'},
      {"check", no_argument, NULL, OPT_CHECK},
      {"dry-run", no_argument, NULL, 'd'},
      {"hydro", no_argument, NULL, 's'},
      {"self-gravity", no_argument, NULL, 'G'},
      {"task-dumps", required_argument, NULL, 'y'},
      {"fpe", no_argument, NULL, 'e'},
      {"gpu", no_argument, NULL, OPT_GPU},
      {"no-gpu", no_argument, NULL, OPT_NO_GPU},
      {"restart", no_argument, NULL, 'r'},
      {"param-reference", no_argument, NULL, OPT_REFERENCE},
      {"partition", required_argument, NULL, OPT_PARTITION},
      {"partition-method", required_argument, NULL, OPT_PART_METHOD},
      {"partition-counts", required_argument, NULL, OPT_PART_COUNTS},
      {"verbose", optional_argument, NULL, 'v'},
      {"help", no_argument, NULL, 'h'},
      {"version", no_argument, NULL, 'V'}};
  int nl = 0;
  for (size_t k = 0; k < sizeof own / sizeof own[0]; k++) longopts[nl++] = own[k];
  for (int k = 0; k < MAIN_NR_SWIFT; k++)
    longopts[nl++] = (struct option){
        main_swift_options[k].name, main_swift_options[k].has_arg ? required_argument : no_argument,
        NULL, MAIN_OPT_SWIFT + k};
  longopts[nl] = (struct option){NULL, 0, NULL, 0};
  /* SWIFT's letters: the ones with a value take it, so that it is not taken
   * for the parameter file */
  char optstring[128] = ":sGt:n:P:v::ry:edhV";
  for (size_t k = 0; k < sizeof main_swift_letters / sizeof main_swift_letters[0]; k++) {
    size_t l = strlen(optstring);
    optstring[l] = main_swift_letters[k].letter;
    optstring[l + 1] = '\0';
    for (int j = 0; j < MAIN_NR_SWIFT; j++)
      if (strcmp(main_swift_options[j].name, main_swift_letters[k].name) == 0 &&
          main_swift_options[j].has_arg)
        strcat(optstring, ":");
  }
  int c;
  opterr = 0;
  while ((c = getopt_long(argc, argv, optstring, longopts, NULL)) != -1) {
    switch (c) {
      case 't':
        opt.nr_threads = (int)parse_count("--threads", optarg);
        if (opt.nr_threads < 1) error_exit("option --threads expects at least 1");
        break;
      case 'n':
        opt.max_steps = parse_count("--steps", optarg);
        break;
      case 'P':
        user[n_user++] = optarg;
        break;
      case 's':
        with_hydro = 1;
        break;
      case 'G':
        with_gravity = 1;
        break;
      case 'y':
        snprintf(dump_tasks, sizeof dump_tasks, "Scheduler:dump_tasks:%ld",
                 parse_count("--task-dumps", optarg));
        break;
      case 'e':
        fpe = 1;
        break;
      case 'v':
        if (!optarg)
          error_verbosity++;
        else if (strspn(optarg, "v") == strlen(optarg)) /* -vv, -vvv */
          error_verbosity += 1 + (int)strlen(optarg);
        else
          error_verbosity = (int)parse_count("--verbose", optarg);
        break;
      case 'd':
      case OPT_CHECK:
        opt.check_only = 1;
        break;
      case OPT_GPU:
        opt.use_gpu = 2;
        break;
      case OPT_NO_GPU:
        opt.use_gpu = 0;
        break;
      case 'r':
        opt.restart = 1;
        break;
      case OPT_REFERENCE:
        params_write_reference(stdout);
        free(overrides);
        free(user);
        ranks_finalize();
        return 0;
      case OPT_PARTITION:
        partition = (int)parse_count("--partition", optarg);
        break;
      case OPT_PART_COUNTS:
        partition_counts = optarg;
        break;
      case OPT_PART_METHOD:
        if (strcmp(optarg, "all") != 0 && partition_method_parse(optarg) < 0)
          error_exit("option --partition-method expects metis, morton, slabs or all, not '%s'",
                     optarg);
        if (strcmp(optarg, "metis") == 0 && !partition_have_metis())
          error_exit(
              "--partition-method metis: this build has no METIS (apt-get install "
              "libmetis-dev and configure again)");
        partition_method = optarg;
        break;
      case 'h':
        usage(stdout);
        free(overrides);
        free(user);
        ranks_finalize();
        return 0;
      case 'V':
        version();
        free(overrides);
        free(user);
        ranks_finalize();
        return 0;
      case ':':
        error_exit("option %s needs a value (see --help)", argv[optind - 1]);
      case '?':
        error_exit("unknown option '%s' (see --help)", argv[optind - 1]);
      default:
        if (c >= MAIN_OPT_SWIFT && c < MAIN_OPT_SWIFT + MAIN_NR_SWIFT) {
          main_swift_option(c - MAIN_OPT_SWIFT);
          break;
        }
        for (size_t k = 0; k < sizeof main_swift_letters / sizeof main_swift_letters[0]; k++)
          if (main_swift_letters[k].letter == c)
            for (int j = 0; j < MAIN_NR_SWIFT; j++)
              if (strcmp(main_swift_options[j].name, main_swift_letters[k].name) == 0)
                main_swift_option(j);
        break;
    }
  }
  if (partition_counts) {
    if (partition < 0) error_exit("--partition-counts needs --partition N");
    if (optind < argc) error_exit("--partition-counts takes no parameter file");
    const int rc = main_partition_counts(partition, partition_method, partition_counts);
    free(overrides);
    free(user);
    ranks_finalize();
    return rc;
  }
  if (optind >= argc)
    error_exit("no parameter file given (usage: bolide [OPTIONS] PARAMS.yml; see --help)");
  if (optind + 1 < argc)
    error_exit("unexpected argument '%s' after the parameter file", argv[optind + 1]);
  /* several MPI ranks: rank 0 writes the run's log (errors come from any) */
  if (ranks_rank() != 0) {
    error_log_quiet = 1;
    error_rank = ranks_rank();
    error_warn_quiet = 1; /* (until the run starts: what rank 0 says too) */
  }
  {
    /* the ranks of one node share its cores (src/runner.c) */
    int lr, ln;
    ranks_local(&lr, &ln);
    runner_share_node(lr, ln);
  }

  /* the flags first, so that -P can still say otherwise */
  int n_overrides = 0;
  static char hydro_on[] = "SPH:hydro:true", hydro_off[] = "SPH:hydro:false";
  static char gravity_on[] = "Gravity:enabled:true", gravity_off[] = "Gravity:enabled:false";
  if (with_hydro || with_gravity) {
    overrides[n_overrides++] = with_hydro ? hydro_on : hydro_off;
    overrides[n_overrides++] = with_gravity ? gravity_on : gravity_off;
  }
  if (dump_tasks[0]) overrides[n_overrides++] = dump_tasks;
  for (int k = 0; k < n_user; k++) overrides[n_overrides++] = user[k];

  const char *file = argv[optind];
  /* every rank reads the same file: rank 0 first, so that a mistake in it is
   * reported once (the other ranks wait, and mpirun stops them when rank 0
   * exits); a rank that then cannot read it says so itself */
  int params_ok = 0;
  if (ranks_size() > 1 && ranks_rank() != 0) ranks_bcast_ints(&params_ok, 1);
  struct params *params = params_read(file, n_overrides, overrides);
  if (ranks_size() > 1 && ranks_rank() == 0) {
    params_ok = 1;
    ranks_bcast_ints(&params_ok, 1);
  }
  if ((with_hydro || with_gravity) && !(with_hydro && with_gravity)) {
    const char *off = with_hydro ? "Gravity:enabled" : "SPH:hydro";
    const char *t = params_file_text(params, off);
    if (t && (strcasecmp(t, "true") == 0 || strcasecmp(t, "yes") == 0 || strcasecmp(t, "on") == 0 ||
              strcmp(t, "1") == 0))
      error_note(
          "%s: %s is true in the file but %s alone was given: as in SWIFT, the physics not named "
          "on "
          "the command line is off (give -s -G for both)",
          file, off, with_hydro ? "-s" : "-G");
  }
  const int gline = params_section_line(params, "Gravity");
  if (gline > 0 && !params_given(params, "Gravity:enabled"))
    error_warning(
        "%s:%d: the file has a Gravity section but self-gravity is off; switch it on with -G "
        "(--self-gravity) as in SWIFT, or with 'enabled: true' in the Gravity section",
        file, gline);
  if (fpe) main_enable_fpe();
  if (partition >= 0) {
    const int rc = main_partition(partition, partition_method, params, &opt);
    params_free(params);
    free(overrides);
    free(user);
    ranks_finalize();
    return rc;
  }
  struct engine e;
  engine_init(&e, params, &opt);
  error_warn_quiet = 0;
  if (!opt.check_only) engine_run(&e);
  engine_clean(&e);
  params_free(params);
  free(overrides);
  free(user);
  ranks_finalize();
  return 0;
}
