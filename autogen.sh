#!/bin/sh
# Generate configure and Makefile.in from configure.ac and Makefile.am.
set -e
cd "$(dirname "$0")"
mkdir -p m4 build-aux
# the build fragment of the task families, from their registry (Makefile.am)
sh tools/families_am.sh . >tasks/families.am
autoreconf --install --force
