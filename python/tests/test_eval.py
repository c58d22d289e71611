"""legwork.eval: metrics on known displacements, and bad input."""
import json
import pathlib

import numpy as np
import pytest

import legwork
from conftest import SOURCE, TRIAL

ev = legwork.eval


@pytest.fixture(scope="module")
def track():
    return ev.role_track(legwork.io.read_bvh(str(TRIAL), drop_first=True))


def shifted(track, offset):
    return ev.RoleTrack(track.fps, np.ascontiguousarray(track.positions + np.asarray(offset)), track.present)


def test_truth_against_itself_is_zero(track):
    m = ev.evaluate_trial(track, track)
    assert m.mpjpe_cm == 0 and m.mpjve_cm_s == 0
    assert m.jitter == m.jitter_truth > 0
    assert m.foot_skating_cm == m.foot_skating_truth_cm
    assert m.hand_correlation[0] == pytest.approx(1.0)


def test_a_constant_shift_is_its_length_in_cm(track):
    off = shifted(track, [0.0, 0.03, 0.04])  # 5 cm
    assert ev.mpjpe(off, track) == pytest.approx(5.0, rel=1e-9)
    assert ev.mpjve(off, track) == pytest.approx(0.0, abs=1e-9)  # same velocities
    m = ev.evaluate_trial(off, track)
    assert all(v == pytest.approx(5.0, rel=1e-9) for v in m.part_cm.values())


def test_jitter_and_foot_skating_see_noise(track):
    rng = np.random.default_rng(7)
    noisy = ev.RoleTrack(track.fps, track.positions + rng.normal(0, 0.005, track.positions.shape) * np.array(track.present)[None, :, None],
                         track.present)
    assert ev.mean_jerk(noisy) > 10 * ev.mean_jerk(track)
    slide, contact = ev.foot_skating(track)
    noisy_slide, _ = ev.foot_skating(noisy)
    assert 0 < contact < 1 and noisy_slide > slide


def test_role_track_layout(track):
    assert track.positions.shape == (track.frames, len(ev.ROLES), 3)
    assert len(ev.PARTS) == 5 and ev.ROLES[0] == "pelvis"
    assert all(track.present)


def test_bad_tracks(track):
    with pytest.raises(ValueError, match=r"positions: .*\(frames, 21 roles, 3\)"):
        ev.RoleTrack(90.0, np.zeros((10, 20, 3)), track.present)
    with pytest.raises(ValueError, match=r"present: expected 21 flags"):
        ev.RoleTrack(90.0, np.zeros((10, 21, 3)), [True])
    with pytest.raises(ValueError, match="positions: element 0 is not finite"):
        ev.RoleTrack(90.0, np.full((10, 21, 3), np.nan), track.present)
    short = ev.RoleTrack(track.fps, np.ascontiguousarray(track.positions[:10]), track.present)
    with pytest.raises(legwork.Error, match="frames|length"):
        ev.evaluate_trial(short, track)


def test_evaluate_combined_equals_the_cli(cli, tmp_path):
    """legwork.eval.evaluate_combined gives `legwork eval combined`'s report (same trials, same table)."""
    files = sorted(str(p) for p in (SOURCE / "data/cmu/bvh/walking").glob("*.bvh"))[:2]
    table = str(SOURCE / "data/wip/learned_mapping.txt")
    report = legwork.eval.evaluate_combined(files, wip_table=table)
    folder = tmp_path / "walks"
    folder.mkdir()
    for f in files:
        (folder / pathlib.Path(f).name).symlink_to(f)
    cli("eval", "combined", "--data", folder, "--wip-table", table, "--out", tmp_path / "out")
    expected = json.loads((tmp_path / "out/report.json").read_text())
    assert set(report["methods"]) == {"ik", "combined_ik", "combined_ik_learned"}
    for method, figures in expected["methods"].items():
        for key, value in figures.items():
            assert report["methods"][method][key] == pytest.approx(value, rel=1e-12), (method, key)
    # The learned legs are nearer the capture's than the IK avatar's on these walks.
    assert report["methods"]["combined_ik_learned"]["lower_body_cm"] < report["methods"]["ik"]["lower_body_cm"]
    with pytest.raises(legwork.Error, match=r"CMakeLists.txt:1: not a learned walking-in-place mapping"):
        legwork.eval.evaluate_combined(files, wip_table=str(SOURCE / "CMakeLists.txt"))
    with pytest.raises(legwork.Error, match="no walking trials given"):
        legwork.eval.evaluate_combined([])
