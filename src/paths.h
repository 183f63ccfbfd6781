/* Where the running program finds the files Bolide ships (the material
 * library, the plotting scripts, the Python interpreter of the plots), with
 * no path compiled in, so that an install can be moved (issue 23 item 6).
 *
 * A file is looked for, in this order:
 *   1. the environment variable that names it, when set (used as given);
 *   2. the install: a path relative to the program's own folder
 *      (/proc/self/exe), e.g. ../share/bolide/materials.yml;
 *   3. the source tree the program was built from: the build writes the
 *      file .bolide-srcdir (one line, the source folder) beside the programs
 *      it builds; a program in a subfolder of the build (tests/helpers/,
 *      tests/unit/, ...) reads the one a folder or two up;
 *   4. $BOLIDE_SRCDIR, the source tree (make check exports it).
 * Leaf module: includes only the C library. */
#ifndef BOLIDE_PATHS_H
#define BOLIDE_PATHS_H

#include <stddef.h>

/** The folder of the running program, "" when /proc/self/exe cannot be read. */
const char *paths_exe_dir(void);

/** Find a shipped file: `env` the environment variable overriding it (or
 *  NULL), `installed` its path relative to the program's folder in an
 *  install (or NULL), `source` its path relative to the top of the source
 *  tree (or NULL).  Writes the path found to out (size bytes) and returns 1;
 *  returns 0 when no candidate is readable, with out holding the first
 *  candidate tried (for the error message). */
int paths_find(char *out, size_t size, const char *env, const char *installed, const char *source);

/** The Python interpreter that runs the plotting scripts: $PYTHON when set,
 *  else the build's virtual environment when the program runs from its build
 *  folder (.venv/bin/python beside it or a folder or two up), else "python3" (looked
 *  up in PATH; execvp). */
const char *paths_python(void);

#endif
