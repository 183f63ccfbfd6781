/* Bad input to the space stops with one clear line and exit status 1, never
 * a crash: a non-finite position or smoothing length (naming the particle),
 * a kernel support above half a periodic box, bad space_init arguments.
 * Each case runs in a child process; the parent checks the exit status and
 * that stderr is one line containing the expected words.
 * Exit 0 pass, 1 fail. */
#ifdef HAVE_CONFIG_H
#include "config.h"
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "src/error.h"
#include "src/part.h"
#include "src/space.h"

enum bad_case { BAD_NAN_X, BAD_ZERO_H, BAD_BIG_H, BAD_SPLIT, BAD_BOX, NR_BAD };

static const char *bad_name[NR_BAD] = {"NaN position", "zero smoothing length",
                                       "support above half the periodic box", "split size 0",
                                       "negative box"};
static const char *bad_expect[NR_BAD] = {"particle id 5", "particle id 7", "particle id 9",
                                         "split size", "box size"};

/** The child: build a small space with one defect. */
static void child(enum bad_case c) {
  const double L[3] = {1.0, 1.0, 1.0}, Lbad[3] = {1.0, -1.0, 1.0};
  struct parts p;
  parts_alloc(&p, 20);
  for (size_t i = 0; i < p.count; i++) {
    p.x[i] = 0.05 * i;
    p.y[i] = 0.5;
    p.z[i] = 0.5;
    p.h[i] = 0.05;
    p.id[i] = (int64_t)i;
  }
  if (c == BAD_NAN_X) p.x[5] = NAN;
  if (c == BAD_ZERO_H) p.h[7] = 0.0;
  if (c == BAD_BIG_H) p.h[9] = 0.3;
  struct space s;
  space_init(&s, &p, c == BAD_BOX ? Lbad : L, 1, c == BAD_SPLIT ? 0 : 8, 16);
  space_rebuild(&s);
  exit(0); /* not reached when the defect is caught */
}

int main(int argc, char **argv) {
  int failures = 0;
  for (int c = 0; c < NR_BAD; c++) {
    int fd[2];
    if (pipe(fd) != 0) return 1;
    fflush(stdout);
    const pid_t pid = fork();
    if (pid == 0) {
      close(fd[0]);
      dup2(fd[1], 2);
      error_init("test_space_errors");
      child((enum bad_case)c);
    }
    close(fd[1]);
    char out[4096];
    size_t n = 0;
    ssize_t r;
    while ((r = read(fd[0], out + n, sizeof out - 1 - n)) > 0) n += (size_t)r;
    out[n] = '\0';
    close(fd[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    int lines = 0;
    for (size_t k = 0; k < n; k++) lines += out[k] == '\n';
    const int ok = WIFEXITED(status) && WEXITSTATUS(status) == 1 && lines == 1 &&
                   strstr(out, "test_space_errors: error: ") == out &&
                   strstr(out, bad_expect[c]) != NULL;
    printf("%-38s exit %d, %d line(s): %s%s", bad_name[c],
           WIFEXITED(status) ? WEXITSTATUS(status) : -1, lines,
           ok ? "ok: " : "FAIL: ", n ? out : "(nothing)\n");
    if (!ok) failures++;
  }
  (void)argc;
  (void)argv;
  printf("%s\n", failures ? "FAIL" : "PASS");
  return failures ? 1 : 0;
}
