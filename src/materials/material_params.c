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
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "material.h"
#include "params.h"

/** Libraries read while building one table (read each file once). */
#define MATERIAL_MAX_LIBRARIES 8
struct material_libraries {
  int n;                                       /**< libraries read */
  char path[MATERIAL_MAX_LIBRARIES][PATH_MAX]; /**< their paths */
  struct params *lib[MATERIAL_MAX_LIBRARIES];  /**< their trees */
};

/** Extra state of one material while its keys are applied. */
struct material_extra {
  char table_file[PATH_MAX]; /**< file: of a tabulated EOS */
  int table_format;          /**< format: 0 rho_u, 1 rho_T */
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
      else
        param_node_error(owner, v, "material '%s': key 'format' must be rho_u or rho_T (got '%s')",
                         mat->name, s);
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

void material_table_from_params(struct material_table *t, const struct params *p) {
  char msg[512];
  material_table_init(t);
  const struct param_node *sec = params_section(p, "Materials");
  if (!sec || (param_node_kind(sec) == 1 && param_node_count(sec) == 0) ||
      (param_node_kind(sec) == 0 && (!param_node_text(sec) || !param_node_text(sec)[0]))) {
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
