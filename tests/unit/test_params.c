/* Tests of the parameter reader (src/io/params.c): typed values and defaults
 * from tests/data/params_valid.yml, every accepted spelling of numbers and
 * booleans, -P overrides, the YAML written back (re-read to the same values
 * for every key of the table), params_write_used, the node API of free-form
 * sections, and the messages of params_error / param_node_error (in a forked
 * child, since they exit).  The error classes of params_read itself are
 * checked by tests/program/test_params_errors.sh. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "src/error.h"
#include "src/io/param_list.h"
#include "src/io/params.h"

static int failures = 0;

/** Record a failed check with its line. */
#define CHECK(cond)                                                       \
  do {                                                                    \
    if (!(cond)) {                                                        \
      fprintf(stderr, "test_params.c:%d: FAILED: %s\n", __LINE__, #cond); \
      failures++;                                                         \
    }                                                                     \
  } while (0)

#define NAME_OF(name, ...) name,
/** Every key of the table (from the same X-macro as params.c). */
static const char *const all_names[] = {BOLIDE_PARAMS(NAME_OF)};
#define N_NAMES ((int)(sizeof all_names / sizeof all_names[0]))

static char tmpdir[] = "/tmp/test_params_XXXXXX";
static char valid[4096]; /* path of tests/data/params_valid.yml */

/** Path of a file in the temporary folder (static buffer, one at a time per slot). */
static const char *tmp_path(const char *name, int slot) {
  static char buf[4][4096];
  snprintf(buf[slot], sizeof buf[slot], "%s/%s", tmpdir, name);
  return buf[slot];
}

/** Write text to a file in the temporary folder; returns its path. */
static const char *write_file(const char *name, const char *text) {
  const char *path = tmp_path(name, 0);
  FILE *f = fopen(path, "w");
  if (!f) error_exit("%s: cannot write", path);
  fputs(text, f);
  fclose(f);
  return path;
}

/** Minimal valid file with the required keys (plus `extra` appended). */
static const char *minimal_file(const char *extra) {
  char text[4096];
  snprintf(text, sizeof text,
           "InitialConditions:\n  file_name: ics.hdf5\nTimeIntegration:\n  time_end: 2\n%s", extra);
  return write_file("minimal.yml", text);
}

/** 1 if two parameter sets hold the same value for key `name`. */
static int same_value(const struct params *a, const struct params *b, const char *name) {
  const struct param_spec *s = params_spec(name);
  double x[64], y[64];
  int nx, ny;
  switch (s->type) {
    case PARAM_INT:
      return params_get_int(a, name) == params_get_int(b, name);
    case PARAM_REAL:
      return params_get_real(a, name) == params_get_real(b, name);
    case PARAM_BOOL:
      return params_get_bool(a, name) == params_get_bool(b, name);
    case PARAM_STRING:
    case PARAM_WORDS:
      return strcmp(params_get_string(a, name), params_get_string(b, name)) == 0;
    case PARAM_ENUM:
      return params_get_enum(a, name) == params_get_enum(b, name);
    case PARAM_REAL_ARRAY:
      nx = params_get_real_array(a, name, x, 64);
      ny = params_get_real_array(b, name, y, 64);
      return nx == ny && memcmp(x, y, (size_t)nx * sizeof x[0]) == 0;
    case PARAM_SECTION:
      return param_node_count(params_section(a, name)) == param_node_count(params_section(b, name));
  }
  return 0;
}

/** Values of tests/data/params_valid.yml, given and default. */
static void test_valid_file(void) {
  struct params *p = params_read(valid, 0, NULL);
  double a[8];
  CHECK(strcmp(params_filename(p), valid) == 0);
  CHECK(strcmp(params_get_string(p, "MetaData:run_name"), "test run: one") == 0);
  CHECK(params_get_real(p, "InternalUnitSystem:UnitMass_in_cgs") == 5.9722e27);
  CHECK(params_get_real(p, "InternalUnitSystem:UnitVelocity_in_cgs") == 1e5);
  CHECK(params_get_real(p, "TimeIntegration:time_end") == 1e5);
  CHECK(params_get_real(p, "TimeIntegration:dt_max") == 10.);
  CHECK(params_get_real(p, "Gravity:theta_cr") == 0.7);
  CHECK(params_get_int(p, "Snapshots:compression") == 4);
  CHECK(params_get_bool(p, "InitialConditions:periodic") == 1);
  CHECK(params_get_bool(p, "Snapshots:accelerations") == 1);
  CHECK(params_get_bool(p, "SPH:balsara") == 0);
  CHECK(params_get_bool(p, "Gravity:enabled") == 1);
  CHECK(params_get_enum(p, "SPH:density") == 1); /* continuity */
  CHECK(params_get_real_array(p, "InitialConditions:shift", a, 8) == 3);
  CHECK(a[0] == 1.5 && a[1] == -2. && a[2] == 0.5);
  CHECK(params_get_real_array(p, "InitialConditions:box_size", a, 8) == 3);
  CHECK(a[0] == 10. && a[1] == 20. && a[2] == 30.);
  CHECK(params_get_real_array(p, "InitialConditions:box_size", a, 2) == 2); /* maxn honoured */
  /* defaults, from the table's text */
  CHECK(!params_given(p, "SPH:resolution_eta"));
  CHECK(params_get_real(p, "SPH:resolution_eta") == KERNEL_ETA_DEFAULT); /* the kernel's */
  CHECK(params_get_real(p, "SPH:h_tolerance") == 1e-4);
  CHECK(params_get_int(p, "SPH:max_ghost_iterations") == 30);
  CHECK(params_get_bool(p, "Restarts:enable") == 0);
  CHECK(strcmp(params_get_string(p, "Snapshots:subdir"), ".") == 0);
  CHECK(strcmp(params_get_string(p, "Snapshots:output_list"), "") == 0);
  CHECK(params_get_real(p, "InternalUnitSystem:UnitCurrent_in_cgs") == 1.);
  CHECK(params_get_real_array(p, "InitialConditions:box_size", a, 0) == 0);
  struct params *q = params_read(minimal_file(""), 0, NULL);
  CHECK(params_get_real_array(q, "InitialConditions:box_size", a, 8) == 0);
  CHECK(params_get_real_array(q, "InitialConditions:shift", a, 8) == 3 && a[0] == 0. && a[2] == 0.);
  CHECK(params_section(q, "Materials") == NULL);
  params_free(q);
  CHECK(params_given(p, "SPH:CFL_condition") && params_given(p, "Materials"));
  /* relative paths are relative to the file's folder */
  char *path = params_get_path(p, "InitialConditions:file_name"), want[4200];
  snprintf(want, sizeof want, "%s/tests/data/ics/impact.hdf5", getenv("BOLIDE_SRCDIR"));
  CHECK(strcmp(path, want) == 0);
  free(path);
  params_free(p);
}

/** Every accepted spelling of numbers and booleans, through the file. */
static void test_spellings(void) {
  static const struct {
    const char *text;
    double value;
  } reals[] = {{"1e5", 1e5},       {"1.0e+05", 1e5}, {".5", 0.5},    {"5.", 5.},
               {"-0.5e-3", -5e-4}, {"+2", 2.},       {"1E-2", 1e-2}, {"0", 0.}};
  static const struct {
    const char *text;
    int value;
  } bools[] = {{"true", 1}, {"false", 0}, {"yes", 1}, {"no", 0},   {"on", 1},
               {"off", 0},  {"1", 1},     {"0", 0},   {"True", 1}, {"NO", 0}};
  char extra[256];
  for (size_t k = 0; k < sizeof reals / sizeof reals[0]; k++) {
    snprintf(extra, sizeof extra, "Snapshots:\n  time_first: %s\n", reals[k].text);
    struct params *p = params_read(minimal_file(extra), 0, NULL);
    CHECK(params_get_real(p, "Snapshots:time_first") == reals[k].value);
    params_free(p);
  }
  for (size_t k = 0; k < sizeof bools / sizeof bools[0]; k++) {
    snprintf(extra, sizeof extra, "Gravity:\n  enabled: %s\n", bools[k].text);
    struct params *p = params_read(minimal_file(extra), 0, NULL);
    CHECK(params_get_bool(p, "Gravity:enabled") == bools[k].value);
    params_free(p);
  }
  /* an empty section and an empty Materials are allowed */
  struct params *p = params_read(minimal_file("SPH:\nMaterials:\n"), 0, NULL);
  CHECK(params_get_real(p, "SPH:CFL_condition") == 0.2);
  CHECK(!params_given(p, "Materials"));
  params_free(p);
  /* a single number is a one-element array */
  p = params_read(write_file("box.yml",
                             "InitialConditions: {file_name: a, box_size: 4}\n"
                             "TimeIntegration: {time_end: 1}\n"),
                  0, NULL);
  double a[3];
  CHECK(params_get_real_array(p, "InitialConditions:box_size", a, 3) == 1 && a[0] == 4.);
  params_free(p);
}

/** -P overrides: after the file, values with ':', arrays, required keys. */
static void test_overrides(void) {
  char *over[] = {
      "SPH:CFL_condition:0.25", "MetaData:run_name:a:b: c", "InitialConditions:shift:[4, 5, 6]",
      "Gravity:enabled:off",    "SPH:density: summation ",  "SPH:CFL_condition:0.125"};
  struct params *p = params_read(valid, 6, over);
  double a[3];
  CHECK(params_get_real(p, "SPH:CFL_condition") == 0.125); /* the last one wins */
  CHECK(strcmp(params_get_string(p, "MetaData:run_name"), "a:b: c") == 0);
  CHECK(params_get_real_array(p, "InitialConditions:shift", a, 3) == 3 && a[2] == 6.);
  CHECK(params_get_bool(p, "Gravity:enabled") == 0);
  CHECK(params_get_enum(p, "SPH:density") == 0);
  CHECK(params_given(p, "SPH:CFL_condition"));
  params_free(p);
  /* a required key given only by -P */
  char *end[] = {"TimeIntegration:time_end:3"};
  p = params_read(write_file("noend.yml", "InitialConditions:\n  file_name: x.hdf5\n"), 1, end);
  CHECK(params_get_real(p, "TimeIntegration:time_end") == 3.);
  params_free(p);
}

/** The YAML written back reads to the same value for every key. */
static void test_round_trip(void) {
  char *over[] = {"MetaData:run_name:odd: 'text' # with \"quotes\"", "Snapshots:output_list:"};
  struct params *p = params_read(valid, 2, over);
  char *text = params_to_string(p);
  const char *copy = write_file("copy.yml", text);
  struct params *q = params_read(copy, 0, NULL);
  for (int i = 0; i < N_NAMES; i++) {
    if (!same_value(p, q, all_names[i])) fprintf(stderr, "round trip differs: %s\n", all_names[i]);
    CHECK(same_value(p, q, all_names[i]));
  }
  const struct param_node *m = params_section(q, "Materials");
  CHECK(param_node_real(q, param_node_get(param_node_get(m, "granite"), "shear_modulus"), "x") ==
        3.5e10);
  CHECK(strcmp(
            param_node_text(param_node_child(param_node_get(param_node_get(m, "iron"), "list"), 2)),
            "three") == 0);
  params_free(q);
  /* params_write_used: final name, no temporary left, same text */
  const char *used = tmp_path("used.yml", 1);
  params_write_used(p, used);
  CHECK(access(tmp_path("used.yml.tmp", 2), F_OK) != 0);
  FILE *f = fopen(used, "r");
  CHECK(f != NULL);
  if (f) {
    char buf[16384];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    CHECK(strcmp(buf, text) == 0);
  }
  free(text);
  params_free(p);
}

/** The node API on the Materials section and on a free-standing tree. */
static void test_nodes(void) {
  struct params *p = params_read(valid, 0, NULL);
  const struct param_node *m = params_section(p, "Materials");
  CHECK(param_node_kind(m) == 1 && param_node_count(m) == 2);
  CHECK(strcmp(param_node_key(m, 0), "granite") == 0 && strcmp(param_node_key(m, 1), "iron") == 0);
  const struct param_node *g = param_node_child(m, 0);
  CHECK(g == param_node_get(m, "granite"));
  CHECK(param_node_line(param_node_get(g, "id")) == 39);
  CHECK(param_node_int(p, param_node_get(g, "id"), "Materials:granite:id") == 1);
  CHECK(param_node_real(p, param_node_get(g, "rho_0"), "rho_0") == 2680.);
  CHECK(strcmp(param_node_text(param_node_get(g, "eos")), "Tillotson") == 0);
  CHECK(param_node_get(g, "nothing") == NULL && param_node_text(g) == NULL);
  const struct param_node *list = param_node_get(param_node_get(m, "iron"), "list");
  CHECK(param_node_kind(list) == 2 && param_node_count(list) == 3);
  CHECK(param_node_key(list, 0) == NULL && param_node_kind(param_node_child(list, 0)) == 0);
  CHECK(param_node_child(list, 3) == NULL);
  params_free(p);
  struct params *t = params_read_tree(valid);
  const struct param_node *root = params_section(t, "");
  CHECK(param_node_kind(root) == 1 && param_node_count(root) == 8);
  CHECK(param_node_real(t, param_node_get(param_node_get(root, "SPH"), "CFL_condition"), "x") ==
        0.3);
  params_free(t);
}

/** Run fn in a child; check it exits 1 with one stderr line containing
 *  every string of `want` (NULL-terminated). */
static void expect_error(void (*fn)(void), const char *const *want) {
  int fd[2];
  if (pipe(fd) != 0) error_exit("pipe failed");
  fflush(NULL);
  pid_t pid = fork();
  if (pid == 0) {
    dup2(fd[1], 2);
    close(fd[0]);
    fn();
    _exit(0);
  }
  close(fd[1]);
  char buf[4096];
  size_t n = 0;
  ssize_t r;
  while ((r = read(fd[0], buf + n, sizeof buf - 1 - n)) > 0) n += (size_t)r;
  buf[n] = '\0';
  close(fd[0]);
  int status;
  waitpid(pid, &status, 0);
  CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 1);
  CHECK(n > 0 && strchr(buf, '\n') == buf + n - 1);
  for (const char *const *w = want; *w; w++) {
    if (!strstr(buf, *w)) fprintf(stderr, "missing '%s' in: %s", *w, buf);
    CHECK(strstr(buf, *w) != NULL);
  }
}

