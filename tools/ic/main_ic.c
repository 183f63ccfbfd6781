/* bolide-ic: initial conditions in HDF5 (the layout of src/io/snapshot.h).
 *
 *   bolide-ic box   [options]   uniform lattice (cubic, fcc, hcp), optionally perturbed
 *   bolide-ic sod   [options]   3-D Sod shock tube
 *   bolide-ic sedov [options]   Sedov-Taylor blast
 *
 * Values are written as given, with /Units declaring SI. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "tools/ic/ic_impact.h"
#include "tools/ic/ic_tools.h"
#include "tasks/hydro/kernel.h"
#include "src/io/snapshot.h"
#include "src/io/units.h"
#include "src/version.h"

/** Subcommands, as bits so that each option lists where it applies. */
enum icgen_cmd { CMD_BOX = 1, CMD_SOD = 2, CMD_SEDOV = 4, CMD_ALL = 7 };

/** Long options; val doubles as the key of the switch below. */
enum {
  OPT_N = 256,
  OPT_NX,
  OPT_SIZE,
  OPT_RHO,
  OPT_U,
  OPT_PERTURB,
  OPT_SEED,
  OPT_PERIODIC,
  OPT_NO_PERIODIC,
  OPT_MAT,
  OPT_ETA,
  OPT_LATTICE,
  OPT_ENERGY,
  OPT_RADIUS,
  OPT_WEIGHTING,
  OPT_GAMMA,
  OPT_VERSION
};

static const struct option icgen_longopts[] = {
    {"output", required_argument, NULL, 'o'},
    {"n", required_argument, NULL, OPT_N},
    {"nx", required_argument, NULL, OPT_NX},
    {"size", required_argument, NULL, OPT_SIZE},
    {"rho", required_argument, NULL, OPT_RHO},
    {"u", required_argument, NULL, OPT_U},
    {"perturb", required_argument, NULL, OPT_PERTURB},
    {"seed", required_argument, NULL, OPT_SEED},
    {"periodic", no_argument, NULL, OPT_PERIODIC},
    {"no-periodic", no_argument, NULL, OPT_NO_PERIODIC},
    {"mat", required_argument, NULL, OPT_MAT},
    {"eta", required_argument, NULL, OPT_ETA},
    {"lattice", required_argument, NULL, OPT_LATTICE},
    {"energy", required_argument, NULL, OPT_ENERGY},
    {"radius", required_argument, NULL, OPT_RADIUS},
    {"weighting", required_argument, NULL, OPT_WEIGHTING},
    {"gamma", required_argument, NULL, OPT_GAMMA},
    {"help", no_argument, NULL, 'h'},
    {"version", no_argument, NULL, OPT_VERSION},
    {NULL, 0, NULL, 0}};

/** Which subcommands take each option (index = val - OPT_N). */
static const int icgen_applies[] = {[OPT_N - OPT_N] = CMD_BOX | CMD_SEDOV,
                                    [OPT_NX - OPT_N] = CMD_ALL,
                                    [OPT_SIZE - OPT_N] = CMD_ALL,
                                    [OPT_RHO - OPT_N] = CMD_BOX | CMD_SEDOV,
                                    [OPT_U - OPT_N] = CMD_BOX | CMD_SEDOV,
                                    [OPT_PERTURB - OPT_N] = CMD_BOX | CMD_SEDOV,
                                    [OPT_SEED - OPT_N] = CMD_BOX | CMD_SEDOV,
                                    [OPT_PERIODIC - OPT_N] = CMD_BOX | CMD_SEDOV,
                                    [OPT_NO_PERIODIC - OPT_N] = CMD_BOX | CMD_SEDOV,
                                    [OPT_MAT - OPT_N] = CMD_ALL,
                                    [OPT_ETA - OPT_N] = CMD_ALL,
                                    [OPT_LATTICE - OPT_N] = CMD_ALL,
                                    [OPT_ENERGY - OPT_N] = CMD_SEDOV,
                                    [OPT_RADIUS - OPT_N] = CMD_SEDOV,
                                    [OPT_WEIGHTING - OPT_N] = CMD_SEDOV,
                                    [OPT_GAMMA - OPT_N] = CMD_SOD,
                                    [OPT_VERSION - OPT_N] = CMD_ALL};

