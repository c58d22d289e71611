"""legwork.accent against `legwork accent build/run`, frame by frame, the C example, and bad input."""
import json
import os

import numpy as np
import pytest

import legwork
from conftest import HELD_OUT, SOURCE, TRIAL

core, accent = legwork.core, legwork.accent


def tracks(motion):
    """Head position/rotation and wrist positions of a motion, as contiguous arrays."""
    pos, rot = core.forward_kinematics(motion)
    roles = motion.skeleton.roles
    c = np.ascontiguousarray
    return (c(pos[:, roles["head"]]), c(rot[:, roles["head"]]), c(pos[:, roles["left_hand"]]),
            c(pos[:, roles["right_hand"]]))


@pytest.fixture(scope="module")
def truth(db):
    """The held-out trial at the database rate, as `legwork accent run` prepares it."""
    return core.resample(legwork.io.read_bvh(str(TRIAL), drop_first=True), db.fps)


def settings_for(motion):
    s = accent.Settings()
    s.user_height = core.measure_body(motion.skeleton)["standing_height"]
    return s


def test_python_build_equals_cli_build(db):
    built = accent.build_database(str(SOURCE / "data/cmu"), exclude=[HELD_OUT])
    assert built.classes == db.classes
    assert built.window_count == db.window_count and built.pose_count == db.pose_count
    assert HELD_OUT not in db.trials and db.is_mapped


def test_info_equals_cli_info(cli, db, db_path):
    """Database.info() is `legwork info FILE.lwdb --json` without the file and its load time."""
    cli_info = json.loads(cli("info", db_path, "--json"))
    info = db.info()
    assert cli_info.pop("file") == str(db_path) and cli_info.pop("load_ms") > 0
    assert info == cli_info
    assert [c["name"] for c in info["classes"]] == db.classes
    assert sum(c["windows"] for c in info["classes"]) == db.window_count == info["windows"]
    assert sum(c["trials"] for c in info["classes"]) == len(db.trials) == len(info["trials"])
    assert info["search_index"] is True and info["height_m"] == pytest.approx(db.height)


def test_accentuate_equals_cli_run(cli, db, db_path, truth, tmp_path):
    out_bvh, report = tmp_path / "run.bvh", tmp_path / "run.json"
    cli("accent", "run", "--db", db_path, "--input", TRIAL, "--drop-first", "--out", out_bvh, "--json", report)
    # From the motion, as the CLI drives it: the devices' full poses (the IK blend reads the wrists' orientation).
    run = accent.accentuate_motion(db, settings_for(truth), truth)
    motion = run["motion"]
    back = legwork.io.read_bvh(str(out_bvh), scale=1.0)
    assert back.frame_count == motion.frame_count == truth.frame_count
    # The CLI's file has 6 decimals (mm-level rounding of degrees and metres).
    assert np.abs(back.positions() - motion.positions()).max() < 2e-4
    # Its ground-truth figures are the eval module's on the same output.
    cli_err = json.loads(report.read_text())["accent_error"]
    m = legwork.eval.evaluate_trial(legwork.eval.role_track(motion), legwork.eval.role_track(truth))
    assert m.mpjpe_cm == pytest.approx(cli_err["full_body_cm"], rel=1e-12)
    assert m.part_cm["left_hand"] == pytest.approx(cli_err["left_hand_cm"], rel=1e-12)
    assert m.part_cm["lower_body"] == pytest.approx(cli_err["lower_body_cm"], rel=1e-12)
    assert m.foot_skating_cm == pytest.approx(cli_err["foot_skating_cm"], rel=1e-12)
    assert 1.0 < m.mpjpe_cm < 30.0  # a body, not a collapsed or exploded pose


