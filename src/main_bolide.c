/* bolide: run a simulation (placeholder until the engine lands). */
#include <stdio.h>
#include "error.h"
#include "version.h"
int main(int argc, char **argv) {
  error_init(argv[0]);
  printf("Bolide %s\n", PACKAGE_VERSION);
  return 0;
}
