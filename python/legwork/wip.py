"""legwork.wip: the Python face of the C++ legwork::wip module (see legwork.__doc__ for units)."""
from ._legwork.wip import *  # noqa: F401,F403
from ._legwork import wip as _native

__doc__ = _native.__doc__