def test_frame_by_frame_equals_whole_clip(db, truth):
    settings = settings_for(truth)
    head, head_rot, left, right = tracks(truth)
    whole = accent.accentuate(db, head, head_rot, left, right, fps=db.fps, settings=settings)
    model = accent.make_model(db, settings)
    state = accent.State(model)
    pose = core.Pose(model.skeleton())
    info = accent.Info()
    frames = core.tracker_frames(db.fps, head, head_rot, left, right)
    rotations = np.empty((len(frames), model.skeleton().joint_count, 4))
    matched = 0
    for i, frame in enumerate(frames):
        status = accent.update(model, frame, state, pose, info)
        assert status == core.UpdateStatus.Ok
        matched += info.match == accent.MatchStatus.Matched
        rotations[i] = pose.rotations
    assert np.array_equal(rotations, whole["motion"].rotations)
    assert np.array_equal(whole["status"], np.zeros(len(frames), dtype=np.int32))
    assert matched > len(frames) // 2


def test_no_class_setting_recognises_walking(db, truth):
    """No class given: the engine recognises the held-out walking trial's class; off, it does not recognise."""
    head, head_rot, left, right = tracks(truth)
    frames = core.tracker_frames(db.fps, head, head_rot, left, right)
    counts, searched_counts = {}, {}
    for recognise in (True, False):
        settings = settings_for(truth)
        assert settings.recognize_class  # the default
        settings.recognize_class = recognise
        model = accent.make_model(db, settings)
        state, pose, info = accent.State(model), core.Pose(model.skeleton()), accent.Info()
        active, searched = [], []
        for frame in frames:
            accent.update(model, frame, state, pose, info)
            active.append(info.active_class)
            if info.searched:  # search_interval: a frame that continued its matches searched no class
                searched.append(info.classes_searched)
            else:
                assert info.classes_searched == 0
            fields = info.fields()  # the server's and the C API's names for the same figures
            assert fields["active_class"] == info.active_class
            assert fields["classes_searched"] == info.classes_searched
            assert fields["searched"] == (1 if info.searched else 0)
            assert fields["match_weight"] == pytest.approx(info.match_weight)
            assert (fields["matches_left"], fields["matches_right"]) == tuple(info.matches)
            assert fields["match"] == {accent.MatchStatus.Matched: "matched", accent.MatchStatus.Partial: "partial",
                                       accent.MatchStatus.Unmatched: "unmatched",
                                       accent.MatchStatus.TrackingLost: "tracking-lost"}[info.match]
        counts[recognise] = active
        searched_counts[recognise] = searched
    walking = db.classes.index("walking")
    assert counts[True].count(walking) > len(frames) // 2
    assert set(counts[False]) == {-1}
    # Off, every class is searched; on, the recognised one and the others whose cost could enter the matches.
    assert set(searched_counts[False]) == {len(db.classes)}
    assert 1 <= min(searched_counts[True]) and max(searched_counts[True]) <= len(db.classes)


def test_cli_reports_recognised_classes_and_can_turn_them_off(cli, db, db_path, truth, tmp_path):
    """`legwork accent run` without --classes recognises the class (frames per class in its JSON, as the
    Python run's Info.active_class counts them); --no-class-recognition leaves the field out."""
    on, off = tmp_path / "on.json", tmp_path / "off.json"
    cli("accent", "run", "--db", db_path, "--input", TRIAL, "--drop-first", "--out", tmp_path / "on.bvh", "--json", on)
    cli("accent", "run", "--db", db_path, "--input", TRIAL, "--drop-first", "--out", tmp_path / "off.bvh", "--json", off,
        "--no-class-recognition")
    recognised = json.loads(on.read_text())["recognized_classes"]
    assert sum(recognised["frames"].values()) == truth.frame_count
    assert max(recognised["frames"], key=recognised["frames"].get) == "walking"
    assert "recognized_classes" not in json.loads(off.read_text())


def g17(x):
    return "%.17g" % x


def test_same_csv_as_the_c_example(db_path):
    """examples/c/main.c's CSV (from CTest's capi fixtures), written again through Python."""
    c_csv = os.environ.get("LEGWORK_CAPI_CSV")
    if not c_csv or not os.path.exists(c_csv):
        pytest.skip("LEGWORK_CAPI_CSV (the C example's output) not available")
    db = accent.load_database(str(db_path))
    settings = accent.Settings()
    settings.user_height = 1.7
    model = accent.make_model(db, settings)
    state, pose = accent.State(model), core.Pose(model.skeleton())
    frames = core.tracker_frames_from_motion(legwork.io.read_bvh(str(TRIAL), drop_first=True), 90.0)
    lines = []
    for f, frame in enumerate(frames):
        status = accent.update(model, frame, state, pose).name.lower()
        rot, pos = pose.rotations, pose.positions(model.skeleton())
        for j in range(len(rot)):
            lines.append(",".join([str(f), status, str(j)] + [g17(v) for v in rot[j]] + [g17(v) for v in pos[j]]))
    with open(c_csv) as fh:
        assert fh.read() == "\n".join(lines) + "\n"


