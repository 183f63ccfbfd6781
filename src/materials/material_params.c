/* Materials from YAML: the Materials section of a run's parameter file and
 * the material library (examples/materials.yml).  See material.h and
 * examples/parameters.yml.
 *
 *   Materials:
 *     0: {name: basalt}                      # from the default library
 *     1: {name: ice, library: my_lib.yml, weibull_m: 9.1}   # plus overrides
 *     2: {eos: tillotson, name: my_rock, rho0: 2700, A: 2.67e10, ...}  # inline
 *     101: {}                                # SWIFT planetary id: the library
 *                                            # entry with swift_id: 101
 *
 * A material with `eos:` is an inline definition (`name:` is then only its
 * name); without `eos:`, `name:` names a library entry and every other key
 * overrides it; with neither, the library entry whose swift_id equals the
 * material id is used.  Relative paths are relative to the folder of the
 * file that names them. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "src/error.h"
#include "src/materials/material.h"
#include "src/io/params.h"

/** Libraries read while building one table (read each file once). */
#define MATERIAL_MAX_LIBRARIES 8
struct material_libraries {
  int n;                                       /**< libraries read */
  char path[MATERIAL_MAX_LIBRARIES][PATH_MAX]; /**< their paths */
  struct params *lib[MATERIAL_MAX_LIBRARIES];  /**< their trees */
};

/** Extra state of one material while its keys are applied. */
struct material_extra {
  char table_file[PATH_MAX];  /**< file: of a tabulated EOS */
  int table_format;           /**< format: 0 rho_u, 1 rho_T, 2 swift, 3 miluphcuda */
  int table_n_rho, table_n_e; /**< n_rho, n_e of format miluphcuda (0: from the file) */
};

/** path relative to the folder of `ref_file` unless absolute. */
static void material_resolve(const char *ref_file, const char *path, char *out, size_t len) {
  const char *slash = ref_file ? strrchr(ref_file, '/') : NULL;
  if (path[0] == '/' || !slash)
    snprintf(out, len, "%s", path);
  else
    snprintf(out, len, "%.*s/%s", (int)(slash - ref_file), ref_file, path);
}

/** The library of that path, read on first use. */
static struct params *material_library(struct material_libraries *libs, const char *path) {
  for (int i = 0; i < libs->n; i++)
    if (strcmp(libs->path[i], path) == 0) return libs->lib[i];
  if (libs->n == MATERIAL_MAX_LIBRARIES) error_exit("%s: too many material libraries", path);
  snprintf(libs->path[libs->n], PATH_MAX, "%s", path);
  libs->lib[libs->n] = params_read_tree(path);
  return libs->lib[libs->n++];
}

/** Root mapping of a library. */
static const struct param_node *material_library_root(struct params *lib) {
  const struct param_node *root = params_section(lib, "");
  if (!root || param_node_kind(root) != 1)
    error_exit("%s: a material library must be a mapping from material name to parameters",
               params_filename(lib));
  return root;
}

/** Scalar text of a node, or a FILE:LINE error. */
static const char *material_text(const struct params *owner, const struct param_node *n,
                                 const struct material *mat, const char *key) {
  const char *s = param_node_text(n);
  if (!s)
    param_node_error(owner, n, "material '%s': key '%s' must be a single value", mat->name, key);
  return s;
}

/** The `eos:` of a mapping, or -1 if it has none. */
static int material_node_eos(const struct params *owner, const struct param_node *m,
                             const char *name) {
  const struct param_node *e = param_node_get(m, "eos");
  if (!e) return -1;
  const char *s = param_node_text(e);
  const int t = s ? material_eos_from_name(s) : -1;
  if (t < 0) {
    char known[256] = "";
    for (int k = 0; k < EOS_COUNT; k++) {
      strncat(known, k ? "|" : "", sizeof known - strlen(known) - 1);
      strncat(known, material_eos_name((enum material_eos_type)k),
              sizeof known - strlen(known) - 1);
    }
    param_node_error(owner, e, "material '%s': key 'eos' must be one of %s (got '%s')", name, known,
                     s ? s : "?");
  }
  return t;
}

/** Apply every key of mapping m (from file `owner`) to mat.  Keys in `skip`
 *  (a '|'-separated list) are handled by the caller. */
