/* Version, git hash and configuration of this build. */
#ifndef BOLIDE_VERSION_H
#define BOLIDE_VERSION_H
#include "config.h"
#ifndef BOLIDE_GIT_HASH
#define BOLIDE_GIT_HASH "unknown"
#endif
#endif