def test_lost_tracking_rows_degrade_not_fail(db, truth):
    head, head_rot, left, right = tracks(truth)
    left = left.copy()
    left[100:120] = np.nan
    run = accent.accentuate(db, head, head_rot, left, right, fps=db.fps, settings=settings_for(truth))
    status = run["status"]
    assert (status[100:120] == int(core.UpdateStatus.Degraded)).all()
    assert (status[:100] == int(core.UpdateStatus.Ok)).all()
    assert np.isfinite(run["motion"].positions()).all()


def test_foot_lift_setting_equals_the_cli_option(cli, db, db_path, truth, tmp_path):
    """Settings.foot_lift_height is the CLI's --foot-lift-height: the same motion either way, and released feet
    rise above the flat release's; out of range it is an error naming the setting."""
    out_bvh = tmp_path / "lift.bvh"
    cli("accent", "run", "--db", db_path, "--input", TRIAL, "--drop-first", "--out", out_bvh, "--foot-lift-height", "0.1",
        "--foot-swing-speed", "0")
    s = settings_for(truth)
    assert s.foot_lift_height == pytest.approx(0.05)  # the default
    s.foot_swing_speed = 0.0  # the release arc alone (swinging feet are lifted by foot_lift_height too)
    s.foot_lift_height = 0.1
    lifted = accent.accentuate_motion(db, s, truth)["motion"]
    s.foot_lift_height = 0.0
    flat = accent.accentuate_motion(db, s, truth)["motion"]
    back = legwork.io.read_bvh(str(out_bvh), scale=1.0)
    assert np.abs(back.positions() - lifted.positions()).max() < 2e-4
    ankles = [lifted.skeleton.roles[r] for r in ("left_ankle", "right_ankle")]
    rise = (lifted.positions()[:, ankles, 1] - flat.positions()[:, ankles, 1]).max()
    assert 0.05 < rise <= 0.1 + 1e-9
    s.foot_lift_height = 0.7
    with pytest.raises(legwork.Error, match="foot_lift_height must be between 0 and 0.5 metres"):
        accent.make_model(db, s)


def test_foot_slack_and_swing_settings_equal_the_cli_options(cli, db, db_path, truth, tmp_path):
    """Settings.foot_lock_slack / foot_lock_hold_seconds / foot_swing_speed are the CLI's --foot-lock-slack /
    --foot-lock-hold / --foot-swing-speed: the same motion either way, and they change it; out of range they are
    errors naming the setting."""
    out_bvh = tmp_path / "slack.bvh"
    cli("accent", "run", "--db", db_path, "--input", TRIAL, "--drop-first", "--out", out_bvh, "--foot-lock-slack", "0.1",
        "--foot-lock-hold", "0", "--foot-swing-speed", "0")
    s = settings_for(truth)
    assert s.foot_lock_slack == pytest.approx(0.0) and s.foot_swing_speed == pytest.approx(0.5)  # the defaults
    assert s.foot_lock_hold_seconds == pytest.approx(0.2)
    default = accent.accentuate_motion(db, s, truth)["motion"]
    s.foot_lock_slack = 0.1
    s.foot_lock_hold_seconds = 0.0
    s.foot_swing_speed = 0.0
    plain = accent.accentuate_motion(db, s, truth)["motion"]
    back = legwork.io.read_bvh(str(out_bvh), scale=1.0)
    assert np.abs(back.positions() - plain.positions()).max() < 2e-4
    assert np.abs(default.positions() - plain.positions()).max() > 1e-3
    s.foot_lock_slack = 1.5
    with pytest.raises(legwork.Error, match="foot_lock_slack must be between 0 and 1 metre"):
        accent.make_model(db, s)
    s.foot_lock_slack = 0.1
    s.foot_swing_speed = 12.0
    with pytest.raises(legwork.Error, match="foot_swing_speed must be between 0 and 10 m/s"):
        accent.make_model(db, s)
    s.foot_swing_speed = 0.0
    s.foot_lock_hold_seconds = float("nan")
    with pytest.raises(legwork.Error, match=r"foot_lock_hold_seconds must be between 0 and 10 s \(how long a planted foot"):
        accent.make_model(db, s)