static void material_apply(struct material *mat, struct material_extra *x,
                           const struct params *owner, const struct param_node *m,
                           const char *skip) {
  char what[160], msg[512];
  for (int i = 0; i < param_node_count(m); i++) {
    const char *key = param_node_key(m, i);
    const struct param_node *v = param_node_child(m, i);
    char pat[80];
    snprintf(pat, sizeof pat, "|%s|", key);
    if (skip && strstr(skip, pat)) continue;
    if (strcmp(key, "reference") == 0) {
      snprintf(mat->reference, sizeof mat->reference, "%s", material_text(owner, v, mat, key));
    } else if (strcmp(key, "swift_id") == 0) {
      snprintf(what, sizeof what, "material '%s': key 'swift_id'", mat->name);
      const long id = param_node_int(owner, v, what);
      if (id < 0 || id > INT32_MAX)
        param_node_error(owner, v, "material '%s': key 'swift_id' must be >= 0", mat->name);
      mat->swift_id = (int32_t)id;
    } else if (strcmp(key, "strength") == 0) {
      const char *s = material_text(owner, v, mat, key);
      const int st = material_strength_from_name(s);
      if (st < 0) {
        char known[256] = "";
        for (int k = 0; k < STRENGTH_COUNT; k++) {
          strncat(known, k ? "|" : "", sizeof known - strlen(known) - 1);
          strncat(known, material_strength_name((enum material_strength_type)k),
                  sizeof known - strlen(known) - 1);
        }
        param_node_error(owner, v, "material '%s': key 'strength' must be one of %s (got '%s')",
                         mat->name, known, s);
      }
      mat->strength = (enum material_strength_type)st;
    } else if (strcmp(key, "boundary") == 0) {
      /* fixed boundary particles (theory/boundaries.md) */
      const char *s = material_text(owner, v, mat, key);
      if (strcmp(s, "true") == 0 || strcmp(s, "yes") == 0)
        mat->boundary = 1;
      else if (strcmp(s, "false") == 0 || strcmp(s, "no") == 0)
        mat->boundary = 0;
      else
        param_node_error(owner, v, "material '%s': key 'boundary' must be true or false (got '%s')",
                         mat->name, s);
    } else if (strcmp(key, "porosity") == 0) {
      porosity_from_node(&mat->porosity, mat->name, owner, v); /* theory/porosity.md */
    } else if (mat->eos_type == EOS_TABLE && strcmp(key, "file") == 0) {
      material_resolve(params_filename(owner), material_text(owner, v, mat, key), x->table_file,
                       sizeof x->table_file);
    } else if (mat->eos_type == EOS_TABLE && strcmp(key, "format") == 0) {
      const char *s = material_text(owner, v, mat, key);
      if (strcmp(s, "rho_u") == 0)
        x->table_format = 0;
      else if (strcmp(s, "rho_T") == 0)
        x->table_format = 1;
      else if (strcmp(s, "swift") == 0)
        x->table_format = 2;
      else if (strcmp(s, "miluphcuda") == 0)
        x->table_format = 3;
      else
        param_node_error(owner, v,
                         "material '%s': key 'format' must be rho_u, rho_T, swift or miluphcuda "
                         "(got '%s')",
                         mat->name, s);
    } else if (mat->eos_type == EOS_TABLE &&
               (strcmp(key, "n_rho") == 0 || strcmp(key, "n_e") == 0)) {
      snprintf(what, sizeof what, "material '%s': key '%s'", mat->name, key);
      const long n = param_node_int(owner, v, what);
      if (n < 2 || n > 100000)
        param_node_error(owner, v, "material '%s': key '%s' must be 2 to 100000 (got %ld)",
                         mat->name, key, n);
      *(strcmp(key, "n_rho") == 0 ? &x->table_n_rho : &x->table_n_e) = (int)n;
    } else {
      snprintf(what, sizeof what, "material '%s': key '%s'", mat->name, key);
      const double value = param_node_real(owner, v, what);
      if (material_set(mat, key, value, msg, sizeof msg)) param_node_error(owner, v, "%s", msg);
    }
  }
}

