/* bolide-ic planet and bolide-ic impact: command lines and body
 * specifications.  The physics is in ic_planet.c (profiles), ic_sea.c (SEA
 * shells) and ic_impact.c (two-body trajectory). */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "src/io/ic.h"
#include "tools/ic/ic_impact.h"
#include "tools/ic/ic_planet.h"
#include "tasks/hydro/kernel.h"
#include "src/io/snapshot.h"
#include "src/io/units.h"
#include "src/version.h"

/** Everything one body (a planet, a uniform sphere or a file) needs. */
struct body {
  const char *what;           /**< "planet", "target", "impactor" (messages) */
  int kind;                   /**< 0 planet, 1 uniform sphere, 2 file */
  struct ic_planet_spec spec; /**< layers, mass or radius, surface P and T */
  char names[IC_PLANET_MAX_LAYERS][MATERIAL_NAME_LEN]; /**< material names, centre outward */
  int n_names, n_frac, n_radii, n_trho, n_ids;         /**< how many of each list were given */
  const char *trho[IC_PLANET_MAX_LAYERS];              /**< T-rho relations as given */
  char trho_buf[IC_PLANET_MAX_LAYERS][64];             /**< storage of trho */
  int32_t mat_ids[IC_PLANET_MAX_LAYERS];               /**< --mat-ids */
  const char *library;                                 /**< material library */
  const char *file;                                    /**< kind 2: the HDF5 file */
  const char *profile;                                 /**< profile table to write, NULL: none */
  double n;                                            /**< particles */
  double eta;                                          /**< h = eta (m/rho)^(1/3) */
  double rho, u, T;          /**< sphere: density, energy or temperature */
  int T_given;               /**< sphere: u from T (else u = 0) */
  double radius_given;       /**< file: radius override */
  uint64_t seed;             /**< random rotations */
  struct ic_sea_options sea; /**< surface iterations and relaxation of the SEA shells */
  /* results */
  struct parts p; /**< the particles, centred on their centre of mass */
  double M, R;    /**< mass and radius */
};

/** Parse a number; stops with "WHAT: KEY: ..." on bad input. */
static double body_real(const struct body *b, const char *key, const char *s, double min) {
  char *end;
  const double v = strtod(s, &end);
  if (end == s || *end || !isfinite(v) || v < min)
    error_exit("%s: %s: expected a number >= %g, got '%s'", b->what, key, min, s);
  return v;
}

/** Split a list "a,b,c" or "a:b:c" into at most IC_PLANET_MAX_LAYERS items. */
static int body_list(const struct body *b, const char *key, const char *s, char out[][64]) {
  int n = 0;
  const char *c = s;
  while (*c) {
    if (n == IC_PLANET_MAX_LAYERS)
      error_exit("%s: %s: at most %d layers", b->what, key, IC_PLANET_MAX_LAYERS);
    size_t len = strcspn(c, ",:");
    if (len == 0 || len >= 64) error_exit("%s: %s: bad list '%s'", b->what, key, s);
    memcpy(out[n], c, len);
    out[n][len] = '\0';
    n++;
    c += len;
    if (*c) c++;
  }
  return n;
}

