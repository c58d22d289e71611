"""legwork.ik, legwork.wip, legwork.walkcycle: the same contract (Settings, make_model, State, reset,
update, Info), against the CLI where it reports figures, and by behaviour otherwise."""
import json
import re

import numpy as np
import pytest

import legwork
from conftest import SOURCE, TRIAL

core, ik, wip, walkcycle = legwork.core, legwork.ik, legwork.wip, legwork.walkcycle


def drive(module, model, frames, info=None):
    """Runs one avatar over frames; returns (Motion at 90 Hz, statuses)."""
    state, pose = module.State(model), core.Pose(model.skeleton())
    rot, trans, status = [], [], []
    for frame in frames:
        status.append(module.update(model, frame, state, pose, info))
        rot.append(pose.rotations)
        trans.append(np.array(pose.translations))
    return core.Motion(model.skeleton(), 90.0, np.ascontiguousarray(rot), np.ascontiguousarray(trans)), status


@pytest.mark.parametrize("module", [ik, wip, walkcycle, legwork.accent, legwork.combined])
def test_every_runtime_has_the_contract_names(module):
    for name in ("Settings", "Model", "make_model", "State", "reset", "update", "Info"):
        assert hasattr(module, name), f"{module.__name__}.{name}"


def protocol_info_names():
    """Each method's pose-info names as docs/protocol.md lists them (the `info` row of the pose message)."""
    row = next(line for line in (SOURCE / "docs/protocol.md").read_text().splitlines() if line.startswith("| `info` |"))
    listed = row.split("writes them). ", 1)[1]
    names, method = {}, None
    for part in re.split(r"(?:^|; )(accent|ik|combined|wip|walker): ", listed)[1:]:
        if method is None:
            method = part
            continue
        flat = part
        while re.search(r"\([^()]*\)", flat):  # drop the explanations in parentheses (they quote values)
            flat = re.sub(r"\([^()]*\)", "", flat)
        names[method] = set(re.findall(r"`([a-z_]+)`", flat))
        method = None
    return names


@pytest.mark.parametrize("method,module", [("accent", legwork.accent), ("ik", ik), ("combined", legwork.combined),
                                           ("wip", wip), ("walker", walkcycle)])
def test_info_fields_are_the_protocols_names(method, module):
    """Info.fields() gives the names docs/protocol.md lists for the server's pose info (the C API's too)."""
    listed = protocol_info_names()
    assert method in listed, f"docs/protocol.md lists no info names for {method}"
    fields = module.Info().fields()
    assert set(fields) == listed[method]
    assert all(isinstance(v, (float, str)) for v in fields.values())


def test_ik_equals_the_cli_baseline(cli, db_path, tmp_path):
    report = tmp_path / "ik.json"
    cli("accent", "run", "--db", db_path, "--input", TRIAL, "--drop-first", "--out", tmp_path / "a.bvh",
        "--compare-ik", "--json", report)
    truth = core.resample(legwork.io.read_bvh(str(TRIAL), drop_first=True), 90.0)
    # The baseline gets what the engine gets: the database's skeleton scaled to the user's height.
    settings = legwork.accent.Settings()
    settings.user_height = core.measure_body(truth.skeleton)["standing_height"]
    engine = legwork.accent.make_model(legwork.accent.load_database(str(db_path)), settings)
    assert json.loads(report.read_text())["ik_skeleton"] == "database skeleton at the user's height"
    model = ik.make_model(engine.skeleton())
    out, status = drive(ik, model, core.tracker_frames_from_motion(truth))
    assert all(s == core.UpdateStatus.Ok for s in status)
    m = legwork.eval.evaluate_trial(legwork.eval.role_track(out), legwork.eval.role_track(truth))
    assert m.mpjpe_cm == pytest.approx(json.loads(report.read_text())["ik_error"]["full_body_cm"], rel=1e-12)
    head, true_head = model.skeleton().roles["head"], truth.skeleton.roles["head"]
    assert np.abs(out.positions()[:, head] - truth.positions()[:, true_head]).max() < 1e-6  # the head is placed exactly


