/* params_check: read a parameter file as bolide does and print values.
 *
 *   params_check FILE [-P Section:key:value]... [--yaml] [--tree] [KEY]...
 *
 * Prints "KEY=VALUE" for each KEY (arrays as "a,b,c"), then with --yaml the
 * parameters in use as YAML.  --tree reads FILE with params_read_tree
 * instead (no validation).  Errors are bolide's: one line, exit 1.  Used by
 * tests/program/test_params_errors.sh. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "src/error.h"
#include "src/io/params.h"

/** Print KEY=VALUE for one key, formatted by its type. */
static void print_key(const struct params *p, const char *name) {
  const struct param_spec *s = params_spec(name);
  if (!s) error_exit("%s: no such key", name);
  printf("%s=", name);
  double a[64];
  int n;
  switch (s->type) {
    case PARAM_INT:
      printf("%ld", params_get_int(p, name));
      break;
    case PARAM_REAL:
      printf("%.17g", params_get_real(p, name));
      break;
    case PARAM_BOOL:
      printf("%d", params_get_bool(p, name));
      break;
    case PARAM_STRING:
    case PARAM_WORDS:
      printf("%s", params_get_string(p, name));
      break;
    case PARAM_ENUM:
      printf("%d", params_get_enum(p, name));
      break;
    case PARAM_REAL_ARRAY:
      n = params_get_real_array(p, name, a, 64);
      for (int k = 0; k < n; k++) printf("%s%.17g", k ? "," : "", a[k]);
      break;
    case PARAM_SECTION:
      printf("%d", param_node_count(params_section(p, name)));
      break;
  }
  printf("\n");
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  if (argc < 2) error_exit("usage: params_check FILE [-P S:k:v]... [--yaml] [--tree] [KEY]...");
  char **overrides = calloc((size_t)argc, sizeof *overrides);
  int n_over = 0, yaml = 0, tree = 0;
  for (int i = 2; i < argc; i++) {
    if (strcmp(argv[i], "-P") == 0 && i + 1 < argc) overrides[n_over++] = argv[++i];
    if (strcmp(argv[i], "--yaml") == 0) yaml = 1;
    if (strcmp(argv[i], "--tree") == 0) tree = 1;
  }
  struct params *p = tree ? params_read_tree(argv[1]) : params_read(argv[1], n_over, overrides);
  for (int i = 2; i < argc; i++) {
    if (strcmp(argv[i], "-P") == 0)
      i++;
    else if (argv[i][0] != '-')
      print_key(p, argv[i]);
  }
  if (yaml) params_write_yaml(p, stdout);
  params_free(p);
  free(overrides);
  return 0;
}