def test_no_floor_equals_the_cli_flag(cli, db, db_path, truth, tmp_path):
    """Settings.floor = False is `accent run --no-floor`: the same motion either way, and a different one from the
    default's (the walk's synthesized feet dip below their rest heights over the floor on some frames)."""
    out_bvh = tmp_path / "no_floor.bvh"
    cli("accent", "run", "--db", db_path, "--input", TRIAL, "--drop-first", "--out", out_bvh, "--no-floor")
    s = settings_for(truth)
    assert s.floor is True and s.floor_height == 0.0  # the defaults
    default = accent.accentuate_motion(db, s, truth)["motion"]
    s.floor = False
    loose = accent.accentuate_motion(db, s, truth)["motion"]
    back = legwork.io.read_bvh(str(out_bvh), scale=1.0)
    assert np.abs(back.positions() - loose.positions()).max() < 2e-4
    assert np.abs(default.positions() - loose.positions()).max() > 1e-3


@pytest.mark.parametrize("name, flag, value, default, changes, bad, message", [
    # the travel terms' weight (0 = hand features only)
    ("travel_weight", "--travel-weight", 0.0, 2.0, True, -1.0, r"travel_weight must be between 0 and 100 \(0 = off\)"),
    # the head-height gate (its effect: tests/accent's AStandingUserGetsNoLyingBodyUnderTheHead)
    ("max_head_height_diff", "--max-head-height-diff", 0.3, 0.15, False, 2.5,
     r"max_head_height_diff must be between 0 and 2"),
    # the candidates' motion played forward in the smoothing (effect: tests/accent's HeldOutRunner)
    ("smooth_feedforward", "--smooth-feedforward", 0.0, 1.0, True, 1.5, r"smooth_feedforward must be between 0 and 1"),
    # a lying user's root smoothed longer; the walk stands, so no change (effect: tests/accent's HeldOutLyingSwimmer)
    ("lying_root_smoothing", "--lying-root-smoothing", 1.0, 8.0, False, 0.5,
     r"lying_root_smoothing must be between 1 and 20"),
    # a lying user turned by the headset's crown; the walk stands, so no change (effect: tests/accent's HeldOutBackStroke)
    ("lying_crown", "--lying-crown", 0.0, 1.0, False, 1.5, r"lying_crown must be between 0 and 1"),
    # other classes at a cost while recognising the class (effect: tests/accent's
    # NoClassGivenOtherClassesAtACostBringTheRunnerNearerTheTruth); the sample database holds several classes and
    # the walk's class is recognised, so the walk changes
    ("other_class_cost", "--other-class-cost", 0.0, 1.25, True, 0.5,
     r"other_class_cost must be 0 \(search only the classes to match\) or a factor from 1 to 1e6"),
    # searching every hop, the matches continued in between (effect: tests/accent's
    # SearchingEveryHopContinuesTheMatchesInTheirTrials)
    ("search_interval", "--search-interval", 0.0, 0.044, True, 1.5,
     r"search_interval must be between 0 and 1 second \(0 = search every frame\)"),
    # where the floor is: half a metre up, every foot stands higher (effect: tests/accent's
    # FeetNeverGoThroughTheFloorAndFeetPushedIntoItStand)
    ("floor_height", "--floor-height", 0.5, 0.0, True, 12.0, r"floor_height must be between -10 and 10 metres"),
])
def test_engine_setting_equals_the_cli_option(cli, db, db_path, truth, tmp_path, name, flag, value, default, changes,
                                              bad, message):
    """Each of these Settings fields is its CLI option of `accent run`: the same motion either way (and, where the
    setting acts on the walk, a different one from the default's); out of range it is an error naming the
    setting."""
    out_bvh = tmp_path / (name + ".bvh")
    cli("accent", "run", "--db", db_path, "--input", TRIAL, "--drop-first", "--out", out_bvh, flag, str(value))
    s = settings_for(truth)
    assert getattr(s, name) == pytest.approx(default)  # the engine's default
    before = accent.accentuate_motion(db, s, truth)["motion"]
    setattr(s, name, value)
    after = accent.accentuate_motion(db, s, truth)["motion"]
    back = legwork.io.read_bvh(str(out_bvh), scale=1.0)
    assert np.abs(back.positions() - after.positions()).max() < 2e-4
    assert (np.abs(before.positions() - after.positions()).max() > 1e-3) == changes
    setattr(s, name, bad)
    with pytest.raises(legwork.Error, match=message):
        accent.make_model(db, s)