def test_rejected_frames_leave_state_and_pose_untouched():
    walk = legwork.io.read_bvh(str(TRIAL), drop_first=True)
    model = ik.make_model(walk.skeleton)
    state, pose = ik.State(model), core.Pose(model.skeleton())
    frames = core.tracker_frames_from_motion(walk)
    assert ik.update(model, frames[0], state, pose) == core.UpdateStatus.Ok
    before = pose.rotations
    assert ik.update(model, frames[0], state, pose) == core.UpdateStatus.Rejected
    bad = frames[1]
    bad.time = float("nan")
    assert ik.update(model, bad, state, pose) == core.UpdateStatus.Rejected
    assert np.array_equal(pose.rotations, before)
    with pytest.raises(ValueError, match=r"out: a Pose of the model's skeleton \(31 joints\)"):
        ik.update(model, frames[1], state, core.Pose(core.Skeleton(["a"], [-1], np.zeros((1, 3)))))


def test_wip_walks_while_the_feet_step_and_stands_when_they_stop():
    walk = core.resample(legwork.io.read_bvh(str(SOURCE / "data/cmu/bvh/walking/16_15.bvh"), drop_first=True), 90.0)
    settings = wip.Settings()
    settings.signal.rate = 90.0
    model = wip.make_model(walk.skeleton, settings)
    frames = core.tracker_frames_from_motion(walk)
    for f in frames:  # walking in place: the ankles keep their heights, not their travel
        for d in (core.Device.LeftFoot, core.Device.RightFoot):
            p, r, _ = f.get(d)
            f.set(d, np.array([0.1 if d == core.Device.LeftFoot else -0.1, p[1], 0.0]), r)
    info = wip.Info()
    state, pose = wip.State(model), core.Pose(model.skeleton())
    floor = min(f.get(core.Device.LeftFoot)[0][1] for f in frames)
    wip.set_floor(state, floor, floor)
    walking = 0
    phases = set()
    for f in frames:
        assert wip.update(model, f, state, pose, info) in (core.UpdateStatus.Ok, core.UpdateStatus.Degraded)
        walking += info.walking
        fields = info.fields()
        assert fields["walking"] == float(info.walking) and fields["distance"] == pytest.approx(info.distance)
        phases.add(fields["phase_left"])
    # the gait machine's four states, under the names the server and the C API use
    assert phases == {"double_support", "initial_swing", "mid_swing", "terminal_swing"}
    assert state.calibrated and walking > len(frames) // 3
    assert info.distance > 1.0  # metres walked by the avatar
    still = frames[-1]
    distance = []
    for i in range(1, 361):  # four seconds of standing still
        f = core.TrackerFrame(still.time + i / 90.0)
        for d in (core.Device.Head, core.Device.LeftFoot, core.Device.RightFoot):
            p, r, _ = still.get(d)
            f.set(d, p, r)
        wip.update(model, f, state, pose, info)
        distance.append(info.distance)
    # It stops (after the document's stop time of double support) and then stays put.
    # The speed decays exponentially (speed_tau): below 1 mm/s, under a millimetre in the last second.
    assert not info.walking and info.speed < 1e-3
    assert distance[-1] - distance[-90] < 1e-3


