"""Helpers shared by the command-line scripts in tools/: one-line errors in
Bolide's format ("PROGRAM: error: ...", exit 1) and figures written to a
temporary name and renamed, so an interrupted run never leaves a truncated PNG
under the final name."""

import os
import sys


def die(message):
    """Print "PROGRAM: error: MESSAGE" to stderr and exit with status 1."""
    prog = os.path.basename(sys.argv[0]) if sys.argv and sys.argv[0] else "bolide-tool"
    sys.stderr.write("%s: error: %s\n" % (prog, message))
    sys.exit(1)


def warn(message):
    """Print "PROGRAM: warning: MESSAGE" to stderr and carry on."""
    prog = os.path.basename(sys.argv[0]) if sys.argv and sys.argv[0] else "bolide-tool"
    sys.stderr.write("%s: warning: %s\n" % (prog, message))


def save_figure(fig, path, dpi=120):
    """Write a matplotlib figure as PNG to PATH through PATH.tmp + rename."""
    directory = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(directory):
        raise OSError("%s: directory %s does not exist" % (path, directory))
    tmp = path + ".tmp"
    try:
        fig.savefig(tmp, dpi=dpi, format="png")
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def write_figure(fig, path, dpi=120):
    """save_figure, or "PROGRAM: error: ..." and exit 1 when PATH cannot be
    written (the ending of every plotting command)."""
    try:
        save_figure(fig, path, dpi)
    except OSError as exc:
        die(str(exc))


def default_output(input_path, suffix):
    """Default PNG name: the input's base name without extension + SUFFIX,
    in the current directory (e.g. snap_0005.hdf5 -> snap_0005_sod.png)."""
    stem = os.path.splitext(os.path.basename(input_path))[0]
    return stem + suffix