/** Load the table of a tabulated EOS, finalize and check. */
static void material_complete(struct material *mat, struct material_extra *x,
                              const struct params *owner, const struct param_node *at) {
  char msg[512];
  if (mat->eos_type == EOS_TABLE) {
    if (!x->table_file[0])
      param_node_error(owner, at, "material '%s': key 'file' is required for EOS table", mat->name);
    if ((x->table_n_rho || x->table_n_e) && x->table_format != 3)
      param_node_error(owner, at, "material '%s': keys n_rho, n_e belong to format: miluphcuda",
                       mat->name);
    if (x->table_format == 3)
      material_eos_table_load_miluphcuda(&mat->eos.table, x->table_file, x->table_n_rho,
                                         x->table_n_e);
    else
      material_eos_table_load(&mat->eos.table, x->table_file, x->table_format);
  }
  if (material_finalize(mat, msg, sizeof msg)) param_node_error(owner, at, "%s", msg);
}

/** Build material `id` from its entry m of the run's Materials section. */
static void material_from_node(struct material *mat, struct material_libraries *libs,
                               const struct params *p, const struct param_node *m, long id) {
  char libpath[PATH_MAX], label[64];
  struct material_extra x;
  memset(&x, 0, sizeof x);
  snprintf(label, sizeof label, "%ld", id);
  const struct param_node *ln = param_node_get(m, "library");
  if (ln) {
    const char *lt = param_node_text(ln);
    if (!lt) param_node_error(p, ln, "material %ld: key 'library' must be a file name", id);
    material_resolve(params_filename(p), lt, libpath, sizeof libpath);
  } else
    snprintf(libpath, sizeof libpath, "%s", material_default_library());
  const struct param_node *nn = param_node_get(m, "name");
  const char *name = nn ? param_node_text(nn) : NULL;
  if (nn && !name) param_node_error(p, nn, "material %ld: key 'name' must be a single value", id);
  int type = material_node_eos(p, m, name ? name : label);
  const struct param_node *base = NULL;
  struct params *lib = NULL;
  if (type < 0) {
    lib = material_library(libs, libpath);
    const struct param_node *root = material_library_root(lib);
    if (name) {
      base = param_node_get(root, name);
      if (!base)
        param_node_error(p, nn, "material %ld: '%s' is not in the material library %s", id, name,
                         libpath);
    } else {
      /* a SWIFT planetary id: the library entry with that swift_id */
      for (int i = 0; i < param_node_count(root) && !base; i++) {
        const struct param_node *e = param_node_child(root, i);
        const struct param_node *s = param_node_get(e, "swift_id");
        const char *t = s ? param_node_text(s) : NULL;
        if (t && strtol(t, NULL, 10) == id) {
          base = e;
          name = param_node_key(root, i);
        }
      }
      if (!base)
        param_node_error(p, m,
                         "material %ld: give 'name:' (an entry of the library %s) or 'eos:' (an "
                         "inline definition); no library entry has swift_id %ld",
                         id, libpath, id);
    }
    if (param_node_kind(base) != 1)
      param_node_error(lib, base, "material '%s': a library entry must be a mapping", name);
    type = material_node_eos(lib, base, name);
    if (type < 0) param_node_error(lib, base, "material '%s': key 'eos' is required", name);
  }
  material_init(mat, (int32_t)id, name ? name : label, (enum material_eos_type)type);
  if (base) material_apply(mat, &x, lib, base, "|eos|name|");
  material_apply(mat, &x, p, m, "|eos|name|library|");
  material_complete(mat, &x, p, m);
}

/* ---- SWIFT's EoS section ---------------------------------------------- */

/** How SWIFT defines a planetary material of its EoS section. */
enum material_swift_kind {
  MATERIAL_SWIFT_LIBRARY, /**< fixed parameters: the library entry with its swift_id */
  MATERIAL_SWIFT_TABLE,   /**< a SESAME-like table file (planetary_NAME_table_file) */
  MATERIAL_SWIFT_HM80,    /**< a Hubbard & MacFarlane table file (not read yet) */
  MATERIAL_SWIFT_TIL_FILE /**< a Tillotson parameter file (planetary_NAME_param_file; not read yet)
                           */
};

/** SWIFT's planetary materials: NAME of its EoS:planetary_use_NAME key, the
 *  material id (SWIFT: type * 100 + unit; its equation_of_state.h) and the
 *  kind; the custom ids 190-199 and 900-909 follow in material_swift_find. */
