"""The analysis code of Bolide's tools is the `bolide` Python package
(python/bolide; `pip install` it from a build: BUILD/python).  This name is
kept so that scripts written for it still run: bolide_tools.snapshot is
bolide.snapshot, and so on."""
import os
import sys

try:
    import bolide
except ImportError:  # the source tree's package, beside tools/
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
    import bolide

from bolide import common, l1, riemann, sedov, snapshot  # noqa: E402

for _m in ("common", "l1", "riemann", "sedov", "snapshot"):
    sys.modules["bolide_tools." + _m] = sys.modules["bolide." + _m]
