"""legwork.accent: the Python face of the C++ legwork::accent module (see legwork.__doc__ for units)."""
from ._legwork.accent import *  # noqa: F401,F403
from ._legwork import accent as _native

__doc__ = _native.__doc__
