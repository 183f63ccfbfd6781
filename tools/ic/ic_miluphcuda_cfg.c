/* bolide-ic miluphcuda-materials: miluphcuda's libconfig material file
 * (material.cfg) as a Bolide `Materials` section (issue 23 item 7).
 *
 * miluphcuda reads, per material of the list `materials`, its ID, the
 * equation of state (eos.type and the keys of that EOS in the group eos) and
 * the strength and porosity parameters (also in eos); which strength model
 * applies is one of its compile-time switches (parameter.h), given here as
 * --plasticity.  The mapping, with what differs, is the table of
 * theory/miluphcuda.md.  Every key that is not converted is named, with why,
 * in a comment of the output and in a note on stderr.  Built only with
 * libconfig (configure: HAVE_LIBCONFIG); without it the subcommand says so. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "config.h"
#include "src/error.h"
#include "tools/ic/ic_impact.h"

static void milucfg_usage(FILE *f) {
  fprintf(f,
          "Usage: bolide-ic miluphcuda-materials MATERIAL.cfg [options]\n"
          "Convert miluphcuda's libconfig material file into a Bolide Materials section\n"
          "(YAML, SI; paste it into the parameter file).  @include paths are relative to\n"
          "the folder of MATERIAL.cfg.  miluphcuda's compile-time switches are options:\n"
          "  -o, --output FILE      write the YAML to FILE (default: standard output)\n"
          "  --plasticity MODEL     the plasticity switch miluphcuda was built with:\n"
          "                         none (default: strength elastic where shear_modulus > 0),\n"
          "                         von_mises, drucker_prager, mohr_coulomb, collins,\n"
          "                         collins_simple or johnson_cook\n"
          "  --von-mises-limit      VON_MISES_PLASTICITY as well (drucker_prager,\n"
          "                         mohr_coulomb): yield_stress caps the strength\n"
          "  --fragmentation        FRAGMENTATION 1: convert fragmentation.weibull_k/m\n"
          "                         (Bolide draws flaws from them at start-up)\n"
          "  --hydro                HYDRO 1 (SOLID 0): every material a fluid\n"
          "  -h, --help             this help\n"
          "miluphcuda's pressure-dependent yield strengths are limits of sqrt(J2), Bolide's\n"
          "of sqrt(3 J2): their cohesions, frictions and limits are multiplied by sqrt(3).\n"
          "Keys without a counterpart are listed as comments and notes; an EOS Bolide\n"
          "does not have is an error.  Table: theory/miluphcuda.md.\n");
}

#ifndef HAVE_LIBCONFIG

int icgen_miluphcuda_cfg_main(int argc, char **argv) {
  if (argc > 1 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
    milucfg_usage(stdout);
    return 0;
  }
  error_exit(
      "miluphcuda-materials: this bolide-ic was built without libconfig (configure found no "
      "libconfig; Debian: apt-get install libconfig-dev, then configure again)");
}

#else
#include <libconfig.h>

enum milucfg_plasticity {
  PL_NONE,
  PL_VON_MISES,
  PL_DRUCKER_PRAGER,
  PL_MOHR_COULOMB,
  PL_COLLINS,
  PL_COLLINS_SIMPLE,
  PL_JOHNSON_COOK
};
static const char *const milucfg_plasticity_names[] = {
    "none",    "von_mises",      "drucker_prager", "mohr_coulomb",
    "collins", "collins_simple", "johnson_cook"};

/** The conversion's state: options, output, the keys used so far. */
struct milucfg {
  enum milucfg_plasticity plasticity;
  int von_mises_limit, fragmentation, hydro;
  FILE *out;
  const char *file;
  const config_setting_t *used[256];
  int nused;
  int errors;
  char dropped[4096]; /* the keys of this material not converted, for its comment */
};

static void milucfg_use(struct milucfg *c, const config_setting_t *s) {
  if (c->nused < (int)(sizeof c->used / sizeof c->used[0])) c->used[c->nused++] = s;
}

static int milucfg_was_used(const struct milucfg *c, const config_setting_t *s) {
  for (int i = 0; i < c->nused; i++)
    if (c->used[i] == s) return 1;
  return 0;
}

/** Number `name` of group g into *v (int or float; miluphcuda reads floats
 *  only, an integer there gets its default: warned).  0 when absent. */
