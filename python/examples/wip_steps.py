"""Scores the walking-in-place step detector the field's way (foot-offs matched one to one within
+-200 ms) on walking BVH trials, from Python: what `legwork wip eval` reports as strict_200ms, and its
false steps per minute on the trials' still segments.

    PYTHONPATH=build/python python3 python/examples/wip_steps.py --data data/cmu/bvh/walking [--noise]

Each trial's ankles (and head) become 30 Hz tracker frames, one avatar runs over them without
solving its legs (keep_poses=False: only the gait is scored), and its swings are matched against the
trial's true swings. --noise adds `legwork wip eval`'s Kinect-like corruption (1.5 cm jitter, 2 %
drops; its seeds). Another detector's foot-offs can be scored the same way: make
legwork.wip.SwingEvent(foot, off, strike) for each and pass them to legwork.eval.match_foot_offs."""
import argparse
import pathlib

import legwork
from legwork import core, wip

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--data", required=True, help="folder of walking .bvh trials")
parser.add_argument("--noise", action="store_true", help="Kinect-like noise on the feet, as wip eval's noisy run")
args = parser.parse_args()

trials = sorted(pathlib.Path(args.data).glob("*.bvh"))
if not trials:
    raise SystemExit(f"wip_steps: no .bvh trials in {args.data}")
scores, still_minutes, false_steps = [], 0.0, 0
for index, path in enumerate(trials):
    motion = legwork.io.read_bvh(str(path), drop_first=True)
    settings = wip.Settings()                                    # 30 Hz trackers, the adaptive detector
    model = wip.make_model(motion.skeleton, settings)
    frames = core.tracker_frames_from_motion(motion, settings.signal.rate)
    if args.noise:
        frames = wip.add_tracker_noise(frames, seed=1 * 1000003 + index)
    run = wip.run(model, frames, calibrate=False, keep_poses=False)  # walking: a rolling floor, no standing start
    detected = legwork.eval.detected_swings(run.frames)
    truth = wip.foot_swings(motion, end_swings=True)             # a swing the clip's end cuts was taken too
    score = legwork.eval.match_foot_offs(detected, truth, t_begin=0.5, t_end=motion.duration - 0.1)
    scores.append(score)
    for segment in legwork.eval.still_segments(motion, detected, t_begin=0.5, t_end=motion.duration - 0.1):
        still_minutes += (segment.end - segment.begin) / 60                 # both feet down for at least 1 s
        false_steps += segment.false_steps
    print(f"{path.stem}: {score.matched} of {score.true_steps} steps, F1 {score.f1:.3f}, "
          f"foot-off latency median {score.median_ms:.0f} ms")
pooled = legwork.eval.combine(scores)
print(f"pooled over {len(trials)} trials: precision {pooled.precision:.3f}, recall {pooled.recall:.3f}, "
      f"F1 {pooled.f1:.3f}, latency median {pooled.median_ms:.0f} ms, p90 {pooled.p90_ms:.0f} ms")
print(f"false steps: {false_steps / still_minutes:.2f} per minute over {still_minutes:.2f} min of still segments"
      if still_minutes > 0 else "false steps: n/a (no still segment of 1 s or more in these trials)")