/** Set one key of a body (the long option names of `planet`). */
static void body_set(struct body *b, const char *key, const char *val) {
  char items[IC_PLANET_MAX_LAYERS][64];
  if (!strcmp(key, "materials") || !strcmp(key, "material")) {
    b->n_names = body_list(b, key, val, items);
    for (int k = 0; k < b->n_names; k++)
      snprintf(b->names[k], MATERIAL_NAME_LEN, "%.47s", items[k]);
  } else if (!strcmp(key, "mass-fractions")) {
    b->n_frac = body_list(b, key, val, items);
    for (int k = 0; k < b->n_frac; k++) b->spec.layer[k].mass_frac = body_real(b, key, items[k], 0);
  } else if (!strcmp(key, "layer-radii")) {
    b->n_radii = body_list(b, key, val, items);
    for (int k = 0; k < b->n_radii; k++) b->spec.layer[k].r_out = body_real(b, key, items[k], 0);
  } else if (!strcmp(key, "T-rho")) {
    b->n_trho = body_list(b, key, val, items);
    for (int k = 0; k < b->n_trho; k++)
      memcpy(b->trho_buf[k], items[k], 64), b->trho[k] = b->trho_buf[k];
  } else if (!strcmp(key, "mat-ids")) {
    b->n_ids = body_list(b, key, val, items);
    for (int k = 0; k < b->n_ids; k++) b->mat_ids[k] = (int32_t)body_real(b, key, items[k], 0);
  } else if (!strcmp(key, "mass")) {
    b->spec.M = body_real(b, key, val, 1e-300);
  } else if (!strcmp(key, "radius")) {
    b->spec.R = b->radius_given = body_real(b, key, val, 1e-300);
  } else if (!strcmp(key, "P-surface")) {
    b->spec.P_s = body_real(b, key, val, 0);
  } else if (!strcmp(key, "T-surface") || !strcmp(key, "T")) {
    b->spec.T_s = b->T = body_real(b, key, val, 0);
    b->T_given = 1;
  } else if (!strcmp(key, "n")) {
    b->n = body_real(b, key, val, 0);
  } else if (!strcmp(key, "n-prof")) {
    b->spec.n_prof = (int)body_real(b, key, val, 100);
  } else if (!strcmp(key, "eta")) {
    b->eta = body_real(b, key, val, 1e-3);
  } else if (!strcmp(key, "density-iter")) {
    b->sea.density_iter = (int)body_real(b, key, val, 0);
  } else if (!strcmp(key, "relax")) {
    b->sea.relax = (int)body_real(b, key, val, 0);
  } else if (!strcmp(key, "shell-thickness")) {
    b->sea.shell_thickness = body_real(b, key, val, 0.5);
  } else if (!strcmp(key, "stretch-a")) {
    b->sea.stretch_a = body_real(b, key, val, 0);
  } else if (!strcmp(key, "seed")) {
    b->seed = (uint64_t)body_real(b, key, val, 0);
  } else if (!strcmp(key, "rho")) {
    b->rho = body_real(b, key, val, 1e-300);
  } else if (!strcmp(key, "u")) {
    b->u = body_real(b, key, val, 0);
  } else if (!strcmp(key, "library")) {
    b->library = val;
  } else if (!strcmp(key, "profile")) {
    b->profile = val;
  } else if (!strcmp(key, "file")) {
    b->file = val;
    b->kind = 2;
  } else {
    error_exit("%s: unknown key '%s'", b->what, key);
  }
}

static void body_init(struct body *b, const char *what) {
  memset(b, 0, sizeof *b);
  b->what = what;
  b->spec.P_s = 1e5;
  b->spec.T_s = b->T = 300;
  b->spec.n_prof = 10000;
  b->n = 1e5;
  /* SPH:resolution_eta's default: the SEA shells are iterated against it */
  b->eta = KERNEL_ETA_DEFAULT;
  b->seed = 1;
  b->sea = (struct ic_sea_options)IC_SEA_OPTIONS_DEFAULT;
  b->u = -1;
}

/** Centre of mass (position and velocity) of p. */
static void body_com(const struct parts *p, double x[3], double v[3], double *M) {
  double s[7] = {0};
  for (size_t i = 0; i < p->count; i++) {
    const double m = p->m[i];
    s[0] += m, s[1] += m * p->x[i], s[2] += m * p->y[i], s[3] += m * p->z[i];
    s[4] += m * p->vx[i], s[5] += m * p->vy[i], s[6] += m * p->vz[i];
  }
  for (int k = 0; k < 3; k++) x[k] = s[1 + k] / s[0], v[k] = s[4 + k] / s[0];
  *M = s[0];
}