static int milucfg_num(struct milucfg *c, const config_setting_t *g, const char *name, double *v) {
  if (!g) return 0;
  config_setting_t *s = config_setting_get_member(g, name);
  if (!s) return 0;
  const int again = milucfg_was_used(c, s); /* warn once */
  if (!again) milucfg_use(c, s);
  switch (config_setting_type(s)) {
    case CONFIG_TYPE_FLOAT:
      *v = config_setting_get_float(s);
      return 1;
    case CONFIG_TYPE_INT:
    case CONFIG_TYPE_INT64:
      *v = (double)config_setting_get_int64(s);
      if (!again && strcmp(name, "type") != 0 && strcmp(name, "ID") != 0 &&
          strcmp(name, "crushcurve_style") != 0 && strcmp(name, "interactions") != 0 &&
          strcmp(name, "n_rho") != 0 && strcmp(name, "n_e") != 0)
        error_warning(
            "%s:%d: %s = %lld is an integer: miluphcuda reads floats only (libconfig) and "
            "takes its default instead; converted as written (write %lld.0 for miluphcuda)",
            c->file, config_setting_source_line(s), name, (long long)*v, (long long)*v);
      return 1;
    default:
      if (!again) {
        error_warning("%s:%d: %s is not a number: not converted", c->file,
                      config_setting_source_line(s), name);
        c->errors++;
      }
      return 0;
  }
}

/** Write "    KEY: VALUE" (%.15g: the decimal the file gave). */
static void milucfg_put(struct milucfg *c, const char *key, double v) {
  fprintf(c->out, "    %s: %.15g\n", key, v);
}

/** Convert a number if present; returns whether it was. */
static int milucfg_copy(struct milucfg *c, const config_setting_t *g, const char *from,
                        const char *to, double factor) {
  double v;
  if (!milucfg_num(c, g, from, &v)) return 0;
  milucfg_put(c, to, v * factor);
  return 1;
}

/** The reason a key of miluphcuda's has no counterpart in Bolide (NULL: an
 *  unknown key). */
static const char *milucfg_why(const char *key) {
  static const struct {
    const char *key, *why;
  } why[] = {
      {"sml", "h follows the density (SPH:resolution_eta)"},
      {"interactions", "h follows the density (SPH:resolution_eta)"},
      {"factor_sml_min", "h is bounded by SPH:h_max only"},
      {"factor_sml_max", "h is bounded by SPH:h_max only"},
      {"energy_floor", "no energy floor per material"},
      {"artificial_viscosity", "run-wide in Bolide: SPH:viscosity_alpha, SPH:viscosity_beta"},
      {"alpha", "run-wide in Bolide: SPH:viscosity_alpha"},
      {"beta", "run-wide in Bolide: SPH:viscosity_beta"},
      {"low_density_weakening", "no low-density weakening in Bolide"},
      {"fast_integration", "no fast integration scheme in Bolide"},
      {"density_via_kernel_sum", "run-wide in Bolide: SPH:density"},
      {"cs_porous",
       "Bolide's porous sound speed is the matrix's (its c_s, c_e also switch on elastic "
       "compaction, which miluphcuda has not)"},
      {"porepsilon_epsilon_c", "Bolide derives eps_c from the other eps-alpha parameters"},
      {"fragmentation", "FRAGMENTATION not given (--fragmentation)"},
      {"weibull_k", "FRAGMENTATION not given (--fragmentation)"},
      {"weibull_m", "FRAGMENTATION not given (--fragmentation)"},
      {"shear_modulus", "a fluid (--hydro or no strength)"},
      {"yield_stress", "not used by the plasticity model given (--plasticity)"},
      {"cohesion", "not used by the plasticity model given (--plasticity)"},
      {"friction_angle", "not used by the plasticity model given (--plasticity)"},
      {"cohesion_damaged", "not used by the plasticity model given (--plasticity)"},
      {"friction_angle_damaged", "not used by the plasticity model given (--plasticity)"},
      {"melt_energy", "not used by the plasticity model given (--plasticity)"},
      {"exponent_tensor", "run-wide in Bolide: SPH:artificial_stress_n"},
      {"epsilon_stress", "run-wide in Bolide: SPH:artificial_stress_epsilon"},
      {"nu", "kinematic viscosity: Bolide's viscosity is dynamic (Pa s), per fluid material"},
      {"alpha_shakura", "no Shakura-Sunyaev viscosity in Bolide"},
      {"eta", "no bulk viscosity in Bolide"},
      {"zeta", "no bulk viscosity in Bolide"},
      {"aneos_e_norm", "Bolide's initial conditions take u from the particle file"},
      {"aneos_molar_mass", "no ideal-gas fallback above a table: Bolide clamps to its edge"},
      {"aneos_gamma", "no ideal-gas fallback above a table: Bolide clamps to its edge"},
  };
  for (size_t i = 0; i < sizeof why / sizeof why[0]; i++)
    if (strcmp(why[i].key, key) == 0) return why[i].why;
  return NULL;
}