def test_wip_learned_mapping_swings_the_feet_and_needs_its_table():
    walk = legwork.io.read_bvh(str(SOURCE / "data/cmu/bvh/walking/05_01.bvh"), drop_first=True)
    settings = wip.Settings()
    settings.mapping.depth = wip.DepthMapping.Learned
    with pytest.raises(legwork.Error, match="learned depth mapping needs a learned table"):
        wip.make_model(walk.skeleton, settings)
    with pytest.raises(legwork.Error, match=r"CMakeLists.txt:1: not a learned walking-in-place mapping"):
        wip.read_learned_mapping(str(SOURCE / "CMakeLists.txt"))
    table = wip.read_learned_mapping(str(SOURCE / "data/wip/learned_mapping.txt"))
    assert table.samples > 5000 and table.lookup(0, 0, 1, 0.05) > 0 > table.lookup(0, 0, 0, 0.05)
    model = wip.make_model(walk.skeleton, settings, table)
    state, pose, info = wip.State(model), core.Pose(model.skeleton()), wip.Info()
    depths, turn = [], []
    for f in core.tracker_frames_from_motion(walk, 30.0):
        wip.update(model, f, state, pose, info)
        depths.append(info.z)
        turn.append(info.turn_rate)
    z = np.array(depths)
    assert np.all(np.isfinite(z))
    # 05_01 turns round: the head's smoothed turn rate rises, and the table's gain shortens steps there.
    assert max(turn) > 0.5 and table.turn_gain(max(turn)) < table.turn_gain(0.0)
    for foot in (0, 1):  # each foot goes in front of and behind the pelvis
        assert z[:, foot].min() < -0.1 * model.leg_length < 0.1 * model.leg_length < z[:, foot].max()


def test_wip_speed_gain_zero_takes_the_detectors_calibrated_gain():
    s = wip.Settings()
    assert s.gait.detector == wip.StepDetector.Adaptive and s.mapping.speed_gain == 0
    adaptive = wip.step_speed_gain(s)
    s.gait.detector = wip.StepDetector.Document
    document = wip.step_speed_gain(s)
    assert adaptive > document > 0  # the adaptive detector's phases average less of the swing's speed
    s.mapping.speed_gain = 3.0
    assert wip.step_speed_gain(s) == 3.0


def test_wip_min_swing_time_is_a_setting_checked_by_make_model():
    s = wip.Settings()
    assert s.gait.min_swing_time == pytest.approx(0.1)  # the default `wip tune` chose (docs/wip.md)
    walk = legwork.io.read_bvh(str(SOURCE / "data/cmu/bvh/walking/05_01.bvh"), drop_first=True)
    s.gait.min_swing_time = 0.0  # 0 = off
    wip.make_model(walk.skeleton, s)
    s.gait.min_swing_time = -0.1
    with pytest.raises(Exception, match=r"gait\.min_swing_time -0\.100000 must be finite and >= 0"):
        wip.make_model(walk.skeleton, s)


def test_wip_step_detector_is_a_setting_and_the_adaptive_one_lifts_earlier():
    walk = legwork.io.read_bvh(str(SOURCE / "data/cmu/bvh/walking/05_01.bvh"), drop_first=True)
    assert wip.Settings().gait.detector in (wip.StepDetector.Document, wip.StepDetector.Adaptive)
    first_swing = {}
    for detector in (wip.StepDetector.Document, wip.StepDetector.Adaptive):
        settings = wip.Settings()
        settings.gait.detector = detector
        model = wip.make_model(walk.skeleton, settings)
        state, pose, info = wip.State(model), core.Pose(model.skeleton()), wip.Info()
        for i, f in enumerate(core.tracker_frames_from_motion(walk, 30.0)):
            wip.update(model, f, state, pose, info)
            if info.phase[0] != wip.GaitPhase.DoubleSupport:
                first_swing[detector] = i
                break
    assert wip.StepDetector.Document in first_swing and wip.StepDetector.Adaptive in first_swing
    assert first_swing[wip.StepDetector.Adaptive] < first_swing[wip.StepDetector.Document]