/** Long name of the option with value val. */
static const char *icgen_optname(int val) {
  for (const struct option *o = icgen_longopts; o->name; o++)
    if (o->val == val) return o->name;
  return "?";
}

static void icgen_usage(FILE *f) {
  fprintf(
      f,
      "Usage: bolide-ic SUBCOMMAND [options]\n"
      "Write initial conditions as HDF5 (SWIFT layout, /Units SI, plus an XDMF file).\n"
      "\n"
      "Subcommands:\n"
      "  box     uniform lattice, optionally perturbed\n"
      "  sod     3-D Sod shock tube: rho 1 | 0.125, P 1 | 0.1 along x, periodic,\n"
      "          interfaces at x = 0 and x = Lx/2, equal particle masses\n"
      "  sedov   Sedov-Taylor blast: energy E deposited near the centre of a box\n"
      "  planet  layered planet in hydrostatic equilibrium, SEA shells (planet --help)\n"
      "  impact  two bodies on a collision course (impact --help)\n"
      "  import-miluphcuda  a miluphcuda ASCII or HDF5 input file (import-miluphcuda --help)\n"
      "  miluphcuda-materials  a miluphcuda material.cfg as a Bolide Materials section,\n"
      "          written as YAML, not HDF5 (miluphcuda-materials --help)\n"
      "  import-mesh  a finite-element mesh's nodes: a node file or a keyword deck's\n"
      "          *NODE sections (import-mesh --help)\n"
      "\n"
      "Options (subcommands they apply to in brackets):\n"
      "  -o, --output FILE     output file (default: SUBCOMMAND.hdf5)\n"
      "  --lattice NAME        cubic (default), fcc or hcp (box, sedov; sod: cubic, fcc)\n"
      "  --n N                 lattice cells along x (cubic, hcp: particles; fcc: 4-particle\n"
      "                        cells); y and z follow the box shape (default 32) [box, sedov]\n"
      "  --nx NX[,NY,NZ]       cells along each axis [box, sedov]; sod: NX along x of the\n"
      "                        left (dense) state, even (default 64)\n"
      "  --size L[,Ly,Lz]      box size (default 1; sod: 1,0.125,0.125)\n"
      "  --rho RHO             density (default 1) [box, sedov]\n"
      "  --u U                 specific internal energy (default: box 1, sedov 1e-6)\n"
      "  --perturb FRAC        random displacement, up to FRAC x spacing per axis [box, sedov]\n"
      "  --seed S              seed of the displacement (default 1)\n"
      "  --periodic, --no-periodic  periodic box (default: box no, sod and sedov yes)\n"
      "  --mat ID              material id of every particle (default 0)\n"
      "  --eta ETA             h = ETA x mean particle spacing (default: SPH:resolution_eta's,\n"
      "                        " KERNEL_ETA_DEFAULT_STR
      " with the compiled-in kernel)\n"
      "  --energy E            energy deposited (default 1) [sedov]\n"
      "  --radius R            deposit radius (default 2 h) [sedov]\n"
      "  --weighting W         kernel (cubic spline in r/R, default) or uniform [sedov]\n"
      "  --gamma G             adiabatic index turning P into u (default 5/3) [sod]\n"
      "  -h, --help            this help\n"
      "  --version             version\n"
      "Environment: BOLIDE_IC_THREADS  threads of the SPH density and relaxation passes of\n"
      "  planet, impact and sphere bodies (default: all online cores; the output does\n"
      "  not depend on it)\n");
}