static const struct {
  const char *name;
  int id;
  enum material_swift_kind kind;
} material_swift[] = {
    {"idg_def", 0, MATERIAL_SWIFT_LIBRARY},       {"Til_iron", 100, MATERIAL_SWIFT_LIBRARY},
    {"Til_granite", 101, MATERIAL_SWIFT_LIBRARY}, {"Til_water", 102, MATERIAL_SWIFT_LIBRARY},
    {"Til_basalt", 103, MATERIAL_SWIFT_LIBRARY},  {"Til_ice", 104, MATERIAL_SWIFT_LIBRARY},
    {"HM80_HHe", 200, MATERIAL_SWIFT_HM80},       {"HM80_ice", 201, MATERIAL_SWIFT_HM80},
    {"HM80_rock", 202, MATERIAL_SWIFT_HM80},      {"SESAME_iron", 300, MATERIAL_SWIFT_TABLE},
    {"SESAME_basalt", 301, MATERIAL_SWIFT_TABLE}, {"SESAME_water", 302, MATERIAL_SWIFT_TABLE},
    {"SS08_water", 303, MATERIAL_SWIFT_TABLE},    {"AQUA", 304, MATERIAL_SWIFT_TABLE},
    {"CMS19_H", 305, MATERIAL_SWIFT_TABLE},       {"CMS19_He", 306, MATERIAL_SWIFT_TABLE},
    {"CD21_HHe", 307, MATERIAL_SWIFT_TABLE},      {"ANEOS_forsterite", 400, MATERIAL_SWIFT_TABLE},
    {"ANEOS_iron", 401, MATERIAL_SWIFT_TABLE},    {"ANEOS_Fe85Si15", 402, MATERIAL_SWIFT_TABLE},
};
#define MATERIAL_NR_SWIFT ((int)(sizeof material_swift / sizeof material_swift[0]))

/** SWIFT's keys of its EoS section for equations of state chosen when SWIFT
 *  is compiled, which Bolide sets per material instead. */
static const char *const material_swift_compiled[] = {
    "isothermal_internal_energy", "barotropic_vacuum_sound_speed", "barotropic_core_density"};

/** Id and kind of SWIFT's material NAME (custom_0..9: 900-909 tables;
 *  Til_custom_0..9: 190-199 Tillotson files); -1 when SWIFT has none. */
static int material_swift_find(const char *name, enum material_swift_kind *kind) {
  for (int k = 0; k < MATERIAL_NR_SWIFT; k++)
    if (strcmp(material_swift[k].name, name) == 0) {
      *kind = material_swift[k].kind;
      return material_swift[k].id;
    }
  if (strncmp(name, "custom_", 7) == 0 && name[7] >= '0' && name[7] <= '9' && !name[8]) {
    *kind = MATERIAL_SWIFT_TABLE;
    return 900 + name[7] - '0';
  }
  if (strncmp(name, "Til_custom_", 11) == 0 && name[11] >= '0' && name[11] <= '9' && !name[12]) {
    *kind = MATERIAL_SWIFT_TIL_FILE;
    return 190 + name[11] - '0';
  }
  return -1;
}

/** The EoS key nearest to a misspelt one (within three slips), "" if none. */
static void material_swift_suggest(const char *key, char *out, size_t len) {
  int best = 4;
  out[0] = '\0';
  char cand[128];
  for (int k = 0; k < MATERIAL_NR_SWIFT + 20 + 3; k++) {
    for (int form = 0; form < 2; form++) {
      const char *name;
      char custom[32];
      if (k < MATERIAL_NR_SWIFT) {
        if (form && material_swift[k].kind == MATERIAL_SWIFT_LIBRARY) continue;
        name = material_swift[k].name;
      } else if (k < MATERIAL_NR_SWIFT + 20) {
        const int c = k - MATERIAL_NR_SWIFT;
        snprintf(custom, sizeof custom, c < 10 ? "custom_%d" : "Til_custom_%d", c % 10);
        name = custom;
      } else {
        if (form) continue;
        name = NULL;
      }
      if (name && form == 0)
        snprintf(cand, sizeof cand, "planetary_use_%s", name);
      else if (name)
        snprintf(cand, sizeof cand, "planetary_%s_%s", name,
                 strncmp(name, "Til_custom_", 11) == 0 ? "param_file" : "table_file");
      else
        snprintf(cand, sizeof cand, "%s", material_swift_compiled[k - MATERIAL_NR_SWIFT - 20]);
      const int d = params_edit_distance(key, cand);
      if (d < best) {
        best = d;
        snprintf(out, len, " (did you mean '%s'?)", cand);
      }
    }
  }
}

/** The problems found in an EoS section, reported together. */
struct material_swift_problems {
  int n;           /**< number found */
  char last[1024]; /**< the last one (given to error_exit) */
};