/** Note every member of group g (recursively) that was not converted. */
static void milucfg_report_unused(struct milucfg *c, const config_setting_t *g, const char *path,
                                  int id) {
  const int n = config_setting_length(g);
  for (int i = 0; i < n; i++) {
    const config_setting_t *s = config_setting_get_elem(g, (unsigned)i);
    const char *name = config_setting_name(s);
    if (!name) continue;
    char full[256];
    snprintf(full, sizeof full, "%s%s%s", path, path[0] ? "." : "", name);
    if (config_setting_type(s) == CONFIG_TYPE_GROUP) {
      milucfg_report_unused(c, s, full, id);
      continue;
    }
    if (milucfg_was_used(c, s)) continue;
    const char *why = milucfg_why(name);
    error_note("%s:%d: material %d: %s not converted: %s", c->file, config_setting_source_line(s),
               id, full, why ? why : "not a key Bolide knows of miluphcuda's");
    const size_t l = strlen(c->dropped);
    snprintf(c->dropped + l, sizeof c->dropped - l, "%s%s", l ? ", " : "", full);
  }
}

/** The P-alpha porosity of a type 5/6 material (miluphcuda's crush curve,
 *  scaled to pass through alpha_0, in Bolide's unscaled form: alpha_e =
 *  alpha_0, alpha_t rescaled; theory/porosity.md PA2). */
static void milucfg_palpha(struct milucfg *c, const config_setting_t *eos, int id) {
  double a0 = 1, ae = 1, at = 1, pe = 0, pt = 0, ps = 0, n1 = 0, n2 = 0, style = 0;
  milucfg_num(c, eos, "porjutzi_alpha_0", &a0);
  milucfg_num(c, eos, "porjutzi_alpha_e", &ae);
  milucfg_num(c, eos, "porjutzi_alpha_t", &at);
  milucfg_num(c, eos, "porjutzi_p_elastic", &pe);
  milucfg_num(c, eos, "porjutzi_p_transition", &pt);
  milucfg_num(c, eos, "porjutzi_p_compacted", &ps);
  milucfg_num(c, eos, "porjutzi_n1", &n1);
  milucfg_num(c, eos, "porjutzi_n2", &n2);
  milucfg_num(c, eos, "crushcurve_style", &style);
  if (style != 0 && style != 1) {
    /* miluphcuda's src/pressure.cu: 2 (Blum et al. 2023) and 3, 4 (Malamud
     * et al. 2023) are fitted laws with constants fixed in the code, not of
     * the keys above; Bolide's crush curve (theory/porosity.md PA2) has
     * another form (theory/miluphcuda.md) */
    error_warning(
        "%s:%d: material %d: eos.crushcurve_style = %g cannot be converted: miluphcuda's "
        "measured crush curves 2-4 (constants fixed in its pressure.cu) are not of Bolide's "
        "P-alpha form (crush curves 0 and 1 only)",
        c->file, config_setting_source_line(config_setting_get_member(eos, "crushcurve_style")), id,
        style);
    c->errors++;
    return;
  }
  fprintf(c->out, "    porosity:   # P-alpha, crush curve %s\n",
          style == 0 ? "0 (quadratic)" : "1 (Jutzi et al. 2009)");
  fprintf(c->out, "      model: palpha\n      alpha_0: %.15g\n      alpha_e: %.15g\n", a0, a0);
  fprintf(c->out, "      p_e: %.15g\n      p_s: %.15g\n", pe, ps);
  if (style == 1) {
    /* miluphcuda: 1 + (a0-1)/(ae-1) [(ae-at) A + (at-1) B]; Bolide with
     * alpha_e = a0: 1 + (a0-at') A + (at'-1) B, equal for at' below */
    const double at2 = ae > 1 ? 1 + (at - 1) * (a0 - 1) / (ae - 1) : at;
    fprintf(c->out, "      alpha_t: %.15g   # 1 + (alpha_t - 1)(alpha_0 - 1)/(alpha_e - 1)\n", at2);
    fprintf(c->out, "      p_t: %.15g\n      n1: %.15g\n      n2: %.15g\n", pt, n1, n2);
  }
}

