/* Where the running program finds the files Bolide ships (paths.h). */
#include "src/paths.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

const char *paths_exe_dir(void) {
  static char dir[PATH_MAX];
  static int done;
  if (done) return dir;
  done = 1;
  const ssize_t n = readlink("/proc/self/exe", dir, sizeof dir - 1);
  if (n <= 0) {
    dir[0] = '\0';
    return dir;
  }
  dir[n] = '\0';
  char *slash = strrchr(dir, '/');
  if (slash == dir)
    dir[1] = '\0';
  else if (slash)
    *slash = '\0';
  else
    dir[0] = '\0';
  return dir;
}

/** The source folder named by DIR/.bolide-srcdir into out; 0 if none. */
static int paths_srcdir_file(char *out, size_t size, const char *dir) {
  char file[PATH_MAX + 32];
  snprintf(file, sizeof file, "%s/.bolide-srcdir", dir);
  FILE *f = fopen(file, "r");
  if (!f) return 0;
  const int ok = fgets(out, (int)size, f) != NULL;
  fclose(f);
  if (!ok) return 0;
  out[strcspn(out, "\r\n")] = '\0';
  return out[0] != '\0';
}

/** Try candidate `path`: copy it to out (the first one tried too) and say
 *  whether it is readable. */
static int paths_try(char *out, size_t size, const char *path, int *first) {
  if (*first || access(path, R_OK) == 0) {
    snprintf(out, size, "%s", path);
    *first = 0;
  }
  return access(path, R_OK) == 0;
}

int paths_find(char *out, size_t size, const char *env, const char *installed, const char *source) {
  const char *v = env ? getenv(env) : NULL;
  if (v && *v) {
    snprintf(out, size, "%s", v);
    return access(out, R_OK) == 0;
  }
  const char *exe = paths_exe_dir();
  char path[2 * PATH_MAX];
  int first = 1;
  if (installed && exe[0]) {
    snprintf(path, sizeof path, "%s/%s", exe, installed);
    if (paths_try(out, size, path, &first)) return 1;
  }
  if (source) {
    char src[PATH_MAX], up[PATH_MAX + 8], up2[PATH_MAX + 8];
    snprintf(up, sizeof up, "%s/..", exe);
    snprintf(up2, sizeof up2, "%s/../..", exe);
    if (exe[0] &&
        (paths_srcdir_file(src, sizeof src, exe) || paths_srcdir_file(src, sizeof src, up) ||
         paths_srcdir_file(src, sizeof src, up2))) {
      snprintf(path, sizeof path, "%s/%s", src, source);
      if (paths_try(out, size, path, &first)) return 1;
    }
    const char *top = getenv("BOLIDE_SRCDIR");
    if (top && *top) {
      snprintf(path, sizeof path, "%s/%s", top, source);
      if (paths_try(out, size, path, &first)) return 1;
    }
  }
  if (first) snprintf(out, size, "%s", installed ? installed : source ? source : "");
  return 0;
}

const char *paths_python(void) {
  static char py[2 * PATH_MAX];
  const char *v = getenv("PYTHON");
  if (v && *v) return v;
  const char *exe = paths_exe_dir();
  if (exe[0]) {
    snprintf(py, sizeof py, "%s/.venv/bin/python", exe);
    if (access(py, X_OK) == 0) return py;
    snprintf(py, sizeof py, "%s/../.venv/bin/python", exe);
    if (access(py, X_OK) == 0) return py;
    snprintf(py, sizeof py, "%s/../../.venv/bin/python", exe);
    if (access(py, X_OK) == 0) return py;
  }
  return "python3";
}
