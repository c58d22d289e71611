"""legwork.eval: the Python face of the C++ legwork::eval module (see legwork.__doc__ for units)."""
from ._legwork.eval import *  # noqa: F401,F403
from ._legwork import eval as _native

__doc__ = _native.__doc__
