#!/usr/bin/env python3
"""The impact plot of Bolide: bolide.plot_impact of the bolide Python package
(console script bolide-plot-impact once the package is installed); this script
runs it from a source tree or an install.  --help lists the options."""
import os
import sys

# an installed bolide first, else the source tree's (python/ beside tools/)
# or an install's (PREFIX/bin/SCRIPT: PREFIX/share/bolide/python)
_here = os.path.dirname(os.path.abspath(__file__))
sys.path += [os.path.join(_here, "..", "python"), os.path.join(_here, "..", "share", "bolide", "python")]
from bolide.plot_impact import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
