"""legwork.io against `legwork info --json`, round trips and bad files."""
import json

import numpy as np
import pytest

import legwork
from conftest import SOURCE, TRIAL


def test_read_bvh_matches_cli_info(cli):
    info = json.loads(cli("info", TRIAL, "--json"))
    motion, report = legwork.io.read_bvh(str(TRIAL), report=True)
    skel = motion.skeleton
    assert motion.frame_count == info["frames"]
    assert skel.joint_count == info["joints"]
    # info rounds for people (120.0, not 120.00048000192); frame_time_s is exact.
    assert motion.fps == pytest.approx(info["fps"], abs=5e-4)
    assert 1.0 / motion.fps == pytest.approx(info["frame_time_s"], rel=1e-12)
    assert motion.duration == pytest.approx(info["duration_s"], abs=5e-5)
    assert report["scale"] == info["scale_to_metres"]
    assert report["scale_reason"] == info["scale_reason"]
    assert report["repaired_zero_frames"] == info["repaired_zero_frames"]
    names = [j["name"] for j in info["joint_list"]]
    assert skel.names == names
    parents = [names.index(j["parent"]) if j["parent"] else -1 for j in info["joint_list"]]
    assert skel.parents.tolist() == parents
    assert [names[i] for i in skel.mirror] == [j["mirror"] for j in info["joint_list"]]
    assert {role: names[j] for role, j in skel.roles.items()} == info["roles"]
    body = legwork.core.measure_body(skel)
    for key in ("standing_height", "hip_height", "leg_length", "arm_length"):
        assert body[key] == pytest.approx(info[key + "_m"], abs=5e-5)  # rounded to 0.1 mm


def test_arrays_have_documented_shapes_and_units():
    motion = legwork.io.read_bvh(str(TRIAL), drop_first=True)
    f, j = motion.frame_count, motion.joint_count
    assert motion.rotations.shape == (f, j, 4) and motion.rotations.dtype == np.float64
    assert np.allclose(np.linalg.norm(motion.rotations, axis=2), 1.0)
    assert motion.translations.shape == (f, j, 3)
    pos = motion.positions()
    assert pos.shape == (f, j, 3)
    # Metres: a CMU walker's head is 1.3-1.8 m above the floor (y up).
    head = motion.skeleton.roles["head"]
    assert 1.2 < np.median(pos[:, head, 1] - pos[:, :, 1].min(axis=1)) < 1.9
    # FK keeps bone lengths equal to the rest offsets.
    parents = motion.skeleton.parents
    child = np.arange(1, j)
    bone = np.linalg.norm(pos[:, child] - pos[:, parents[child]], axis=2)
    assert np.allclose(bone, np.linalg.norm(motion.skeleton.offsets[child], axis=1), atol=1e-9)


def test_translations_are_a_view_not_a_copy():
    motion = legwork.io.read_bvh(str(TRIAL))
    a, b = motion.translations, motion.translations
    assert np.shares_memory(a, b)
    before = motion.positions()[:, 0].copy()
    a[:, 0, 1] += 0.5
    assert np.allclose(motion.positions()[:, 0, 1], before[:, 1] + 0.5)


def test_write_then_read_round_trip(tmp_path):
    motion = legwork.io.read_bvh(str(TRIAL), drop_first=True)
    out = tmp_path / "round.bvh"
    legwork.io.write_bvh(str(out), motion)
    back = legwork.io.read_bvh(str(out), scale=1.0)
    assert back.skeleton.names == motion.skeleton.names
    assert back.frame_count == motion.frame_count
    # Six decimals in the file: positions agree to well under a millimetre.
    assert np.abs(back.positions() - motion.positions()).max() < 1e-4


def test_motion_from_arrays_writes_what_it_was_given(tmp_path):
    src = legwork.io.read_bvh(str(TRIAL), drop_first=True)
    made = legwork.core.Motion(src.skeleton, src.fps, src.rotations, np.array(src.translations))
    assert np.array_equal(made.positions(), src.positions())
    legwork.io.write_bvh(str(tmp_path / "made.bvh"), made)
    assert legwork.io.read_bvh(str(tmp_path / "made.bvh"), scale=1.0).frame_count == src.frame_count


def test_missing_and_malformed_files_raise_legwork_error(tmp_path):
    with pytest.raises(legwork.Error, match="nope.bvh"):
        legwork.io.read_bvh(str(tmp_path / "nope.bvh"))
    bad = tmp_path / "bad.bvh"
    bad.write_text("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 zero\n")
    with pytest.raises(legwork.Error, match=r"bad.bvh:4"):
        legwork.io.read_bvh(str(bad))
    with pytest.raises(ValueError, match="scale"):
        legwork.io.read_bvh(str(TRIAL), scale=-1.0)