def test_walker_walks_forward_and_turns_to_the_head():
    walk = walkcycle.load_walk(str(SOURCE / "data/walks/normal.json"))
    cycle = walkcycle.build_cycle(walk.skeleton, walk.keys)
    settings = walkcycle.Settings()
    model = walkcycle.make_model(cycle, settings)
    state, pose, info = walkcycle.State(model), core.Pose(model.skeleton()), walkcycle.Info()
    yaw90 = np.array([np.cos(np.pi / 4), 0.0, np.sin(np.pi / 4), 0.0])  # 90 degrees about +y
    headings = []
    for i in range(300):  # 5 s at 60 Hz: straight for 2 s, then the head turns left
        f = core.TrackerFrame(i / 60.0)
        f.set(core.Device.Head, np.array([0.0, 1.7, 0.0]), np.array([1.0, 0, 0, 0]) if i < 120 else yaw90)
        assert walkcycle.update(model, f, state, pose, info) == core.UpdateStatus.Ok
        headings.append(info.heading)
        if i == 119:
            root_at_2s = np.array(pose.translations[0])
            assert abs(info.heading) < 1e-9 and root_at_2s[2] > 1.0  # walked forward (+z)
    assert info.heading == pytest.approx(np.pi / 2, abs=1e-6)
    steps = np.abs(np.diff(headings))
    assert steps.max() <= settings.max_turn_per_step + 1e-9
    with pytest.raises(legwork.Error, match="missing.json"):
        walkcycle.load_walk(str(SOURCE / "data/walks/missing.json"))


def test_walker_root_is_smooth_by_default_and_pivot_on_request():
    walk = walkcycle.load_walk(str(SOURCE / "data/walks/normal.json"))
    cycle = walkcycle.build_cycle(walk.skeleton, walk.keys)
    assert walkcycle.Settings().root == walkcycle.RootMotion.Smooth
    spread = {}
    for root in (walkcycle.RootMotion.Smooth, walkcycle.RootMotion.Pivot):
        settings = walkcycle.Settings()
        settings.root = root
        model = walkcycle.make_model(cycle, settings)
        state, pose, info = walkcycle.State(model), core.Pose(model.skeleton()), walkcycle.Info()
        roots = []
        for i in range(180):  # 3 s at 60 Hz, straight
            f = core.TrackerFrame(i / 60.0)
            f.set(core.Device.Head, np.array([0.0, 1.7, 0.0]), np.array([1.0, 0, 0, 0]))
            assert walkcycle.update(model, f, state, pose, info) == core.UpdateStatus.Ok
            roots.append(np.array(pose.translations[0])[[0, 2]])
        speed = np.linalg.norm(np.diff(np.array(roots[60:]), axis=0), axis=1) * 60.0
        spread[root] = (speed.max() - speed.min()) / speed.mean()
        assert not info.reach_limited
    assert spread[walkcycle.RootMotion.Smooth] < 0.4 < spread[walkcycle.RootMotion.Pivot]  # within +-20 % / lunging
    bad = walkcycle.Settings()
    bad.soft_reach = 1.5
    with pytest.raises(legwork.Error, match=r"soft_reach must be in \(0, 1\]"):
        walkcycle.make_model(cycle, bad)