/** The strength keys of the material under the plasticity switch given;
 *  returns whether it is a solid. */
static int milucfg_strength(struct milucfg *c, const config_setting_t *eos, int id) {
  double mu_shear = 0;
  const int has_mu = milucfg_num(c, eos, "shear_modulus", &mu_shear);
  if (c->hydro || !has_mu || !(mu_shear > 0)) {
    if (c->plasticity != PL_NONE && !c->hydro)
      error_note("%s: material %d: no shear_modulus: a fluid (no strength)", c->file, id);
    if (has_mu && c->hydro) {
      /* listed as not converted */
      c->used[--c->nused] = NULL;
    }
    return 0;
  }
  milucfg_put(c, "shear_modulus", mu_shear);
  const double r3 = sqrt(3.0); /* sqrt(J2) -> sqrt(3 J2) */
  double v, phi;
  switch (c->plasticity) {
    case PL_NONE:
      fprintf(c->out, "    strength: elastic\n");
      break;
    case PL_VON_MISES:
      fprintf(c->out, "    strength: von_mises\n");
      milucfg_copy(c, eos, "yield_stress", "yield_stress", 1.0);
      break;
    case PL_DRUCKER_PRAGER: {
      /* miluphcuda: sqrt(J2) <= A + 3 B P with A = 6 c cos(phi) / (sqrt3 (3 - sin phi)),
       * B = 2 sin(phi) / (sqrt3 (3 - sin phi)) */
      double coh = 0;
      phi = 0;
      milucfg_num(c, eos, "cohesion", &coh);
      milucfg_num(c, eos, "friction_angle", &phi);
      fprintf(c->out, "    strength: drucker_prager   # Y0, mu from cohesion, friction_angle\n");
      milucfg_put(c, "yield_stress", 6 * coh * cos(phi) / (3 - sin(phi)));
      milucfg_put(c, "friction_intact", 6 * sin(phi) / (3 - sin(phi)));
      if (c->von_mises_limit && milucfg_num(c, eos, "yield_stress", &v))
        milucfg_put(c, "yield_stress_max", r3 * v);
      else
        fprintf(c->out, "    yield_stress_max: 1e30   # no limit (no VON_MISES_PLASTICITY)\n");
      break;
    }
    case PL_MOHR_COULOMB:
      fprintf(c->out, "    strength: mohr_coulomb\n");
      milucfg_copy(c, eos, "cohesion", "yield_stress", r3);
      if (milucfg_num(c, eos, "friction_angle", &phi))
        milucfg_put(c, "friction_intact", r3 * tan(phi));
      if (c->von_mises_limit) milucfg_copy(c, eos, "yield_stress", "yield_stress_max", r3);
      break;
    case PL_COLLINS:
    case PL_COLLINS_SIMPLE:
      fprintf(c->out, "    strength: collins\n");
      milucfg_copy(c, eos, "cohesion", "yield_stress", r3);
      if (milucfg_num(c, eos, "friction_angle", &phi))
        milucfg_put(c, "friction_intact", r3 * tan(phi));
      milucfg_copy(c, eos, "yield_stress", "yield_stress_max", r3);
      if (c->plasticity == PL_COLLINS) {
        milucfg_copy(c, eos, "cohesion_damaged", "cohesion_damaged", r3);
        if (milucfg_num(c, eos, "friction_angle_damaged", &phi))
          milucfg_put(c, "friction_damaged", r3 * tan(phi));
        milucfg_copy(c, eos, "melt_energy", "melt_energy", 1.0);
      }
      break;
    case PL_JOHNSON_COOK:
      fprintf(c->out, "    strength: johnson_cook\n");
      milucfg_copy(c, eos, "jc_y0", "jc_A", 1.0);
      milucfg_copy(c, eos, "jc_B", "jc_B", 1.0);
      milucfg_copy(c, eos, "jc_C", "jc_C", 1.0);
      milucfg_copy(c, eos, "jc_m", "jc_m", 1.0);
      milucfg_copy(c, eos, "jc_n", "jc_n", 1.0);
      milucfg_copy(c, eos, "jc_edot0", "jc_strain_rate_ref", 1.0);
      milucfg_copy(c, eos, "jc_Tref", "T_ref", 1.0);
      milucfg_copy(c, eos, "jc_Tmelt", "T_melt", 1.0);
      milucfg_copy(c, eos, "CV", "specific_heat", 1.0);
      break;
  }
  return 1;
}

