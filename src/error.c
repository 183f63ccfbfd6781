/* Errors, warnings and log messages: see error.h. */
#include "src/error.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

const char *error_progname = "bolide";
int error_verbosity = 0;
int error_log_quiet = 0;
int error_rank = 0, error_warn_quiet = 0;
void (*error_exit_hook)(void) = NULL;

static struct timespec error_t0;
#define ERROR_MAX_TMPFILES 16
static char *error_tmpfiles[ERROR_MAX_TMPFILES];
static pthread_mutex_t error_lock = PTHREAD_MUTEX_INITIALIZER;

void error_init(const char *argv0) {
  const char *slash = argv0 ? strrchr(argv0, '/') : NULL;
  error_progname = argv0 ? (slash ? slash + 1 : argv0) : "bolide";
  /* libtool-style wrappers prefix "lt-" */
  if (strncmp(error_progname, "lt-", 3) == 0) error_progname += 3;
  clock_gettime(CLOCK_MONOTONIC, &error_t0);
}

double error_walltime(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)(t.tv_sec - error_t0.tv_sec) + 1e-9 * (double)(t.tv_nsec - error_t0.tv_nsec);
}

static void error_cleanup(void) {
  pthread_mutex_lock(&error_lock);
  for (int i = 0; i < ERROR_MAX_TMPFILES; i++)
    if (error_tmpfiles[i]) {
      unlink(error_tmpfiles[i]);
      free(error_tmpfiles[i]);
      error_tmpfiles[i] = NULL;
    }
  pthread_mutex_unlock(&error_lock);
}

/** Print msg as the one line of error_exit and error_exit_status, then exit. */
static void error_exit_msg(int status, char *msg) __attribute__((noreturn));
static void error_exit_msg(int status, char *msg) {
  /* one line: fold newlines */
  for (char *c = msg; *c; c++)
    if (*c == '\n') *c = ' ';
  fflush(stdout);
  fprintf(stderr, "%s: error: %s\n", error_progname, msg);
  fflush(stderr);
  error_cleanup();
  if (error_exit_hook) error_exit_hook();
  exit(status);
}

void error_exit(const char *fmt, ...) {
  char msg[4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  error_exit_msg(1, msg);
}

void error_exit_status(int status, const char *fmt, ...) {
  char msg[4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  error_exit_msg(status, msg);
}

void error_bug_at(const char *file, int line, const char *fmt, ...) {
  char msg[4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  error_exit("internal error at %s:%d: %s (please report this bug)", file, line, msg);
}

/** One line "PROGRAM: KIND: MESSAGE" on stderr (after what stdout holds). */
static void error_line(const char *kind, const char *fmt, va_list ap) {
  char msg[4096];
  vsnprintf(msg, sizeof msg, fmt, ap);
  fflush(stdout);
  fprintf(stderr, "%s: %s: %s\n", error_progname, kind, msg);
  fflush(stderr);
}

void error_warning(const char *fmt, ...) {
  if (error_warn_quiet) return;
  va_list ap;
  va_start(ap, fmt);
  char kind[32];
  snprintf(kind, sizeof kind, error_rank ? "warning (rank %d)" : "warning", error_rank);
  error_line(kind, fmt, ap);
  va_end(ap);
}

void error_note(const char *fmt, ...) {
  if (error_warn_quiet) return;
  va_list ap;
  va_start(ap, fmt);
  char kind[32];
  snprintf(kind, sizeof kind, error_rank ? "note (rank %d)" : "note", error_rank);
  error_line(kind, fmt, ap);
  va_end(ap);
}

void error_report(const char *fmt, ...) {
  char msg[4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  for (char *c = msg; *c; c++)
    if (*c == '\n') *c = ' ';
  fflush(stdout);
  fprintf(stderr, "%s: error: %s\n", error_progname, msg);
  fflush(stderr);
}

void error_log(int level, const char *fmt, ...) {
  if (level > error_verbosity || error_log_quiet) return;
  char msg[4096];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  printf("[%9.3f s] %s\n", error_walltime(), msg);
  fflush(stdout);
}

void error_register_tmpfile(const char *path) {
  pthread_mutex_lock(&error_lock);
  for (int i = 0; i < ERROR_MAX_TMPFILES; i++)
    if (!error_tmpfiles[i]) {
      error_tmpfiles[i] = strdup(path);
      break;
    }
  pthread_mutex_unlock(&error_lock);
}

void error_unregister_tmpfile(const char *path) {
  pthread_mutex_lock(&error_lock);
  for (int i = 0; i < ERROR_MAX_TMPFILES; i++)
    if (error_tmpfiles[i] && strcmp(error_tmpfiles[i], path) == 0) {
      free(error_tmpfiles[i]);
      error_tmpfiles[i] = NULL;
    }
  pthread_mutex_unlock(&error_lock);
}

void *error_malloc(size_t size, const char *what) {
  void *p = malloc(size ? size : 1);
  if (!p) error_exit("out of memory allocating %zu bytes for %s", size, what);
  return p;
}

void *error_calloc(size_t n, size_t size, const char *what) {
  void *p = calloc(n ? n : 1, size ? size : 1);
  if (!p) error_exit("out of memory allocating %zu x %zu bytes for %s", n, size, what);
  return p;
}

void *error_realloc(void *p, size_t size, const char *what) {
  void *q = realloc(p, size ? size : 1);
  if (!q) error_exit("out of memory reallocating %zu bytes for %s", size, what);
  return q;
}
