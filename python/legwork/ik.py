"""legwork.ik: the Python face of the C++ legwork::ik module (see legwork.__doc__ for units)."""
from ._legwork.ik import *  # noqa: F401,F403
from ._legwork import ik as _native

__doc__ = _native.__doc__