/** Build the body's particles (and its profile) from its keys. */
static void body_make(struct body *b, int64_t first_id, int verbose) {
  struct unit_system si;
  units_init_si(&si);
  if (b->kind == 2) {
    ic_read(b->file, &si, NULL, 0, &b->p, NULL);
    double x[3], v[3];
    body_com(&b->p, x, v, &b->M);
    double r2 = 0;
    for (size_t i = 0; i < b->p.count; i++) {
      b->p.x[i] -= x[0], b->p.y[i] -= x[1], b->p.z[i] -= x[2];
      b->p.vx[i] -= v[0], b->p.vy[i] -= v[1], b->p.vz[i] -= v[2];
      r2 = fmax(r2, b->p.x[i] * b->p.x[i] + b->p.y[i] * b->p.y[i] + b->p.z[i] * b->p.z[i]);
      b->p.id[i] = first_id + (int64_t)i;
    }
    b->R = b->radius_given > 0 ? b->radius_given : sqrt(r2);
    return;
  }
  if (b->n_names < 1) error_exit("%s: no materials given", b->what);
  if (!b->library) b->library = material_default_library();
  struct ic_planet_spec *s = &b->spec;
  s->n_layers = b->n_names;
  if (b->n_frac && b->n_frac != s->n_layers)
    error_exit("%s: %d mass fractions for %d layers", b->what, b->n_frac, s->n_layers);
  if (b->n_radii && b->n_radii != s->n_layers)
    error_exit("%s: %d layer radii for %d layers", b->what, b->n_radii, s->n_layers);
  if (b->n_ids && b->n_ids != s->n_layers)
    error_exit("%s: %d material ids for %d layers", b->what, b->n_ids, s->n_layers);
  if (b->n_trho > 1 && b->n_trho != s->n_layers)
    error_exit("%s: %d T-rho relations for %d layers", b->what, b->n_trho, s->n_layers);
  if (b->n_radii && s->M > 0)
    error_exit("%s: layer radii go with the radius, not the mass", b->what);
  if (b->n_frac && s->R > 0)
    error_exit("%s: mass fractions go with the mass, not the radius", b->what);
  if (b->n > 0 && b->n < 4) error_exit("%s: n: at least 4 particles (or 0: profile only)", b->what);
  if (b->n_radii && !(s->R > 0)) s->R = s->layer[s->n_layers - 1].r_out;
  for (int k = 0; k < s->n_layers; k++) {
    struct ic_planet_layer *l = &s->layer[k];
    material_from_library(&l->mat, b->library, b->names[k], 0);
    l->mat.id = b->n_ids ? b->mat_ids[k] : l->mat.swift_id >= 0 ? l->mat.swift_id : k;
    b->mat_ids[k] = l->mat.id;
    const char *rel = b->n_trho ? b->trho[b->n_trho > 1 ? k : 0] : "isothermal";
    if (ic_planet_parse_trho(rel, l) != 0)
      error_exit("%s: T-rho: expected isothermal, adiabatic or power=ALPHA, got '%s'", b->what,
                 rel);
  }
  struct ic_planet_profile prof;
  if (b->kind == 1) {
    if (s->n_layers != 1) error_exit("%s: a uniform sphere has one material", b->what);
    const struct material *mat = &s->layer[0].mat;
    const double rho = b->rho > 0 ? b->rho : mat->rho0;
    if ((s->M > 0) == (s->R > 0))
      error_exit("%s: give the mass or the radius of the sphere", b->what);
    const double R = s->R > 0 ? s->R : cbrt(3 * s->M / (4 * M_PI * rho));
    double u = b->u;
    if (u < 0) {
      ic_planet_spec_prepare(s, b->what);
      u = b->T_given && material_has_temperature(mat) ? ic_planet_u_rho_T(&s->layer[0], rho, b->T)
                                                      : 0;
    }
    ic_planet_profile_uniform(&prof, mat, R, rho, u, 10000);
  } else {
    ic_planet_spec_prepare(s, b->what);
    ic_planet_profile_make(s, &prof, units_G(&si));
  }
  b->M = prof.M, b->R = prof.R;
  if (verbose)
    printf("%s: M = %.8e kg, R = %.8e m, %d layer(s), central rho %.6g kg/m^3, P %.6g Pa\n",
           b->what, prof.M, prof.R, prof.n_layers, prof.rho[0], prof.P[0]);
  if (b->profile) ic_planet_profile_write(&prof, b->profile);
  if (b->n >= 4)
    ic_sea_planet(&prof, b->mat_ids, (size_t)llround(b->n), b->eta, b->seed, first_id, &b->p,
                  &b->sea, verbose);
  ic_planet_profile_free(&prof);
  ic_planet_spec_free(s);
}

/** Write p with snapshot_write in IC mode: box of side 4 x the largest
 *  coordinate or 2 half_min, whichever is larger, positions shifted by half
 *  the box (the centre of mass at the box centre).  Returns the side. */