def test_step_f1_equals_cli_wip_eval(cli, tmp_path):
    """Walking in place driven frame by frame from Python, scored by legwork.eval, against `legwork wip eval`:
    the strict +-200 / +-100 ms scores (the headline), the noisy run's and the lenient overlap score."""
    folder = SOURCE / "data/cmu/bvh/walking"
    cli("wip", "eval", "--data", folder, "--clip", folder / "07_01.bvh", "--out", tmp_path)
    report = json.loads((tmp_path / "report.json").read_text())
    assert report["per_trial"]
    for index, trial in enumerate(report["per_trial"]):
        motion = legwork.io.read_bvh(str(folder / (trial["trial"] + ".bvh")), drop_first=True)
        settings = wip.Settings()  # the CLI's defaults: 30 Hz trackers
        model = wip.make_model(motion.skeleton, settings)
        state, pose = wip.State(model), core.Pose(model.skeleton())
        infos = []
        frames = core.tracker_frames_from_motion(motion, settings.signal.rate)
        for frame in frames:
            info = wip.Info()
            if wip.update(model, frame, state, pose, info) != core.UpdateStatus.Rejected:
                infos.append(info)
        t_begin, t_end = 0.5, motion.duration - 0.1  # the evaluation's settling time and end
        score = legwork.eval.score_steps(legwork.eval.detected_swings(infos), wip.foot_swings(motion), t_begin, t_end)
        cli_steps = trial["lenient_overlap"]  # overlap score, the secondary figure
        assert (score.true_steps, score.detected, score.matched) == (
            cli_steps["true_steps"], cli_steps["detected"], cli_steps["matched"]), trial["trial"]
        assert score.f1 == pytest.approx(cli_steps["f1"], rel=1e-12)
        assert score.off_latency_ms == pytest.approx(cli_steps["foot_off_latency_ms"], rel=1e-12)

        truth = wip.foot_swings(motion, end_swings=True)
        detected = legwork.eval.detected_swings(infos)
        # The whole clip in one call gives the same per-frame figures, with or without solving the legs.
        run = wip.run(model, frames, calibrate=False, keep_poses=False)
        assert run.motion is None and len(run) == len(infos)
        assert [(e.foot, e.off, e.strike) for e in legwork.eval.detected_swings(run.frames)] == [
            (e.foot, e.off, e.strike) for e in detected]
        noisy = wip.run(model, wip.add_tracker_noise(frames, seed=1 * 1000003 + index), calibrate=False, keep_poses=False)
        for key, found, tolerance in (("strict_200ms", detected, 0.2), ("strict_100ms", detected, 0.1),
                                      ("strict_200ms_noisy", legwork.eval.detected_swings(noisy.frames), 0.2)):
            strict, expected = legwork.eval.match_foot_offs(found, truth, t_begin, t_end, tolerance), trial[key]
            assert (strict.true_steps, strict.detected, strict.matched) == (
                expected["true_steps"], expected["detected"], expected["matched"]), (trial["trial"], key)
            assert strict.tolerance_ms == expected["tolerance_ms"]
            assert strict.f1 == pytest.approx(expected["f1"], rel=1e-12)
            assert strict.median_ms == pytest.approx(expected["latency_median_ms"], rel=1e-12)
            assert strict.p90_ms == pytest.approx(expected["latency_p90_ms"], rel=1e-12)
            assert len(strict.latencies_ms) == strict.matched
        pooled = legwork.eval.combine([legwork.eval.match_foot_offs(detected, truth, t_begin, t_end)] * 2)
        assert (pooled.true_steps, pooled.matched) == (2 * trial["strict_200ms"]["true_steps"],
                                                       2 * trial["strict_200ms"]["matched"])
        assert pooled.f1 == pytest.approx(trial["strict_200ms"]["f1"], rel=1e-12)


