#!/usr/bin/env python3
"""The fragments plot of Bolide: bolide.plot_fragments of the bolide Python package
(console script bolide-plot-fragments once the package is installed); this script
runs it from a source tree or an install.  --help lists the options."""
import os
import sys

try:
    from bolide.plot_fragments import main
except ImportError:
    # the source tree's package beside tools/, or an install's (PREFIX/bin/SCRIPT:
    # PREFIX/share/bolide/python)
    _here = os.path.dirname(os.path.abspath(__file__))
    sys.path[:0] = [os.path.join(_here, "..", "python"),
                    os.path.join(_here, "..", "share", "bolide", "python")]
    try:
        from bolide.plot_fragments import main
    except ImportError as exc:
        sys.exit("%s: error: the bolide Python package is not installed (pip install BUILD/python): %s"
                 % (os.path.basename(sys.argv[0]), exc))

if __name__ == "__main__":
    sys.exit(main())