static double body_write(const char *path, struct parts *p, int argc, char **argv, const char *run,
                         double half_min) {
  char command[4096] = "bolide-ic";
  for (int a = 0; a < argc; a++) {
    strncat(command, " ", sizeof command - strlen(command) - 1);
    strncat(command, argv[a], sizeof command - strlen(command) - 1);
  }
  double ext = 0;
  for (size_t i = 0; i < p->count; i++)
    ext = fmax(ext, fmax(fabs(p->x[i]), fmax(fabs(p->y[i]), fabs(p->z[i]))));
  struct unit_system si;
  units_init_si(&si);
  struct snapshot_meta meta = {.time = 0,
                               .periodic = 0,
                               .ic = 1,
                               .run_name = run,
                               .command = command,
                               .hydro = 1,
                               .self_gravity = 1};
  const double half = fmax(2 * ext, half_min);
  for (int d = 0; d < 3; d++) meta.box_size[d] = 2 * half;
  /* the engine's open box is [0, L]^3: centre of mass at the box centre */
  for (size_t i = 0; i < p->count; i++) p->x[i] += half, p->y[i] += half, p->z[i] += half;
  for (size_t i = 0; i < p->count; i++) p->alpha[i] = 1.0; /* not porous */
  snapshot_write(path, &meta, p, &si, 0);
  return 2 * half;
}

static void planet_usage(FILE *f) {
  fprintf(
      f,
      "Usage: bolide-ic planet [options]\n"
      "Layered planet in hydrostatic equilibrium on stretched equal-area shells\n"
      "(Kegerreis et al. 2019).  Lists are comma-separated, centre outward.  SI units.\n"
      "  -o, --output FILE        particles (default planet.hdf5)\n"
      "  --materials A,B          layer materials from the library (e.g. iron,granite)\n"
      "  --mass M                 total mass (the radius is found), or\n"
      "  --radius R               total radius (the mass is found)\n"
      "  --mass-fractions F,G     layer mass fractions (with --mass; sum 1)\n"
      "  --layer-radii R1,R       outer radius of each layer (with --radius)\n"
      "  --P-surface P            surface pressure (default 1e5)\n"
      "  --T-surface T            surface temperature (default 300)\n"
      "  --T-rho REL[,REL]        isothermal (default), adiabatic or power=ALPHA (T ~ rho^ALPHA)\n"
      "  --n N                    particles (default 1e5; 0: profile only)\n"
      "  --n-prof N               radial steps of the profile (default 10000)\n"
      "  --profile FILE           write the profile table (r m rho P T u layer)\n"
      "  --mat-ids I,J            material ids (default: the library's swift_id)\n"
      "  --eta ETA                h = ETA (m/rho)^(1/3) (default " KERNEL_ETA_DEFAULT_STR
      ", as\n"
      "                           SPH:resolution_eta)\n"
      "  --seed S                 seed of the shell rotations (default 1)\n"
      "  --shell-thickness F      SEA shell thickness in particle spacings (default 1.2;\n"
      "                           Kegerreis et al. 2019: 1)\n"
      "  --stretch-a A            latitude stretching a, b = 10 a (default 0.15; paper: 0.2)\n"
      "  --density-iter K         iterations of the shells' placement density against\n"
      "                           their SPH density (default 6; 0: none)\n"
      "  --relax S                steps of relaxation along the shells towards\n"
      "                           SPH density = profile (default 30; 0: none)\n"
      "  --library FILE           material library (default: materials.yml)\n");
}

static const struct option planet_longopts[] = {{"output", required_argument, NULL, 'o'},
                                                {"materials", required_argument, NULL, 0},
                                                {"mass", required_argument, NULL, 0},
                                                {"radius", required_argument, NULL, 0},
                                                {"mass-fractions", required_argument, NULL, 0},
                                                {"layer-radii", required_argument, NULL, 0},
                                                {"P-surface", required_argument, NULL, 0},
                                                {"T-surface", required_argument, NULL, 0},
                                                {"T-rho", required_argument, NULL, 0},
                                                {"n", required_argument, NULL, 0},
                                                {"n-prof", required_argument, NULL, 0},
                                                {"profile", required_argument, NULL, 0},
                                                {"mat-ids", required_argument, NULL, 0},
                                                {"eta", required_argument, NULL, 0},
                                                {"seed", required_argument, NULL, 0},
                                                {"density-iter", required_argument, NULL, 0},
                                                {"relax", required_argument, NULL, 0},
                                                {"shell-thickness", required_argument, NULL, 0},
                                                {"stretch-a", required_argument, NULL, 0},
                                                {"library", required_argument, NULL, 0},
                                                {"help", no_argument, NULL, 'h'},
                                                {NULL, 0, NULL, 0}};

