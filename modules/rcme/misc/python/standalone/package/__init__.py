"""Robust camera motion estimation (model quality aware RANSAC): the standalone twin of cv2.rcme.

Every name comes from the native module rcme._rcme; this package adds the type stub
(__init__.pyi, py.typed) that editors and type checkers read.
"""

from . import _rcme
from ._rcme import *  # noqa: F401,F403 (the binding's public names are the package's)

__doc__ = _rcme.__doc__

# The classes say they live in `rcme` (as cv2.rcme's say cv2.rcme), so that repr, help() and
# pickle name them by their public path.
for _value in list(vars(_rcme).values()):
    if isinstance(_value, type) and _value.__module__ == _rcme.__name__:
        _value.__module__ = __name__
del _value