/** One material: returns 0 when it could not be converted. */
static int milucfg_material(struct milucfg *c, const config_setting_t *m, int *id_out) {
  c->nused = 0;
  c->dropped[0] = '\0';
  const int line = config_setting_source_line(m);
  double idv;
  if (!milucfg_num(c, m, "ID", &idv) || idv < 0 || idv != floor(idv)) {
    error_warning("%s:%d: a material without an integer ID >= 0", c->file, line);
    c->errors++;
    return 0;
  }
  const int id = (int)idv;
  *id_out = id;
  const config_setting_t *eos = config_setting_get_member(m, "eos");
  double type;
  if (!eos || !milucfg_num(c, eos, "type", &type)) {
    error_warning("%s:%d: material %d: no eos.type", c->file, line, id);
    c->errors++;
    return 0;
  }
  const char *name = NULL;
  config_setting_t *ns = config_setting_get_member(m, "name");
  if (ns && config_setting_type(ns) == CONFIG_TYPE_STRING) {
    name = config_setting_get_string(ns);
    milucfg_use(c, ns);
  }
  static const char *const types[] = {"polytropic gas",
                                      "Murnaghan",
                                      "Tillotson",
                                      "isothermal gas",
                                      "regolith (Bui et al. 2008)",
                                      "Tillotson + P-alpha",
                                      "Murnaghan + P-alpha",
                                      "ANEOS",
                                      "viscous regolith",
                                      "ideal gas",
                                      "Sirono porosity",
                                      "Tillotson + eps-alpha",
                                      "locally isothermal gas",
                                      "ANEOS + P-alpha"};
  const int t = (int)type;
  const char *tname = t >= 0 && t <= 13 ? types[t] : "unknown";
  fprintf(c->out, "  %d:   # %s%s%s, eos.type %d (%s)\n", id, name ? "\"" : "",
          name ? name : "(no name)", name ? "\"" : "", t, tname);
  double v;
  switch (t) {
    case 0: { /* P = K rho^gamma */
      double K = 0, g = 0;
      milucfg_num(c, eos, "polytropic_K", &K);
      milucfg_num(c, eos, "polytropic_gamma", &g);
      fprintf(c->out, "    eos: polytropic   # P = P0 (rho/rho0)^gamma, P0 = K at rho0 = 1\n");
      milucfg_put(c, "gamma", g);
      milucfg_put(c, "rho0", 1.0);
      milucfg_put(c, "P0", K);
      break;
    }
    case 9:
      fprintf(c->out, "    eos: ideal_gas\n");
      milucfg_copy(c, eos, "polytropic_gamma", "gamma", 1.0);
      break;
    case 3:
    case 12:
      fprintf(c->out, "    eos: isothermal\n");
      if (!milucfg_copy(c, eos, "isothermal_soundspeed", "cs", 1.0)) {
        error_warning(
            "%s:%d: material %d: an isothermal gas without isothermal_soundspeed "
            "(miluphcuda takes the sound speed from the particles): give cs by hand",
            c->file, line, id);
        c->errors++;
      }
      break;
    case 1:
    case 6:
      fprintf(c->out, "    eos: murnaghan\n");
      milucfg_copy(c, eos, "rho_0", "rho0", 1.0);
      milucfg_copy(c, eos, "bulk_modulus", "K0", 1.0);
      if (!milucfg_copy(c, eos, "n", "n", 1.0)) milucfg_put(c, "n", 1.0);
      if (!milucfg_copy(c, eos, "rho_limit", "eta_limit", 1.0))
        fprintf(c->out, "    eta_limit: 0.9   # miluphcuda's default rho_limit\n");
      break;
    case 2:
    case 5:
    case 11: {
      static const char *const till[][2] = {
          {"till_rho_0", "rho0"},  {"till_A", "A"},      {"till_B", "B"}, {"till_E_0", "E0"},
          {"till_E_iv", "Eiv"},    {"till_E_cv", "Ecv"}, {"till_a", "a"}, {"till_b", "b"},
          {"till_alpha", "alpha"}, {"till_beta", "beta"}};
      fprintf(c->out, "    eos: tillotson\n");
      double rho0 = 0, A = 0;
      for (size_t k = 0; k < sizeof till / sizeof till[0]; k++)
        if (!milucfg_copy(c, eos, till[k][0], till[k][1], 1.0)) {
          error_warning("%s:%d: material %d: eos.%s missing (miluphcuda's default 0)", c->file,
                        line, id, till[k][0]);
          milucfg_put(c, till[k][1], 0.0);
        }
      milucfg_num(c, eos, "till_rho_0", &rho0);
      milucfg_num(c, eos, "till_A", &A);
      double lim = 0.9;
      milucfg_num(c, eos, "rho_limit", &lim);
      fprintf(c->out,
              "    eta_min: %.15g   # miluphcuda's rho_limit%s: P_c falls to 0 from eta_min\n"
              "    eta_zero: %.15g   # to eta_zero (miluphcuda: P = 0 below it for u < Ecv)\n",
              lim, config_setting_get_member(eos, "rho_limit") ? "" : " (its default)",
              lim * 0.999);
      if (milucfg_num(c, eos, "cs_limit", &v))
        milucfg_put(c, "cs_min", v);
      else if (rho0 > 0 && A > 0)
        fprintf(c->out, "    cs_min: %.15g   # miluphcuda's default: 1%% of sqrt(A/rho0)\n",
                0.01 * sqrt(A / rho0));
      break;
    }
    case 7:
    case 13: { /* ANEOS (13: + P-alpha): its lookup table, read as format miluphcuda */
      config_setting_t *tp = config_setting_get_member(eos, "table_path");
      if (!tp || config_setting_type(tp) != CONFIG_TYPE_STRING) {
        error_warning("%s:%d: material %d: ANEOS without a string eos.table_path", c->file, line,
                      id);
        c->errors++;
        return 0;
      }
      milucfg_use(c, tp);
      fprintf(c->out,
              "    eos: table   # miluphcuda's ANEOS lookup table\n"
              "    format: miluphcuda\n"
              "    file: \"%s\"   # Bolide: relative to the YAML file (miluphcuda: to the "
              "run's folder)\n",
              config_setting_get_string(tp));
      milucfg_copy(c, eos, "n_rho", "n_rho", 1.0);
      milucfg_copy(c, eos, "n_e", "n_e", 1.0);
      double rho0 = 0;
      if (milucfg_num(c, eos, "aneos_rho_0", &rho0)) milucfg_put(c, "rho0", rho0);
      double bulk_cs = 0;
      const int have_cs = milucfg_num(c, eos, "aneos_bulk_cs", &bulk_cs);
      if (milucfg_num(c, eos, "cs_limit", &v))
        milucfg_put(c, "cs_min", v);
      else if (have_cs && bulk_cs > 0)
        fprintf(c->out, "    cs_min: %.15g   # miluphcuda's default: 1%% of aneos_bulk_cs\n",
                0.01 * bulk_cs);
      /* above the table's last energy: miluphcuda's ideal gas of aneos_gamma
       * (theory/eos.md T1) */
      if (milucfg_num(c, eos, "aneos_gamma", &v) && v > 1.0)
        milucfg_put(c, "gamma_vapor", v);
      else
        error_note(
            "%s:%d: material %d: no eos.aneos_gamma > 1: miluphcuda's ideal-gas fallback above "
            "the table's last energy would use gamma = %g; Bolide clamps e to that energy "
            "(give gamma_vapor for the fallback)",
            c->file, line, id, config_setting_get_member(eos, "aneos_gamma") ? v : 0.0);
      break;
    }
    default:
      error_warning("%s:%d: material %d: eos.type %d (%s) has no Bolide equation of state", c->file,
                    config_setting_source_line(config_setting_get_member(eos, "type")), id, t,
                    tname);
      c->errors++;
      return 0;
  }
  if (t == 5 || t == 6 || t == 13) milucfg_palpha(c, eos, id);
  if (t == 11) {
    fprintf(c->out, "    porosity:   # eps-alpha\n      model: epsalpha\n");
    static const char *const ea[][2] = {{"porepsilon_alpha_0", "alpha_0"},
                                        {"porepsilon_epsilon_e", "eps_e"},
                                        {"porepsilon_epsilon_x", "eps_x"},
                                        {"porepsilon_kappa", "kappa"}};
    for (size_t k = 0; k < sizeof ea / sizeof ea[0]; k++)
      if (milucfg_num(c, eos, ea[k][0], &v)) fprintf(c->out, "      %s: %.15g\n", ea[k][1], v);
  }
  if (milucfg_num(c, m, "density_floor", &v)) milucfg_put(c, "density_floor", v);
  /* (Bolide's default bulk modulus is rho0 c^2 of the EOS; miluphcuda's is
   * given: its crack growth speed and sound speed estimates use it) */
  if (!c->hydro && milucfg_num(c, eos, "bulk_modulus", &v)) milucfg_put(c, "bulk_modulus", v);
  if (milucfg_strength(c, eos, id) && c->fragmentation) {
    const config_setting_t *fr = config_setting_get_member(m, "fragmentation");
    double k = 0, mm = 0;
    if (milucfg_num(c, fr, "weibull_k", &k) && milucfg_num(c, fr, "weibull_m", &mm)) {
      milucfg_put(c, "weibull_k", k);
      milucfg_put(c, "weibull_m", mm);
    } else {
      error_warning(
          "%s:%d: material %d: --fragmentation but no fragmentation.weibull_k and "
          "weibull_m: no flaws",
          c->file, line, id);
    }
  }
  milucfg_report_unused(c, m, "", id);
  if (c->dropped[0]) fprintf(c->out, "    # not converted: %s\n", c->dropped);
  return 1;
}