int icgen_planet_main(int argc, char **argv) {
  struct body b;
  body_init(&b, "planet");
  const char *out = "planet.hdf5";
  opterr = 0;
  optind = 1;
  int c, idx;
  while ((c = getopt_long(argc, argv, ":o:h", planet_longopts, &idx)) != -1) {
    if (c == '?') error_exit("planet: unknown option '%s' (see --help)", argv[optind - 1]);
    if (c == ':') error_exit("planet: option '%s' needs a value", argv[optind - 1]);
    if (c == 'h') {
      planet_usage(stdout);
      return 0;
    }
    if (c == 'o')
      out = optarg;
    else
      body_set(&b, planet_longopts[idx].name, optarg);
  }
  if (optind < argc) error_exit("planet: unexpected argument '%s'", argv[optind]);
  body_make(&b, 1, 1);
  if (b.p.count > 0) {
    body_write(out, &b.p, argc, argv, "planet", 0.0);
    printf("bolide-ic planet: %zu particles written to %s\n", b.p.count, out);
  }
  parts_free(&b.p);
  return 0;
}

/** Parse a body specification "KIND,key=value,..." (KIND planet or sphere;
 *  or "file=PATH[,radius=R]"). */
static void body_parse(struct body *b, char *spec) {
  char *save = NULL;
  int first = 1;
  for (char *t = strtok_r(spec, ",", &save); t; t = strtok_r(NULL, ",", &save), first = 0) {
    char *eq = strchr(t, '=');
    if (first && !eq) {
      if (!strcmp(t, "planet"))
        b->kind = 0;
      else if (!strcmp(t, "sphere"))
        b->kind = 1;
      else
        error_exit("%s: expected planet, sphere or file=PATH, got '%s'", b->what, t);
      continue;
    }
    if (!eq) error_exit("%s: expected key=value, got '%s'", b->what, t);
    *eq = '\0';
    body_set(b, t, eq + 1);
  }
}

static void impact_usage(FILE *f) {
  fprintf(f,
          "Usage: bolide-ic impact --target SPEC --impactor SPEC [options]\n"
          "Two bodies on a collision course, in the centre-of-mass frame.  SI units.\n"
          "SPEC is one of\n"
          "  planet,materials=iron:granite,mass-fractions=0.3:0.7,mass=M,n=N[,KEY=VALUE...]\n"
          "      (keys of 'bolide-ic planet', lists separated by ':')\n"
          "  sphere,material=granite,radius=R|mass=M,n=N[,rho=RHO][,u=U|T=T]\n"
          "      (uniform sphere; default rho0 and u = 0)\n"
          "  file=PATH[,radius=R]  (an HDF5 file; radius default: farthest particle)\n"
          "Options:\n"
          "  -o, --output FILE       output (default impact.hdf5)\n"
          "  --v-contact V           relative speed at first contact, or\n"
          "  --v-over-vesc X         ... in units of sqrt(2 G (Mt + Mi) / (Rt + Ri))\n"
          "  --angle DEG             angle at contact between the relative velocity and the\n"
          "                          line of centres (0 head-on; default 45), or\n"
          "  --b B                   impact parameter sin(angle)\n"
          "  --separation D          centre distance at the start (default 3 (Rt + Ri)), or\n"
          "  --time T                time before contact at the start\n"
          "  --v-start V --b-start B  instead of the contact speed and angle: relative speed\n"
          "                          and impact parameter (distance of the initial velocity\n"
          "                          line from the target centre) at --separation\n"
          "  --impactor-mat-offset K add K to the impactor's material ids (default 0)\n"
          "  --time-end T            the run's TimeIntegration:time_end: the box holds\n"
          "                          material that moves away from the centre of mass at\n"
          "                          up to twice the larger of the contact and escape\n"
          "                          speeds until then (the ejecta; particles leaving an\n"
          "                          open box are removed from the run)\n"
          "Particle ids: target 1..Nt, impactor Nt+1..Nt+Ni.  At contact the impactor\n"
          "moves along +x; the orbit lies in the x-y plane.  The centre of mass is at\n"
          "the centre of the box (/Header/BoxSize: 4 x the largest coordinate, or\n"
          "larger with --time-end); the chosen box is printed.\n");
}

