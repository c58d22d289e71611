"""legwork.io: the Python face of the C++ legwork::io module (see legwork.__doc__ for units)."""
from ._legwork.io import *  # noqa: F401,F403
from ._legwork import io as _native

__doc__ = _native.__doc__
