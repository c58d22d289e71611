"""Accentuate a CMU trial from its head and hands, and plot the synthesized legs against ground truth.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/plot_accent.py \
        --data data/cmu --trial bvh/walking/07_02.bvh --out accent.png

Builds a database from --data without the trial (a held-out test, as `legwork eval` does), drives
one avatar with the trial's head and wrists, and draws: the ankle heights (truth vs synthesized),
the forward path of the feet, and the per-frame full-body error. Prints MPJPE / foot skating.
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import legwork  # noqa: E402
from legwork import accent, core  # noqa: E402

# --- inputs: the trial at the database rate, its head and wrists as the "headset" ---------------
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--data", default="data/cmu")
parser.add_argument("--trial", default="bvh/walking/07_02.bvh")
parser.add_argument("--out", default="accent.png")
args = parser.parse_args()

db = accent.build_database(args.data, exclude=[args.trial])
truth = core.resample(legwork.io.read_bvh(os.path.join(args.data, args.trial), drop_first=True), db.fps)
pos, rot = core.forward_kinematics(truth)
roles = truth.skeleton.roles
head, head_rot = np.ascontiguousarray(pos[:, roles["head"]]), np.ascontiguousarray(rot[:, roles["head"]])
left, right = np.ascontiguousarray(pos[:, roles["left_hand"]]), np.ascontiguousarray(pos[:, roles["right_hand"]])

# --- the whole clip through one avatar -----------------------------------------------------------
settings = accent.Settings()
settings.user_height = core.measure_body(truth.skeleton)["standing_height"]
run = accent.accentuate(db, head, head_rot, left, right, fps=db.fps, settings=settings)
out = run["motion"]
out_pos = out.positions()
out_roles = out.skeleton.roles

# --- metrics (legwork.eval on role joints, so different skeletons compare) -----------------------
m = legwork.eval.evaluate_trial(legwork.eval.role_track(out), legwork.eval.role_track(truth))
err = np.linalg.norm(legwork.eval.role_track(out).positions - legwork.eval.role_track(truth).positions, axis=2).mean(axis=1)
print(f"{args.trial}: {out.frame_count} frames, MPJPE {m.mpjpe_cm:.1f} cm (lower body {m.part_cm['lower_body']:.1f} cm), "
      f"foot skating {m.foot_skating_cm:.2f} cm/frame (truth {m.foot_skating_truth_cm:.2f})")

# --- plot ----------------------------------------------------------------------------------------
t = np.arange(out.frame_count) / db.fps
fig, ax = plt.subplots(3, 1, figsize=(9, 9), constrained_layout=True)
for side, colour in (("left", "tab:blue"), ("right", "tab:red")):
    j, k = roles[side + "_ankle"], out_roles[side + "_ankle"]
    ax[0].plot(t, pos[:, j, 1], color=colour, label=f"{side} ankle, truth")
    ax[0].plot(t, out_pos[:, k, 1], color=colour, linestyle="--", label=f"{side} ankle, accentuated")
    ax[1].plot(pos[:, j, 2], pos[:, j, 0], color=colour, label=f"{side} ankle, truth")
    ax[1].plot(out_pos[:, k, 2], out_pos[:, k, 0], color=colour, linestyle="--", label=f"{side} ankle, accentuated")
ax[0].set(xlabel="time (s)", ylabel="height (m)", title=f"{args.trial}: legs synthesized from head + hands")
ax[1].set(xlabel="z (m, forward)", ylabel="x (m, left)", title="feet from above")
ax[1].set_aspect("equal", adjustable="datalim")
ax[2].plot(t, err * 100, color="black")
ax[2].set(xlabel="time (s)", ylabel="error (cm)", title=f"mean per-joint error (MPJPE {m.mpjpe_cm:.1f} cm)")
for a in ax[:2]:
    a.legend(fontsize=7, ncol=2)
fig.savefig(args.out, dpi=90)
print(f"wrote {args.out}")