def test_run_reports_foot_contacts_locks_and_the_ik_share(db, truth):
    """The run's dict carries, per frame, the blended candidates' foot contact, whether each foot is planted
    (locked) and the IK body's share: on the held-out walk both feet plant, in turns, only where the contact
    says so (a planted foot lets go below contact_off), and a planted ankle moves less than a free one."""
    s = settings_for(truth)
    run = accent.accentuate_motion(db, s, truth)
    n = len(run["status"])
    contact, locked, share = run["contact"], run["foot_locked"], run["ik_share"]
    assert contact.shape == (n, 2) and locked.shape == (n, 2) and share.shape == (n,)
    assert locked.dtype == bool
    assert ((contact >= 0) & (contact <= 1)).all() and ((share >= 0) & (share <= 1)).all()
    for f in range(2):
        assert 0.1 * n < locked[:, f].sum() < 0.9 * n  # each foot plants and lifts
        assert (contact[locked[:, f], f] > s.contact_off).all()
    assert (locked[:, 0] != locked[:, 1]).sum() > 0.2 * n  # in turns, not together
    pos = run["motion"].positions()
    roles = run["motion"].skeleton.roles
    for f, name in enumerate(["left_ankle", "right_ankle"]):
        step = np.linalg.norm(np.diff(pos[:, roles[name], :], axis=0), axis=1)
        held = locked[1:, f] & locked[:-1, f]
        assert step[held].mean() < 0.5 * step[~held].mean()


def test_bad_settings_and_arrays(db, truth):
    s = accent.Settings()
    s.classes = ["walking", "flying"]
    with pytest.raises(legwork.Error, match=r"flying.*walking|walking.*flying"):
        accent.make_model(db, s)
    s = accent.Settings()
    s.k_left = 33
    with pytest.raises(legwork.Error, match="k must be between 0 and 32"):
        accent.make_model(db, s)
    head, head_rot, left, right = tracks(truth)
    with pytest.raises(ValueError, match=r"head_rotation: .*\(frames, 4\)"):
        accent.accentuate(db, head, head, left, right, fps=90.0)
    with pytest.raises(ValueError, match=r"left_hand: .*frames as head_position.*got shape \(10, 3\)"):
        accent.accentuate(db, head, head_rot, left[:10].copy(), right, fps=90.0)
    with pytest.raises(ValueError, match=r"right_hand: .*non-contiguous"):
        accent.accentuate(db, head, head_rot, left, np.asfortranarray(np.tile(right, (1, 2))[:, :3]), fps=90.0)
    with pytest.raises(ValueError, match=r"fps"):
        accent.accentuate(db, head, head_rot, left, right, fps=-1.0)
    model = accent.make_model(db)
    with pytest.raises(ValueError, match=r"out: a Pose of the model's skeleton \(31 joints\)"):
        accent.update(model, core.TrackerFrame(0.0), accent.State(model), core.Pose(core.Skeleton(["a"], [-1], np.zeros((1, 3)))))


def test_corrupt_database_raises(tmp_path):
    bad = tmp_path / "bad.lwdb"
    bad.write_bytes(b"not a database at all" * 10)
    with pytest.raises(legwork.Error, match=r"bad.lwdb.*not a legwork accent database"):
        accent.load_database(str(bad))
    with pytest.raises(legwork.Error, match="missing.lwdb"):
        accent.load_database(str(tmp_path / "missing.lwdb"))
