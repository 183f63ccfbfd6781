"""Bolide's Python package: read Bolide's (and SWIFT's) snapshots and
statistics files with units, analytic solutions, and the plots.

Modules:

  units           load_snapshot, load_statistics: unyt arrays in SI (as
                  swiftsimio gives them), whatever units the run used
  snapshot        the readers underneath (numpy arrays; si=True converts):
                  load, read_stats, read_stats_units, read_fragments
  plot_impact     collision pictures, mass bound to the largest remnant,
                  energy budget: load_snapshots, bound_history,
                  bound_figure, collision_figure, energy_figure (console
                  script bolide-plot-impact)
  plot_fragments  cumulative fragment mass spectrum of bolide-fof tables:
                  spectrum (bolide-plot-fragments)
  plot_profile    a planet profile of bolide-ic planet --profile:
                  read_profile, profile_figure (bolide-plot-profile)
  plot_tasks      the task timeline of a task dump: read_dump, timeline
                  (bolide-plot-tasks)
  The *_figure functions, spectrum and timeline return matplotlib figures;
  each module's main(argv) is its console script.
  riemann         exact Riemann solver for an ideal gas (Toro 2009, ch. 4)
  sedov           Sedov-Taylor point explosion in 3D (Sedov 1959; Kamm &
                  Timmes 2007)
  l1              L1 error of particle values against an analytic profile
  common          small helpers of the command-line scripts

Only numpy, scipy, h5py and matplotlib are needed (unyt for bolide.units).
The scripts in Bolide's tools/ folder call this package.  __version__ is
Bolide's version, written by the build (make python); from a source tree
that was not built, it is read from configure.ac with "+src".
"""
import os as _os
import re as _re

try:
    from ._version import __version__
except ImportError:  # a source tree: configure.ac's AC_INIT
    __version__ = "unknown"
    _ac = _os.path.join(_os.path.dirname(__file__), "..", "..", "configure.ac")
    if _os.path.exists(_ac):
        _m = _re.search(r"AC_INIT\(\[[^]]*\],\s*\[([^]]*)\]", open(_ac).read())
        if _m:
            __version__ = _m.group(1) + "+src"


def load_snapshot(path):
    """A snapshot's particle fields as unyt arrays in SI (bolide.units)."""
    from .units import load_snapshot as _load
    return _load(path)


def load_statistics(path):
    """A statistics file's columns as unyt arrays in SI (bolide.units)."""
    from .units import load_statistics as _load
    return _load(path)