def test_wip_run_calibrates_from_standing_and_solves_the_legs_only_when_asked():
    walk = core.resample(legwork.io.read_bvh(str(SOURCE / "data/cmu/bvh/walking/16_15.bvh"), drop_first=True), 30.0)
    model = wip.make_model(walk.skeleton)
    frames = core.tracker_frames_from_motion(walk)
    # Real walking has no standing start: the calibration refuses it, naming the ankle.
    with pytest.raises(legwork.Error, match=r"not standing still during the first 3\.0 s \((left|right) ankle height varies"):
        wip.run(model, frames)
    calibration = wip.calibrate_floor(frames)
    assert not calibration.ok and "not standing still" in calibration.message
    # Two seconds of standing (the first frame held) before the walk: calibrated on its ankle heights.
    first = frames[0]
    standing = []
    for i in range(60):
        f = core.TrackerFrame(first.time - (60 - i) / 30.0)
        for d in (core.Device.Head, core.Device.LeftHand, core.Device.RightHand, core.Device.LeftFoot, core.Device.RightFoot):
            f.set(d, *first.get(d)[:2])
        standing.append(f)
    run = wip.run(model, standing + frames, calibration_seconds=1.5)
    assert run.calibration.ok and run.calibration.spread == pytest.approx((0.0, 0.0), abs=1e-6)
    assert run.calibration.floor == pytest.approx((first.get(core.Device.LeftFoot)[0][1],
                                                   first.get(core.Device.RightFoot)[0][1]), rel=1e-12)
    assert run.motion.frame_count == len(run) == len(standing) + len(frames)
    # Driving the same avatar frame by frame gives the same legs; without a pose, the same gait and targets.
    state, pose, info = wip.State(model), core.Pose(model.skeleton()), wip.Info()
    wip.set_floor(state, *run.calibration.floor)
    bare, bare_info = wip.State(model), wip.Info()
    wip.set_floor(bare, *run.calibration.floor)
    for i, f in enumerate(standing + frames):
        wip.update(model, f, state, pose, info)
        assert wip.update(model, f, bare, None, bare_info) != core.UpdateStatus.Rejected
        assert bare_info.fields() == info.fields() == run.frames[i].fields()
        assert (bare_info.z, bare_info.h) == (info.z, info.h)
    assert np.array_equal(pose.rotations, run.motion.rotations[-1])
    strict = legwork.eval.match_foot_offs(legwork.eval.detected_swings(run.frames), wip.foot_swings(walk, end_swings=True),
                                          0.5, walk.duration - 0.1)
    assert strict.true_steps == strict.matched == strict.detected == 6  # every step after the settling time, in time
    # Other runtimes need their pose; bad arguments are named.
    with pytest.raises(ValueError, match=r"out: a Pose of the model's skeleton \(31 joints\) expected, got None"):
        ik.update(ik.make_model(walk.skeleton), frames[0], ik.State(ik.make_model(walk.skeleton)), None)
    with pytest.raises(ValueError, match=r"^seconds: expected a positive number of seconds, got 0"):
        wip.calibrate_floor(frames, seconds=0)
    with pytest.raises(ValueError, match=r"calibration_seconds: expected a positive number of seconds, got -1"):
        wip.run(model, frames, calibration_seconds=-1)
    with pytest.raises(ValueError, match=r"drop_rate: expected a fraction in \[0, 1\], got 2"):
        wip.add_tracker_noise(frames, drop_rate=2)
    with pytest.raises(ValueError, match=r"tolerance: expected seconds in \(0, 10\)"):
        legwork.eval.match_foot_offs([], [], 0, 1, tolerance=float("nan"))
    with pytest.raises(ValueError, match=r"t_begin, t_end: expected finite seconds with t_begin <= t_end"):
        legwork.eval.match_foot_offs([], [], 2, 1)
    with pytest.raises(ValueError, match=r"off, strike: expected finite seconds with strike >= off"):
        wip.SwingEvent(0, 1.0, 0.5)


def test_false_steps_are_counted_on_the_still_segments_of_a_walk():
    """A real walk after two seconds of standing: the standing is a still segment (until the walk's first
    true foot-off), the detector takes no step in it, and a detection there that matches no true step is a
    false one, as `legwork wip eval` counts them; a detection matched to the first true step is not."""
    walk = legwork.io.read_bvh(str(SOURCE / "data/cmu/bvh/walking/16_15.bvh"), drop_first=True)
    n = int(2 * walk.fps)
    standing = core.Motion(walk.skeleton, walk.fps, np.ascontiguousarray(np.repeat(walk.rotations[:1], n, 0)),
                           np.ascontiguousarray(np.repeat(np.array(walk.translations)[:1], n, 0)))
    motion = core.concatenate(standing, walk)
    run = wip.run(wip.make_model(motion.skeleton), core.tracker_frames_from_motion(motion, 30.0), calibrate=False,
                  keep_poses=False)
    detected = legwork.eval.detected_swings(run.frames)
    first = min(wip.foot_swings(motion, end_swings=True), key=lambda e: e.off)
    first_off = first.off
    t_end = motion.duration - 0.1
    still = legwork.eval.still_segments(motion, detected, 0.5, t_end)
    assert len(still) == 1 and still[0].begin == pytest.approx(0.5) and still[0].false_steps == 0
    assert 2.0 <= still[0].end <= first_off + 1e-9  # the standing, up to the first true foot-off
    fake = wip.SwingEvent(0, 1.0, 1.3)  # a step taken while standing
    assert [g.false_steps for g in legwork.eval.still_segments(motion, detected + [fake], 0.5, t_end)] == [1]
    assert legwork.eval.still_segments(motion, [fake], 0.5, 0.9) == []  # shorter than min_duration
    early = wip.SwingEvent(first.foot, first_off - 0.05, first_off + 0.3)  # the first step, detected 50 ms early
    assert [g.false_steps for g in legwork.eval.still_segments(motion, [early], 0.5, t_end)] == [0]
    with pytest.raises(ValueError, match=r"min_duration: expected a positive number of seconds, got -1"):
        legwork.eval.still_segments(motion, detected, 0.5, t_end, min_duration=-1)


