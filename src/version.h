/* Version, git hash and configuration of this build, and the one --version
 * text of every Bolide program (issue 23 item 6): "PROGRAM (Bolide) VERSION
 * (git HASH)", then the configure line, compiler, kernel, CUDA, MPI and
 * METIS. */
#ifndef BOLIDE_VERSION_H
#define BOLIDE_VERSION_H
#include <stdio.h>

#include "config.h"
#ifndef BOLIDE_GIT_HASH
#define BOLIDE_GIT_HASH "unknown"
#endif

/** Print the --version text of program `prog` to stdout. */
static inline void bolide_version_print(const char *prog) {
  printf("%s (Bolide) %s (git %s)\n", prog, PACKAGE_VERSION, BOLIDE_GIT_HASH);
  printf("configured with: %s\n", BOLIDE_CONFIGURE_ARGS[0] ? BOLIDE_CONFIGURE_ARGS : "(defaults)");
  printf("compiler: %s\n", BOLIDE_CC_VERSION);
  printf("kernel: %s\n", BOLIDE_KERNEL_NAME);
#ifdef HAVE_CUDA
  printf("CUDA: yes\n");
#else
  printf("CUDA: no\n");
#endif
#ifdef HAVE_MPI
  printf("MPI: yes\n");
#else
  printf("MPI: no\n");
#endif
#ifdef HAVE_METIS
  printf("METIS: yes\n");
#else
  printf("METIS: no\n");
#endif
}
#endif