int icgen_miluphcuda_cfg_main(int argc, char **argv) {
  struct milucfg c = {.plasticity = PL_NONE};
  const char *outname = NULL;
  enum { O_PLAST = 400, O_VMLIM, O_FRAG, O_HYDRO };
  static const struct option opts[] = {{"output", required_argument, NULL, 'o'},
                                       {"plasticity", required_argument, NULL, O_PLAST},
                                       {"von-mises-limit", no_argument, NULL, O_VMLIM},
                                       {"fragmentation", no_argument, NULL, O_FRAG},
                                       {"hydro", no_argument, NULL, O_HYDRO},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  opterr = 0;
  optind = 1;
  int o;
  while ((o = getopt_long(argc, argv, ":o:h", opts, NULL)) != -1) {
    switch (o) {
      case 'o':
        outname = optarg;
        break;
      case 'h':
        milucfg_usage(stdout);
        return 0;
      case O_PLAST: {
        int found = -1;
        for (int i = 0; i <= PL_JOHNSON_COOK; i++)
          if (strcmp(optarg, milucfg_plasticity_names[i]) == 0) found = i;
        if (found < 0)
          error_exit(
              "miluphcuda-materials: --plasticity: expected none, von_mises, drucker_prager, "
              "mohr_coulomb, collins, collins_simple or johnson_cook, got '%s'",
              optarg);
        c.plasticity = (enum milucfg_plasticity)found;
        break;
      }
      case O_VMLIM:
        c.von_mises_limit = 1;
        break;
      case O_FRAG:
        c.fragmentation = 1;
        break;
      case O_HYDRO:
        c.hydro = 1;
        break;
      case ':':
        error_exit("miluphcuda-materials: option '%s' needs a value", argv[optind - 1]);
      default:
        error_exit("miluphcuda-materials: unknown option '%s' (see --help)", argv[optind - 1]);
    }
  }
  if (optind != argc - 1)
    error_exit("miluphcuda-materials: expected one material file (see --help)");
  c.file = argv[optind];

  config_t cfg;
  config_init(&cfg);
  char dir[4096];
  snprintf(dir, sizeof dir, "%s", c.file);
  char *slash = strrchr(dir, '/');
  if (slash)
    *slash = '\0';
  else
    snprintf(dir, sizeof dir, ".");
  config_set_include_dir(&cfg, dir);
  if (config_read_file(&cfg, c.file) != CONFIG_TRUE) {
    char msg[1024];
    snprintf(msg, sizeof msg, "%s:%d: %s",
             config_error_file(&cfg) ? config_error_file(&cfg) : c.file, config_error_line(&cfg),
             config_error_text(&cfg));
    config_destroy(&cfg);
    error_exit("miluphcuda-materials: %s", msg);
  }
  const config_setting_t *mats = config_lookup(&cfg, "materials");
  if (!mats || !(config_setting_is_list(mats) || config_setting_is_array(mats)) ||
      config_setting_length(mats) == 0) {
    config_destroy(&cfg);
    error_exit("miluphcuda-materials: %s: no list 'materials = ( {...}, ... );'", c.file);
  }

  /* the YAML goes to a buffer first: nothing is written when a material fails */
  char *buf = NULL;
  size_t len = 0;
  c.out = open_memstream(&buf, &len);
  if (!c.out) error_exit("miluphcuda-materials: out of memory");
  fprintf(c.out,
          "# Bolide Materials converted from miluphcuda's %s by bolide-ic miluphcuda-materials\n"
          "# (plasticity: %s%s%s%s; theory/miluphcuda.md lists what maps to what)\n",
          c.file, milucfg_plasticity_names[c.plasticity], c.von_mises_limit ? " + von_mises" : "",
          c.fragmentation ? ", FRAGMENTATION" : "", c.hydro ? ", HYDRO" : ", SOLID");
  const config_setting_t *global = config_lookup(&cfg, "global");
  double G;
  if (global && milucfg_num(&c, global, "c_gravity", &G) && fabs(G / 6.674e-11 - 1) > 1e-2)
    error_warning(
        "%s: global.c_gravity = %g is not SI: miluphcuda then runs in code units; the "
        "values are written as given, and Bolide's Materials are SI (convert them, or "
        "declare the units in InternalUnitSystem)",
        c.file, G);
  fprintf(c.out, "Materials:\n");
  const int n = config_setting_length(mats);
  int ids[1024], nids = 0;
  double av_alpha = NAN, av_beta = NAN;
  int av_differ = 0;
  for (int i = 0; i < n; i++) {
    const config_setting_t *m = config_setting_get_elem(mats, (unsigned)i);
    if (config_setting_type(m) != CONFIG_TYPE_GROUP) {
      error_warning("%s:%d: an element of 'materials' that is not a group {...}", c.file,
                    config_setting_source_line(m));
      c.errors++;
      continue;
    }
    int id = -1;
    if (milucfg_material(&c, m, &id)) {
      for (int k = 0; k < nids; k++)
        if (ids[k] == id) {
          error_warning("%s:%d: material ID %d given twice", c.file, config_setting_source_line(m),
                        id);
          c.errors++;
        }
      if (nids < 1024) ids[nids++] = id;
    }
    const config_setting_t *av = config_setting_get_member(m, "artificial_viscosity");
    double a, b;
    if (av && config_setting_lookup_float(av, "alpha", &a) == CONFIG_TRUE &&
        config_setting_lookup_float(av, "beta", &b) == CONFIG_TRUE) {
      if (!isnan(av_alpha) && (a != av_alpha || b != av_beta)) av_differ = 1;
      if (isnan(av_alpha)) av_alpha = a, av_beta = b;
    }
  }
  if (!isnan(av_alpha))
    fprintf(c.out,
            "# artificial viscosity (miluphcuda: per material%s) is run-wide in Bolide:\n"
            "#   SPH:\n#     viscosity_alpha: %.15g\n#     viscosity_beta: %.15g\n",
            av_differ ? ", and it differs between them: the first is shown" : "", av_alpha,
            av_beta);
  fclose(c.out);
  config_destroy(&cfg);
  if (c.errors) {
    free(buf);
    error_exit("miluphcuda-materials: %s: %d problem%s above: nothing written", argv[optind],
               c.errors, c.errors > 1 ? "s" : "");
  }
  FILE *f = outname ? fopen(outname, "w") : stdout;
  if (!f) error_exit("miluphcuda-materials: %s: cannot write", outname);
  fwrite(buf, 1, len, f);
  free(buf);
  if (outname && fclose(f) != 0) error_exit("miluphcuda-materials: %s: write failed", outname);
  if (outname)
    fprintf(stderr, "bolide-ic miluphcuda-materials: %d materials written to %s\n", nids, outname);
  return 0;
}
#endif