def test_another_detectors_steps_are_scored_the_fields_way():
    """A researcher's own detections, made by hand, against the true foot-offs of a real walk."""
    walk = legwork.io.read_bvh(str(SOURCE / "data/cmu/bvh/walking/16_15.bvh"), drop_first=True)
    truth = wip.foot_swings(walk, end_swings=True)
    # The clip ends mid-swing: that foot-off counts for scoring, its strike is the clip's end.
    assert [e.cut for e in truth] == [False] * len(wip.foot_swings(walk)) + [True]
    assert truth[-1].strike == pytest.approx(walk.duration, abs=1 / walk.fps)
    t_end = walk.duration
    late = [wip.SwingEvent(e.foot, e.off + 0.15, e.strike + 0.15) for e in truth]  # every step 150 ms late
    within = legwork.eval.match_foot_offs(late, truth, 0, t_end)
    assert within.f1 == 1.0 and within.median_ms == pytest.approx(150.0)
    outside = legwork.eval.match_foot_offs(late, truth, 0, t_end, tolerance=0.1)
    assert outside.matched == 0 and outside.f1 == 0.0 and np.isnan(outside.median_ms)
    assert len(legwork.eval.unmatched_detections(late, truth, tolerance=0.1)) == len(late)
    wrong_foot = [wip.SwingEvent(1 - e.foot, e.off, e.strike) for e in truth]  # a foot-off only matches its own foot
    assert legwork.eval.match_foot_offs(wrong_foot, truth, 0, t_end).matched == 0
    none = legwork.eval.match_foot_offs([], truth, 0, t_end)
    assert none.recall == 0.0 and np.isnan(none.precision)
    with pytest.raises(ValueError, match=r"scores: expected one tolerance, got 200 and 100 ms"):
        legwork.eval.combine([within, outside])


def test_combined_legs_come_from_wip_and_the_upper_body_from_ik():
    walk = legwork.io.read_bvh(str(TRIAL), drop_first=True)
    frames = core.tracker_frames_from_motion(walk, 30.0)
    settings = legwork.combined.Settings()
    settings.wip.signal.rate = 30.0
    model = legwork.combined.make_model(walk.skeleton, settings)
    assert not model.accentuated
    out, status = drive(legwork.combined, model, frames)
    ik_out, _ = drive(ik, ik.make_model(walk.skeleton), frames)
    legs = set(model.leg_joints)
    upper = [j for j in range(walk.skeleton.joint_count) if j not in legs]
    assert np.array_equal(out.rotations[:, upper], ik_out.rotations[:, upper])  # the upper body is the IK avatar's
    assert not np.allclose(out.rotations[:, sorted(legs)], ik_out.rotations[:, sorted(legs)])  # the legs are not
    assert status.count(core.UpdateStatus.Ok) > len(frames) // 2


def test_combined_legs_with_the_learned_mapping():
    walk = legwork.io.read_bvh(str(TRIAL), drop_first=True)
    frames = core.tracker_frames_from_motion(walk, 30.0)
    settings = legwork.combined.Settings()
    settings.wip.signal.rate = 30.0
    settings.wip.mapping.depth = wip.DepthMapping.Learned
    with pytest.raises(legwork.Error, match="learned depth mapping needs a learned table"):
        legwork.combined.make_model(walk.skeleton, settings)
    table = wip.read_learned_mapping(str(SOURCE / "data/wip/learned_mapping.txt"))
    model = legwork.combined.make_model(walk.skeleton, settings, learned=table)
    out, _ = drive(legwork.combined, model, frames)
    plain = legwork.combined.Settings()
    plain.wip.signal.rate = 30.0  # the same but for the mapping
    document, _ = drive(legwork.combined, legwork.combined.make_model(walk.skeleton, plain), frames)
    legs = sorted(model.leg_joints)
    assert np.isfinite(out.rotations).all()
    assert not np.allclose(out.rotations[:, legs], document.rotations[:, legs])  # the learned table moves the legs otherwise


