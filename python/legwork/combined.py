"""legwork.combined: the Python face of the C++ legwork::combined module (see legwork.__doc__ for units)."""
from ._legwork.combined import *  # noqa: F401,F403
from ._legwork import combined as _native

__doc__ = _native.__doc__