/** Parse "a[,b,c]" into n values (1 value: all three the same). */
static void icgen_parse_list(const char *opt, const char *s, double *out, int positive) {
  double v[3];
  int n = 0;
  const char *c = s;
  while (n < 3) {
    char *end;
    v[n] = strtod(c, &end);
    if (end == c || !isfinite(v[n]) || (positive && !(v[n] > 0))) break;
    n++;
    if (*end == '\0') {
      c = end;
      break;
    }
    if (*end != ',') {
      n = 0;
      break;
    }
    c = end + 1;
  }
  if (*c != '\0' || (n != 1 && n != 3))
    error_exit("--%s: expected 1 or 3 %snumbers separated by commas, got '%s'", opt,
               positive ? "positive " : "", s);
  for (int d = 0; d < 3; d++) out[d] = v[n == 3 ? d : 0];
}

static double icgen_parse_real(const char *opt, const char *s, double min) {
  char *end;
  const double v = strtod(s, &end);
  if (end == s || *end || !isfinite(v) || v < min)
    error_exit("--%s: expected a number >= %g, got '%s'", opt, min, s);
  return v;
}

static long icgen_parse_int(const char *opt, const char *s, long min, long max) {
  char *end;
  const long v = strtol(s, &end, 10);
  if (end == s || *end || v < min || v > max)
    error_exit("--%s: expected an integer in [%ld, %ld], got '%s'", opt, min, max, s);
  return v;
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  if (argc < 2)
    error_exit(
        "missing subcommand (box, sod, sedov, planet, impact, import-miluphcuda, "
        "miluphcuda-materials or import-mesh; see --help)");
  if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
    icgen_usage(stdout);
    return 0;
  }
  if (strcmp(argv[1], "--version") == 0) {
    bolide_version_print("bolide-ic");
    return 0;
  }
  const char *sub = argv[1];
  if (strcmp(sub, "planet") == 0) return icgen_planet_main(argc - 1, argv + 1);
  if (strcmp(sub, "impact") == 0) return icgen_impact_main(argc - 1, argv + 1);
  if (strcmp(sub, "import-miluphcuda") == 0) return icgen_miluphcuda_main(argc - 1, argv + 1);
  if (strcmp(sub, "import-mesh") == 0) return icgen_mesh_main(argc - 1, argv + 1);
  if (strcmp(sub, "miluphcuda-materials") == 0)
    return icgen_miluphcuda_cfg_main(argc - 1, argv + 1);
  const int cmd = strcmp(sub, "box") == 0     ? CMD_BOX
                  : strcmp(sub, "sod") == 0   ? CMD_SOD
                  : strcmp(sub, "sedov") == 0 ? CMD_SEDOV
                                              : 0;
  if (!cmd)
    error_exit(
        "unknown subcommand '%s' (box, sod, sedov, planet, impact, import-miluphcuda, "
        "miluphcuda-materials or import-mesh; see --help)",
        sub);

  struct icgen_opts o = {.lattice = ICGEN_CUBIC,
                         .n = cmd == CMD_SOD ? 64 : 32,
                         .size = {1, 1, 1},
                         .rho = 1,
                         .u = cmd == CMD_SEDOV ? 1e-6 : 1,
                         .seed = 1,
                         .periodic = cmd != CMD_BOX,
                         .eta = KERNEL_ETA_DEFAULT,
                         .energy = 1,
                         .kernel_weighting = 1,
                         .gamma = 5.0 / 3.0};
  if (cmd == CMD_SOD) o.size[1] = o.size[2] = 0.125;
  char outbuf[64];
  snprintf(outbuf, sizeof outbuf, "%s.hdf5", sub);
  o.output = outbuf;

  opterr = 0;
  optind = 1;
  int c;
  while ((c = getopt_long(argc - 1, argv + 1, ":o:h", icgen_longopts, NULL)) != -1) {
    if (c == '?') error_exit("%s: unknown option '%s' (see --help)", sub, argv[optind]);
    if (c == ':') error_exit("%s: option '%s' needs a value", sub, argv[optind]);
    if (c >= OPT_N && !(icgen_applies[c - OPT_N] & cmd))
      error_exit("%s: option '--%s' does not apply to this subcommand", sub, icgen_optname(c));
    switch (c) {
      case 'o':
        o.output = optarg;
        break;
      case 'h':
        icgen_usage(stdout);
        return 0;
      case OPT_VERSION:
        bolide_version_print("bolide-ic");
        return 0;
      case OPT_N:
        o.n = (int)icgen_parse_int("n", optarg, 1, 100000);
        break;
      case OPT_NX: {
        double v[3];
        icgen_parse_list("nx", optarg, v, 1);
        for (int d = 0; d < 3; d++) {
          if (v[d] != floor(v[d]) || v[d] > 100000)
            error_exit("--nx: expected whole numbers, got '%s'", optarg);
          o.nx[d] = (int)v[d];
        }
        break;
      }
      case OPT_SIZE:
        icgen_parse_list("size", optarg, o.size, 1);
        break;
      case OPT_RHO:
        o.rho = icgen_parse_real("rho", optarg, 1e-300);
        break;
      case OPT_U:
        o.u = icgen_parse_real("u", optarg, 0);
        break;
      case OPT_PERTURB:
        o.perturb = icgen_parse_real("perturb", optarg, 0);
        break;
      case OPT_SEED:
        o.seed = (uint64_t)icgen_parse_int("seed", optarg, 0, 2147483647L);
        break;
      case OPT_PERIODIC:
        o.periodic = 1;
        break;
      case OPT_NO_PERIODIC:
        o.periodic = 0;
        break;
      case OPT_MAT:
        o.mat = (int32_t)icgen_parse_int("mat", optarg, 0, 2147483647L);
        break;
      case OPT_ETA:
        o.eta = icgen_parse_real("eta", optarg, 1e-3);
        break;
      case OPT_ENERGY:
        o.energy = icgen_parse_real("energy", optarg, 0);
        break;
      case OPT_RADIUS:
        o.radius = icgen_parse_real("radius", optarg, 0);
        break;
      case OPT_GAMMA:
        o.gamma = icgen_parse_real("gamma", optarg, 1.0000001);
        break;
      case OPT_LATTICE:
        if (strcmp(optarg, "cubic") == 0)
          o.lattice = ICGEN_CUBIC;
        else if (strcmp(optarg, "fcc") == 0)
          o.lattice = ICGEN_FCC;
        else if (strcmp(optarg, "hcp") == 0)
          o.lattice = ICGEN_HCP;
        else
          error_exit("--lattice: expected cubic, fcc or hcp, got '%s'", optarg);
        break;
      case OPT_WEIGHTING:
        if (strcmp(optarg, "kernel") == 0)
          o.kernel_weighting = 1;
        else if (strcmp(optarg, "uniform") == 0)
          o.kernel_weighting = 0;
        else
          error_exit("--weighting: expected kernel or uniform, got '%s'", optarg);
        break;
      default:
        error_bug("option %d not handled", c);
    }
  }
  if (optind < argc - 1) error_exit("%s: unexpected argument '%s'", sub, argv[optind + 1]);
  if (o.perturb > 0.5) error_exit("--perturb %g: at most 0.5 (particles would cross)", o.perturb);

  struct parts p;
  if (cmd == CMD_BOX) icgen_box(&o, &p);
  if (cmd == CMD_SOD) icgen_sod(&o, &p);
  if (cmd == CMD_SEDOV) icgen_sedov(&o, &p);

  /* the command line, recorded in the file */
  char command[2048] = "";
  for (int a = 0; a < argc; a++) {
    strncat(command, a ? " " : "", sizeof command - strlen(command) - 1);
    strncat(command, a ? argv[a] : "bolide-ic", sizeof command - strlen(command) - 1);
  }
  struct unit_system si;
  units_init_si(&si);
  struct snapshot_meta meta = {
      .time = 0, .periodic = o.periodic, .ic = 1, .run_name = sub, .command = command, .hydro = 1};
  memcpy(meta.box_size, o.size, sizeof meta.box_size);
  for (size_t i = 0; i < p.count; i++) p.alpha[i] = 1.0; /* not porous */
  snapshot_write(o.output, &meta, &p, &si, 0);
  printf("bolide-ic %s: %zu particles written to %s\n", sub, p.count, o.output);
  parts_free(&p);
  return 0;
}
