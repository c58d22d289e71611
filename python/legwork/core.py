"""legwork.core: the Python face of the C++ legwork::core module (see legwork.__doc__ for units)."""
from ._legwork.core import *  # noqa: F401,F403
from ._legwork import core as _native

__doc__ = _native.__doc__