/** A module's semantic error at a key given in the file. */
static void error_at_key(void) {
  struct params *p = params_read(valid, 0, NULL);
  params_error(p, "Gravity:theta_cr", "must be below %g with this kernel", 0.5);
}

/** The same for a key left at its default. */
static void error_at_default(void) {
  struct params *p = params_read(valid, 0, NULL);
  params_error(p, "SPH:h_max", "too small");
}

/** A material's value that is not a number. */
static void error_at_node(void) {
  struct params *p = params_read(valid, 0, NULL);
  const struct param_node *g = param_node_get(params_section(p, "Materials"), "granite");
  param_node_real(p, param_node_get(g, "eos"), "Materials:granite:eos");
}

static void test_errors(void) {
  const char *const at_key[] = {"params_valid.yml:35: Gravity:theta_cr: must be below 0.5", NULL};
  expect_error(error_at_key, at_key);
  const char *const at_default[] = {"params_valid.yml: SPH:h_max (default value): too small", NULL};
  expect_error(error_at_default, at_default);
  const char *const at_node[] = {
      "params_valid.yml:40: Materials:granite:eos: expected a number, got 'Tillotson'", NULL};
  expect_error(error_at_node, at_node);
}

int main(int argc, char **argv) {
  error_init(argv[0]);
  const char *src = getenv("BOLIDE_SRCDIR");
  if (!src) src = BOLIDE_SRCDIR;
  setenv("BOLIDE_SRCDIR", src, 0);
  snprintf(valid, sizeof valid, "%s/tests/data/params_valid.yml", src);
  if (!mkdtemp(tmpdir)) error_exit("cannot make a temporary folder");
  test_valid_file();
  test_spellings();
  test_overrides();
  test_round_trip();
  test_nodes();
  test_errors();
  const char *files[] = {"minimal.yml", "noend.yml", "copy.yml", "used.yml", "box.yml"};
  for (int k = 0; k < 5; k++) unlink(tmp_path(files[k], 0));
  rmdir(tmpdir);
  if (failures) fprintf(stderr, "test_params: %d failures\n", failures);
  return failures ? 1 : 0;
}