/** Report one problem of the EoS section (the previous one, if any, is
 *  printed now: the last goes through error_exit at the end). */
static void material_swift_problem(struct material_swift_problems *pr, const struct params *p,
                                   const struct param_node *at, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void material_swift_problem(struct material_swift_problems *pr, const struct params *p,
                                   const struct param_node *at, const char *fmt, ...) {
  char msg[900];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (pr->n > 0) error_report("%s", pr->last);
  snprintf(pr->last, sizeof pr->last, "%s:%d: %s", params_filename(p), param_node_line(at), msg);
  pr->n++;
}

/** Reference density of a table read from SWIFT's format, which has none:
 *  where the pressure of the coldest row crosses 0 (the density of the
 *  uncompressed solid), else the geometric middle of the density axis. */
static double material_swift_rho0(const struct eos_table *tab) {
  const int nu = tab->n_u;
  for (int i = 0; i + 1 < tab->n_rho; i++) {
    const double p0 = tab->P[(size_t)i * nu], p1 = tab->P[(size_t)(i + 1) * nu];
    if (p0 <= 0.0 && p1 > 0.0) {
      const double w = -p0 / (p1 - p0);
      return exp(tab->ln_rho_min + (i + w) * tab->dln_rho);
    }
  }
  return exp(tab->ln_rho_min + 0.5 * (tab->n_rho - 1) * tab->dln_rho);
}

/** Material `id` of SWIFT's EoS section: the library entry with that
 *  swift_id, or a SWIFT table file. */
static void material_from_swift(struct material *mat, struct material_libraries *libs,
                                const struct params *p, const char *name, int id,
                                enum material_swift_kind kind, const char *table) {
  char msg[512];
  if (kind == MATERIAL_SWIFT_TABLE) {
    material_init(mat, id, name, EOS_TABLE);
    snprintf(mat->reference, sizeof mat->reference, "SWIFT planetary id %d, table %s", id, table);
    mat->swift_id = id;
    material_eos_table_load_swift(&mat->eos.table, table);
    mat->eos.table.rho0 = material_swift_rho0(&mat->eos.table);
    if (material_finalize(mat, msg, sizeof msg)) error_exit("%s: %s", table, msg);
    return;
  }
  const char *libpath = material_default_library();
  struct params *lib = material_library(libs, libpath);
  const struct param_node *root = material_library_root(lib);
  for (int i = 0; i < param_node_count(root); i++) {
    const struct param_node *e = param_node_child(root, i);
    const char *t = param_node_text(param_node_get(e, "swift_id"));
    if (!t || strtol(t, NULL, 10) != id) continue;
    const char *lname = param_node_key(root, i);
    const int type = material_node_eos(lib, e, lname);
    if (type < 0) param_node_error(lib, e, "material '%s': key 'eos' is required", lname);
    struct material_extra x;
    memset(&x, 0, sizeof x);
    material_init(mat, id, lname, (enum material_eos_type)type);
    material_apply(mat, &x, lib, e, "|eos|name|");
    material_complete(mat, &x, lib, e);
    return;
  }
  error_exit("%s: no material of the library %s has swift_id %d (SWIFT's %s)", params_filename(p),
             libpath, id, name);
}

/** Add the materials SWIFT's EoS section enables (EoS:planetary_use_NAME)
 *  that the Materials section does not define; every problem of the
 *  section is reported in one pass. */
static void material_table_from_swift(struct material_table *t, struct material_libraries *libs,
                                      const struct params *p, const struct param_node *eos) {
  struct material_swift_problems pr = {0, ""};
  char hint[160], added[512] = "";
  if (param_node_kind(eos) != 1) {
    if (param_node_text(eos) && !param_node_text(eos)[0]) return; /* "EoS:" alone */
    param_node_error(p, eos, "EoS must be a mapping of SWIFT's planetary keys");
  }
  for (int i = 0; i < param_node_count(eos); i++) {
    const char *key = param_node_key(eos, i);
    const struct param_node *v = param_node_child(eos, i);
    enum material_swift_kind kind = MATERIAL_SWIFT_LIBRARY;
    int compiled = 0;
    for (size_t k = 0; k < sizeof material_swift_compiled / sizeof *material_swift_compiled; k++)
      compiled |= strcmp(key, material_swift_compiled[k]) == 0;
    if (compiled) {
      error_warning(
          "%s:%d: EoS:%s (SWIFT's, for an equation of state chosen when SWIFT is "
          "compiled) has no effect in Bolide: give the material its EOS in the "
          "Materials section (eos: isothermal, polytropic, ...; examples/parameters.yml)",
          params_filename(p), param_node_line(v), key);
      continue;
    }
    if (strncmp(key, "planetary_use_", 14) == 0 && material_swift_find(key + 14, &kind) >= 0) {
      const char *s = param_node_text(v);
      if (!s ||
          (strcmp(s, "0") && strcmp(s, "1") && strcasecmp(s, "true") && strcasecmp(s, "false")))
        material_swift_problem(&pr, p, v, "EoS:%s: expected 0 or 1 (true or false), got %s", key,
                               s ? s : "a collection");
      continue;
    }
    const size_t l = strlen(key);
    if (strncmp(key, "planetary_", 10) == 0 && l > 21 &&
        (strcmp(key + l - 11, "_table_file") == 0 || strcmp(key + l - 11, "_param_file") == 0)) {
      char name[96];
      snprintf(name, sizeof name, "%.*s", (int)(l - 21), key + 10);
      const int id = material_swift_find(name, &kind);
      const int want_param = kind == MATERIAL_SWIFT_TIL_FILE;
      if (id >= 0 && kind != MATERIAL_SWIFT_LIBRARY &&
          want_param == (strcmp(key + l - 11, "_param_file") == 0)) {
        if (!param_node_text(v))
          material_swift_problem(&pr, p, v, "EoS:%s: expected a file name", key);
        continue;
      }
    }
    material_swift_suggest(key, hint, sizeof hint);
    material_swift_problem(&pr, p, v,
                           "unknown key 'EoS:%s'%s (SWIFT's EoS section names planetary "
                           "materials; Bolide's own is the Materials section)",
                           key, hint);
  }
  if (pr.n) error_exit("%s%s", pr.last, pr.n > 1 ? " (and the problems above)" : "");
  /* the materials enabled */
  for (int i = 0; i < param_node_count(eos); i++) {
    const char *key = param_node_key(eos, i);
    const struct param_node *v = param_node_child(eos, i);
    enum material_swift_kind kind;
    if (strncmp(key, "planetary_use_", 14) != 0) continue;
    const char *s = param_node_text(v);
    if (!(strcmp(s, "1") == 0 || strcasecmp(s, "true") == 0)) continue;
    const char *name = key + 14;
    const int id = material_swift_find(name, &kind);
    if (material_table_find(t, id)) {
      error_note("%s:%d: EoS:%s: material %d is defined in the Materials section, which wins",
                 params_filename(p), param_node_line(v), key, id);
      continue;
    }
    char fkey[128], file[PATH_MAX] = "";
    snprintf(fkey, sizeof fkey, "planetary_%s_%s", name,
             kind == MATERIAL_SWIFT_TIL_FILE ? "param_file" : "table_file");
    const struct param_node *fn = param_node_get(eos, fkey);
    if (fn) material_resolve(params_filename(p), param_node_text(fn), file, sizeof file);
    if (kind == MATERIAL_SWIFT_HM80 || kind == MATERIAL_SWIFT_TIL_FILE)
      material_swift_problem(&pr, p, v,
                             "EoS:%s: Bolide does not read SWIFT's %s files yet: define material "
                             "%d in the Materials section (%s)",
                             key,
                             kind == MATERIAL_SWIFT_HM80 ? "HM80 table" : "Tillotson parameter", id,
                             kind == MATERIAL_SWIFT_HM80
                                 ? "eos: table, file: ..., format: rho_T"
                                 : "eos: tillotson with its parameters; examples/materials.yml");
    else if (kind == MATERIAL_SWIFT_TABLE && !fn)
      material_swift_problem(&pr, p, v,
                             "EoS:%s: material %d is a SWIFT table: give its file as "
                             "EoS:%s (or define material %d in the Materials section)",
                             key, id, fkey, id);
    else if (kind == MATERIAL_SWIFT_TABLE && access(file, R_OK) != 0)
      material_swift_problem(
          &pr, p, fn,
          "EoS:%s: cannot read the table %s: %s (SWIFT's planetary tables come "
          "with SWIFT: examples/Planetary/EoSTables/get_eos_tables.sh; README.md, "
          "Coming from SWIFT)",
          fkey, file, strerror(errno));
    if (pr.n) continue;
    struct material mat;
    material_from_swift(&mat, libs, p, name, id, kind, file);
    if (t->n >= MATERIAL_MAX)
      param_node_error(p, v, "too many materials (at most %d)", MATERIAL_MAX);
    material_table_add(t, &mat);
    const size_t n = strlen(added);
    snprintf(added + n, sizeof added - n, "%s%d (%s)", n ? ", " : "", id, mat.name);
  }
  if (pr.n) error_exit("%s%s", pr.last, pr.n > 1 ? " (and the problems above)" : "");
  if (added[0])
    error_note(
        "%s: SWIFT's EoS section read as materials %s; Bolide's own section for materials is "
        "Materials (examples/parameters.yml), where a run can also give strength, damage and "
        "porosity",
        params_filename(p), added);
}

void material_table_from_params(struct material_table *t, const struct params *p) {
  char msg[512];
  material_table_init(t);
  const struct param_node *sec = params_section(p, "Materials");
  const struct param_node *eos = params_section(p, "EoS");
  if (!sec || (param_node_kind(sec) == 1 && param_node_count(sec) == 0) ||
      (param_node_kind(sec) == 0 && (!param_node_text(sec) || !param_node_text(sec)[0]))) {
    if (eos) {
      struct material_libraries libs;
      memset(&libs, 0, sizeof libs);
      material_table_from_swift(t, &libs, p, eos);
      for (int i = 0; i < libs.n; i++) params_free(libs.lib[i]);
      if (t->n > 0) return;
    }
    struct material m;
    material_init(&m, 0, "ideal_gas", EOS_IDEAL_GAS);
    snprintf(m.reference, sizeof m.reference, "default material: ideal gas with SPH:gamma");
    m.eos.ideal_gas.gamma = params_get_real(p, "SPH:gamma");
    if (material_finalize(&m, msg, sizeof msg)) params_error(p, "SPH:gamma", "%s", msg);
    material_table_add(t, &m);
    return;
  }
  if (param_node_kind(sec) != 1)
    param_node_error(p, sec, "Materials must be a mapping from material id to a material");
  struct material_libraries libs;
  memset(&libs, 0, sizeof libs);
  for (int i = 0; i < param_node_count(sec); i++) {
    const char *key = param_node_key(sec, i);
    const struct param_node *m = param_node_child(sec, i);
    char *end;
    const long id = strtol(key, &end, 10);
    if (end == key || *end || id < 0 || id > INT32_MAX)
      param_node_error(p, m, "Materials: '%s' is not a material id (an integer >= 0)", key);
    if (param_node_kind(m) != 1)
      param_node_error(
          p, m, "material %ld must be a mapping (name: ..., or eos: ... and parameters)", id);
    struct material mat;
    material_from_node(&mat, &libs, p, m, id);
    if (material_table_find(t, mat.id))
      param_node_error(p, m, "material id %ld is defined twice", id);
    if (t->n >= MATERIAL_MAX)
      param_node_error(p, m, "too many materials (at most %d)", MATERIAL_MAX);
    material_table_add(t, &mat);
  }
  if (eos) material_table_from_swift(t, &libs, p, eos);
  for (int i = 0; i < libs.n; i++) params_free(libs.lib[i]);
}

void material_from_library(struct material *mat, const char *library, const char *name,
                           int32_t id) {
  struct params *lib = params_read_tree(library);
  const struct param_node *root = material_library_root(lib);
  const struct param_node *e = param_node_get(root, name);
  if (!e) {
    char known[1024] = "";
    for (int i = 0; i < param_node_count(root); i++) {
      strncat(known, i ? ", " : "", sizeof known - strlen(known) - 1);
      strncat(known, param_node_key(root, i), sizeof known - strlen(known) - 1);
    }
    error_exit("%s: no material '%s' (the library has: %s)", library, name, known);
  }
  if (param_node_kind(e) != 1)
    param_node_error(lib, e, "material '%s': a library entry must be a mapping", name);
  const int type = material_node_eos(lib, e, name);
  if (type < 0) param_node_error(lib, e, "material '%s': key 'eos' is required", name);
  struct material_extra x;
  memset(&x, 0, sizeof x);
  material_init(mat, id, name, (enum material_eos_type)type);
  material_apply(mat, &x, lib, e, "|eos|name|");
  material_complete(mat, &x, lib, e);
  params_free(lib);
}