def test_combined_with_a_database(db):
    settings = legwork.combined.Settings()
    settings.accent.user_height = 1.7
    model = legwork.combined.make_model(db, settings)
    assert model.accentuated
    state = legwork.combined.State(model)
    assert state.legs_weight == 0.0


def test_walker_walks_the_ground_it_is_given():
    walk = walkcycle.load_walk(str(SOURCE / "data/walks/normal.json"))
    cycle = walkcycle.build_cycle(walk.skeleton, walk.keys)
    settings = walkcycle.Settings()
    assert settings.ground == "flat" and settings.turn_on_ball
    settings.set_ground('{"slope": {"origin": [0, 0.5], "direction": [0, 1], "grade": 0.1}}')
    assert settings.ground == "slope 10.0 %"
    model = walkcycle.make_model(cycle, settings)
    state, pose, info = walkcycle.State(model), core.Pose(model.skeleton()), walkcycle.Info()
    heights = []
    for i in range(150):  # 5 s at 30 Hz, straight up the slope
        f = core.TrackerFrame(i / 30.0)
        f.set(core.Device.Head, np.array([0.0, 1.7, 0.0]), np.array([1.0, 0, 0, 0]))
        walkcycle.update(model, f, state, pose, info)
        root = np.array(pose.translations[0])
        heights.append(root[1] - 0.1 * max(0.0, root[2] - 0.5))  # above the ground
    assert np.array(pose.translations[0])[2] > 4.0
    assert abs(heights[-1] - heights[0]) < 0.1 * 0.36 + 0.01  # rides the ground (the lower foot: up to half a stride's rise below the mean)
    assert info.ground_rise > 0.3
    with pytest.raises(legwork.Error, match="Settings.set_ground: slope: grade"):
        settings.set_ground('{"slope": {"origin": [0, 0.5], "direction": [0, 1], "grade": 0.5}}')


def test_walker_climbs_stairs():
    # The shipped stairs.json's flight (5 x 0.15 m from z = 1.5 m), at the stairs cadence.
    walk = walkcycle.load_walk(str(SOURCE / "data/walks/normal.json"))
    cycle = walkcycle.build_cycle(walk.skeleton, walk.keys)
    settings = walkcycle.Settings()
    assert settings.stairs_cadence == 0.8
    settings.set_ground('{"stairs": {"origin": [0, 1.5], "direction": [0, 1], "rise": 0.15, "run": 0.36, "count": 5}}')
    assert settings.ground == "stairs up, 5 steps of 0.150 m rise, 0.360 m run"
    model = walkcycle.make_model(cycle, settings)
    state, pose, info = walkcycle.State(model), core.Pose(model.skeleton()), walkcycle.Info()
    first, cadences = None, []
    for i in range(150):  # 5 s at 30 Hz, straight up the flight
        f = core.TrackerFrame(i / 30.0)
        f.set(core.Device.Head, np.array([0.0, 1.7, 0.0]), np.array([1.0, 0, 0, 0]))
        walkcycle.update(model, f, state, pose, info)
        root = np.array(pose.translations[0])
        first = root[1] if first is None else first
        cadences.append(info.cadence)
    assert root[2] > 1.5 + 5 * 0.36  # past the last riser
    assert abs(root[1] - 0.75 - first) < 0.03  # as high above the landing as above the floor
    assert min(cadences) < 0.85  # slower on the flight
    settings.stairs_cadence = 0.0
    with pytest.raises(legwork.Error, match="stairs_cadence must be in"):
        walkcycle.make_model(cycle, settings)