static const struct option impact_longopts[] = {{"output", required_argument, NULL, 'o'},
                                                {"target", required_argument, NULL, 1},
                                                {"impactor", required_argument, NULL, 2},
                                                {"v-contact", required_argument, NULL, 3},
                                                {"v-over-vesc", required_argument, NULL, 4},
                                                {"angle", required_argument, NULL, 5},
                                                {"b", required_argument, NULL, 6},
                                                {"separation", required_argument, NULL, 7},
                                                {"time", required_argument, NULL, 8},
                                                {"impactor-mat-offset", required_argument, NULL, 9},
                                                {"v-start", required_argument, NULL, 10},
                                                {"b-start", required_argument, NULL, 11},
                                                {"time-end", required_argument, NULL, 12},
                                                {"help", no_argument, NULL, 'h'},
                                                {NULL, 0, NULL, 0}};

int icgen_impact_main(int argc, char **argv) {
  struct body t, im;
  body_init(&t, "target");
  body_init(&im, "impactor");
  const char *out = "impact.hdf5";
  double v_c = -1, v_rel = -1, angle = 45, bimp = -1, d0 = -1, t0 = -1, v0 = -1, b0 = -1;
  double t_end = -1;
  int angle_given = 0;
  long mat_off = 0;
  int have_t = 0, have_i = 0;
  opterr = 0;
  optind = 1;
  int c;
  while ((c = getopt_long(argc, argv, ":o:h", impact_longopts, NULL)) != -1) {
    if (c == '?') error_exit("impact: unknown option '%s' (see --help)", argv[optind - 1]);
    if (c == ':') error_exit("impact: option '%s' needs a value", argv[optind - 1]);
    switch (c) {
      case 'h':
        impact_usage(stdout);
        return 0;
      case 'o':
        out = optarg;
        break;
      case 1:
        body_parse(&t, optarg), have_t = 1;
        break;
      case 2:
        body_parse(&im, optarg), have_i = 1;
        break;
      case 3:
        v_c = body_real(&t, "--v-contact", optarg, 0);
        break;
      case 4:
        v_rel = body_real(&t, "--v-over-vesc", optarg, 0);
        break;
      case 5:
        angle = body_real(&t, "--angle", optarg, 0);
        if (angle >= 90) error_exit("impact: --angle must be below 90 degrees");
        angle_given = 1;
        break;
      case 6:
        bimp = body_real(&t, "--b", optarg, 0);
        if (bimp >= 1) error_exit("impact: --b must be below 1");
        break;
      case 7:
        d0 = body_real(&t, "--separation", optarg, 1e-300);
        break;
      case 8:
        t0 = body_real(&t, "--time", optarg, 0);
        break;
      case 9:
        mat_off = (long)body_real(&t, "--impactor-mat-offset", optarg, 0);
        break;
      case 10:
        v0 = body_real(&t, "--v-start", optarg, 1e-300);
        break;
      case 11:
        b0 = body_real(&t, "--b-start", optarg, 0);
        break;
      case 12:
        t_end = body_real(&t, "--time-end", optarg, 1e-300);
        break;
    }
  }
  if (optind < argc) error_exit("impact: unexpected argument '%s'", argv[optind]);
  if (!have_t || !have_i) error_exit("impact: --target and --impactor are required");
  const int start_mode = v0 > 0 || b0 >= 0;
  if (start_mode) {
    if (!(v0 > 0) || !(b0 >= 0)) error_exit("impact: --v-start and --b-start go together");
    if (v_c >= 0 || v_rel >= 0 || angle_given || bimp >= 0 || t0 >= 0)
      error_exit(
          "impact: --v-start/--b-start replace --v-contact, --v-over-vesc, --angle, --b "
          "and --time");
    if (!(d0 > 0)) error_exit("impact: --v-start/--b-start need --separation");
    if (b0 >= d0) error_exit("impact: --b-start must be below --separation");
  } else if ((v_c >= 0) == (v_rel >= 0)) {
    error_exit("impact: give one of --v-contact and --v-over-vesc (or --v-start and --b-start)");
  }
  if (d0 > 0 && t0 >= 0) error_exit("impact: give --separation or --time, not both");
  body_make(&t, 1, 1);
  body_make(&im, 1 + (int64_t)t.p.count, 1);
  if (t.p.count == 0 || im.p.count == 0) error_exit("impact: a body has no particles");
  struct unit_system si;
  units_init_si(&si);
  const double G = units_G(&si);
  const double Mt = t.M, Mi = im.M, d_c = t.R + im.R, mu = G * (Mt + Mi);
  const double v_esc = sqrt(2 * mu / d_c);
  double theta = bimp >= 0 ? asin(bimp) : angle * M_PI / 180;
  if (start_mode) {
    /* the same orbit through the contact point: energy and angular momentum
     * of the start state (theory/planets.md) */
    if (d0 < d_c) error_exit("impact: the initial separation is smaller than R_t + R_i");
    const double E = 0.5 * v0 * v0 - mu / d0;
    v_c = sqrt(2 * (E + mu / d_c));
    const double sin_c = b0 * v0 / (d_c * v_c);
    if (!(sin_c < 1))
      error_exit("impact: with --b-start %g m the bodies pass %g m apart, beyond R_t + R_i = %g m",
                 b0, d_c * sin_c, d_c);
    theta = asin(sin_c);
  }
  if (v_c < 0) v_c = v_rel * v_esc;
  if (d0 <= 0 && t0 < 0) d0 = 3 * d_c;
  double s[6];
  const double t_contact = ic_impact_start(mu, d_c, v_c, theta, d0, t0, s);
  /* centre-of-mass frame: target at -Mi/M r, impactor at +Mt/M r */
  const double ft = -Mi / (Mt + Mi), fi = Mt / (Mt + Mi);
  struct parts all;
  parts_alloc(&all, t.p.count + im.p.count);
  const struct parts *src[2] = {&t.p, &im.p};
  const double f[2] = {ft, fi};
  size_t k = 0;
  for (int bi = 0; bi < 2; bi++)
    for (size_t i = 0; i < src[bi]->count; i++, k++) {
      const struct parts *q = src[bi];
      all.x[k] = q->x[i] + f[bi] * s[0], all.y[k] = q->y[i] + f[bi] * s[1];
      all.z[k] = q->z[i] + f[bi] * s[2];
      all.vx[k] = q->vx[i] + f[bi] * s[3], all.vy[k] = q->vy[i] + f[bi] * s[4];
      all.vz[k] = q->vz[i] + f[bi] * s[5];
      all.m[k] = q->m[i], all.h[k] = q->h[i], all.rho[k] = q->rho[i], all.u[k] = q->u[i];
      all.mat[k] = q->mat[i] + (bi == 1 ? (int32_t)mat_off : 0);
      all.id[k] = q->id[i];
    }
  all.count = k;
  /* the box: material leaving an open box is removed from the run (its
   * energy and momenta are counted in the statistics' *_removed columns,
   * but a planetary user wants the ejecta kept); with --time-end it holds
   * what moves away from the centre of mass at up to twice the larger of
   * the contact and escape speeds (faster jets are rare: 0.4% of the
   * particles left a 4 x extent box after 3000 s of a 45-degree impact at
   * 1.9 v_esc) */
  double ext = 0;
  for (size_t i = 0; i < all.count; i++)
    ext = fmax(ext, fmax(fabs(all.x[i]), fmax(fabs(all.y[i]), fabs(all.z[i]))));
  const double v_eject = 2 * fmax(v_c, v_esc);
  const double box =
      body_write(out, &all, argc, argv, "impact", t_end > 0 ? ext + v_eject * t_end : 0.0);
  printf("impact: v_esc = %.8e m/s, contact: v = %.8e m/s, angle = %.6f deg, d = %.8e m\n", v_esc,
         v_c, theta * 180 / M_PI, d_c);
  printf("impact: start %.8e s before contact, separation %.8e m, v_rel %.8e m/s\n", t_contact,
         sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]),
         sqrt(s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
  if (t_end > 0)
    printf(
        "impact: box %.4e m: holds material moving away at up to %.4e m/s (twice the larger of "
        "the contact and escape speeds) for --time-end %g s\n",
        box, v_eject, t_end);
  else
    printf(
        "impact: box %.4e m (4 x the largest coordinate): material faster than %.4e m/s leaves it "
        "after %.4e s; give --time-end for a box that holds the ejecta to the end of the run\n",
        box, v_eject, (0.5 * box - ext) / v_eject);
  printf("bolide-ic impact: %zu particles (target ids 1..%zu, impactor %zu..%zu) written to %s\n",
         all.count, t.p.count, t.p.count + 1, all.count, out);
  parts_free(&all), parts_free(&t.p), parts_free(&im.p);
  return 0;
}
