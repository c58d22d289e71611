"""legwork: believable bodies for VR and game characters (walking-in-place legs, walk cycles,
accentuation from a headset and two controllers, full-body IK), from Python.

Submodules mirror the C++ modules one to one:

    legwork.core       Skeleton, Pose, Motion, FK, resample, mirror, TrackerFrame
    legwork.io         BVH files <-> Motion (numpy arrays)
    legwork.accent     databases, Settings / make_model / State / update, whole-clip accentuate
    legwork.ik         the full-body IK avatar (VRIK-style baseline)
    legwork.wip        walking-in-place legs
    legwork.walkcycle  walk cycles from key poses; the frame-by-frame walker
    legwork.combined   one avatar: accentuated (or IK) upper body, walking-in-place legs
    legwork.eval       MPJPE, MPJVE, jitter, foot skating, step F1

Units: metres, seconds, radians unless a name says otherwise; legwork's frame is right-handed,
y up, characters face +z. Arrays are float64 and C-contiguous; quaternions are (w, x, y, z) in
the last axis. Errors from the library raise legwork.Error with the library's message; bad
arguments (shape, dtype, contiguity, NaN) raise ValueError naming the argument.
"""
from . import _legwork
from ._legwork import Error
from . import core, io, accent, ik, wip, walkcycle, combined, eval  # noqa: F401  (eval: the module, as in C++)

__all__ = ["Error", "core", "io", "accent", "ik", "wip", "walkcycle", "combined", "eval"]
