"""legwork.walkcycle: the Python face of the C++ legwork::walkcycle module (see legwork.__doc__ for units)."""
from ._legwork.walkcycle import *  # noqa: F401,F403
from ._legwork import walkcycle as _native

__doc__ = _native.__doc__
