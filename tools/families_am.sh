#!/bin/sh
# Write the build fragment of the task families to standard output: one
# "include $(top_srcdir)/tasks/<family>/local.am" per family of the registry
# (tasks/task_families.h), in its order.  autogen.sh writes it to
# tasks/families.am before autoreconf, and Makefile.am's rule again whenever
# the registry changes; Makefile.am includes it, so that a new family's
# folder is built from its registry row alone.
# Usage: tools/families_am.sh [TOP_SRCDIR]
set -e
top=${1:-.}
echo "# Generated from tasks/task_families.h by tools/families_am.sh: do not edit."
sed -n '/^#define TASK_FAMILIES(X)/,/^$/s/^  X(\([a-z0-9_]*\),.*/\1/p' "$top/tasks/task_families.h" |
  while read -r f; do echo "include \$(top_srcdir)/tasks/$f/local.am"; done
