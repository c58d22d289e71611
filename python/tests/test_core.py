"""legwork.core: skeletons and motions from arrays, FK, resample, mirror, bad arrays."""
import numpy as np
import pytest

import legwork
from conftest import TRIAL

core = legwork.core


@pytest.fixture(scope="module")
def walk():
    return legwork.io.read_bvh(str(TRIAL), drop_first=True)


def test_skeleton_from_arrays_resolves_roles(walk):
    s = walk.skeleton
    made = core.Skeleton(s.names, s.parents.tolist(), np.array(s.offsets))
    assert made.roles == s.roles
    assert np.array_equal(made.offsets, s.offsets)
    assert made.find("Head") == s.roles["head"] and made.find("Tail") == -1


def test_skeleton_bad_input_names_the_argument(walk):
    s = walk.skeleton
    with pytest.raises(ValueError, match=r"offsets: expected .* shape \(joints, 3\), got shape \(31, 2\)"):
        core.Skeleton(s.names, s.parents.tolist(), np.zeros((31, 2)))
    with pytest.raises(ValueError, match=r"parents: joint 2 .* has parent 5"):
        core.Skeleton(s.names, [-1, 0, 5] + s.parents.tolist()[3:], np.array(s.offsets))
    with pytest.raises(ValueError, match=r"parents: expected 31 entries"):
        core.Skeleton(s.names, [-1], np.array(s.offsets))


def test_fk_positions_agree_with_forward_kinematics(walk):
    pos, rot = core.forward_kinematics(walk)
    assert np.array_equal(pos, walk.positions())
    assert np.array_equal(pos, core.joint_positions(walk))
    assert rot.shape == (walk.frame_count, walk.joint_count, 4)
    assert np.array_equal(pos[:, 0], walk.translations[:, 0])  # the root sits at its translation
    assert np.allclose(rot[:, 0], walk.rotations[:, 0])


def test_resample_keeps_duration_and_path(walk):
    r = core.resample(walk, 90.0)
    assert r.fps == 90.0
    assert r.frame_count == int(np.floor(walk.duration * 90.0)) + 1
    # Joints at shared instants (every 3rd 90 Hz frame = every 4th 120 Hz frame) within 1 cm.
    a = r.positions()[::3]
    b = walk.positions()[::4][: len(a)]
    assert np.abs(a - b).max() < 0.01


def test_mirror_twice_is_identity_and_swaps_hands(walk):
    m = core.mirror_motion(walk)
    assert np.allclose(core.mirror_motion(m).positions(), walk.positions(), atol=1e-12)
    left, right = walk.skeleton.roles["left_hand"], walk.skeleton.roles["right_hand"]
    reflected = walk.positions()[:, right] * np.array([-1.0, 1.0, 1.0])
    assert np.allclose(m.positions()[:, left], reflected, atol=1e-9)


def test_trim_and_concatenate(walk):
    a = core.trim(walk, 0, 9)
    b = core.trim(walk, 10, 19)
    ab = core.concatenate(a, b)
    assert ab.frame_count == 20
    assert np.array_equal(ab.positions(), core.trim(walk, 0, 19).positions())
    with pytest.raises(legwork.Error, match="range|frames"):
        core.trim(walk, 5, 100000)


@pytest.mark.parametrize(
    "rotations, message",
    [
        (lambda r: r.astype(np.float32), r"rotations: .*got dtype float32"),
        (lambda r: r[:, :, :3].copy(), r"rotations: .*shape \(frames, joints, 4\).*got shape \(\d+, 31, 3\)"),
        (lambda r: r[::2], r"rotations: .*non-contiguous"),  # a strided view is refused, not copied silently
        (lambda r: np.asfortranarray(r), r"rotations: .*non-contiguous"),
        (lambda r: r.tolist(), r"rotations: expected a C-contiguous float64 numpy array .*got a list"),
        (lambda r: np.where(np.arange(r.size).reshape(r.shape) == 7, np.nan, r), r"rotations: element 7 is not finite"),
        (lambda r: np.zeros_like(r), r"rotations: a quaternion has zero length"),
    ],
)
def test_motion_rejects_bad_rotations(walk, rotations, message):
    rot = rotations(walk.rotations)
    trans = np.array(walk.translations)
    with pytest.raises(ValueError, match=message):
        core.Motion(walk.skeleton, walk.fps, rot, trans)


def test_motion_rejects_bad_translations_and_rate(walk):
    rot = walk.rotations
    with pytest.raises(ValueError, match=r"translations: .*same frames as rotations.*got shape \(3, 31, 3\)"):
        core.Motion(walk.skeleton, walk.fps, rot, np.zeros((3, 31, 3)))
    with pytest.raises(ValueError, match=r"fps: expected a finite frame rate"):
        core.Motion(walk.skeleton, float("nan"), rot, np.array(walk.translations))
    with pytest.raises(ValueError, match=r"fps: expected a finite frame rate"):
        core.resample(walk, 0.0)


def test_pose_and_tracker_frame(walk):
    pose = core.Pose(walk.skeleton)
    assert np.array_equal(pose.rotations, np.tile([1.0, 0, 0, 0], (31, 1)))
    assert np.array_equal(pose.translations, walk.skeleton.offsets)
    frame = core.TrackerFrame(1.5)
    frame.set(core.Device.Head, np.array([0.0, 1.7, 0.0]), np.array([1.0, 0, 0, 0]))
    pos, rot, valid = frame.get(core.Device.Head)
    assert valid and pos[1] == 1.7 and core.usable(frame, core.Device.Head)
    assert not core.usable(frame, core.Device.LeftHand)
    frame.set(core.Device.LeftHand, np.array([np.nan, 1.0, 0.0]))
    assert not core.usable(frame, core.Device.LeftHand)  # NaN = lost tracking, not an error
    with pytest.raises(ValueError, match=r"position: .*shape \(3,\)"):
        frame.set(core.Device.Head, np.zeros(4))
