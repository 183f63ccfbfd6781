/* The unit tests' check: CHECK(cond, printf-format, ...) counts a check in
 * `checks` and, when cond is false, a failure in `failures` with the file,
 * the line and the message.  A test's main ends with
 *   printf("NAME: %d checks, %d failed\n", checks, failures);
 *   return failures ? 1 : 0; */
#ifndef BOLIDE_TESTS_CHECK_H
#define BOLIDE_TESTS_CHECK_H

#include <stdio.h>

static int checks, failures;
#define CHECK(cond, ...)                          \
  do {                                            \
    checks++;                                     \
    if (!(cond)) {                                \
      failures++;                                 \
      printf("FAIL %s:%d: ", __FILE__, __LINE__); \
      printf(__VA_ARGS__);                        \
      printf("\n");                               \
    }                                             \
  } while (0)

#endif
