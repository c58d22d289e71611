#!/usr/bin/env bash
# Walking-in-place demo: legs from synthetic in-place stepping and from a real
# CMU walk's ankle heights, the key-frame baseline, and the evaluation on real
# walking (all trials in ../shared/data/cmu/bvh/walking when present).
# Env: LEGWORK (CLI binary), OUT (demo output dir), DATA (repo data/cmu).
set -euo pipefail
out="$OUT/wip"
mkdir -p "$out"
walk="$DATA/bvh/walking/16_15.bvh"
avatar="$DATA/bvh/walking/07_01.bvh"

# 1. Synthetic in-place stepping (Kinect-like noise, drops, a pause), 30 Hz.
"$LEGWORK" wip --synthetic --duration 20 --asymmetry 0.2 --avatar "$avatar" \
  --out "$out/synthetic_legs.glb" --csv "$out/synthetic_frames.csv" \
  --plot "$out/synthetic_phases.png" --tracker-out "$out/synthetic_tracker.csv"
"$LEGWORK" wip --input "$out/synthetic_tracker.csv" --avatar "$avatar" --out "$out/synthetic_legs.bvh" >/dev/null

# 2. A real CMU walk: its ankles act as the tracker (their heights drive the legs, the head's yaw the heading).
"$LEGWORK" wip --input "$walk" --avatar "$avatar" --out "$out/cmu_16_15_legs.glb" \
  --csv "$out/cmu_16_15_frames.csv" --plot "$out/cmu_16_15_phases.png"
"$LEGWORK" wip --input "$walk" --avatar "$avatar" --out "$out/cmu_16_15_legs.bvh" >/dev/null
# The document's comparison condition: the same state machines trigger a canned walk cycle.
"$LEGWORK" wip --input "$walk" --avatar "$avatar" --baseline keyframe --clip "$avatar" --out "$out/cmu_16_15_keyframe.bvh" >/dev/null
if command -v ffmpeg >/dev/null 2>&1; then
  "$LEGWORK" render "$out/cmu_16_15_legs.bvh" --view side --compare "$out/cmu_16_15_keyframe.bvh" \
    --width 960 --height 360 --title "walking in place (left) vs key-frame baseline (right), CMU 16_15 ankles" \
    --out "$out/cmu_16_15_wip_vs_keyframe.mp4"
fi

# 3. Evaluation on real walking (all trials present; progress on stderr).
"$LEGWORK" wip eval --clip "$avatar" --out "$out/eval"
cp "$out/eval/report.md" "$out/eval_report.md"
cp "$out/eval/report.json" "$out/eval_report.json"
cp "$out/eval/summary.png" "$out/eval_summary.png"
cp "$out/eval/16_15.png" "$out/eval_16_15.png" 2>/dev/null || true

cat > "$out/README.txt" <<'TXT'
synthetic_phases.png: synthetic in-place stepping (noise, drops, a 3 s pause): ankle heights, velocities, detected gait phases, IK-target depths (with the key-frame baseline), speed, and a side-view strip of the avatar
synthetic_legs.glb: the avatar's legs driven by the synthetic stepping, walking forward (glTF 2.0)
synthetic_frames.csv: per-frame phases, heights, velocities, IK targets, speed and distance
synthetic_tracker.csv: the synthetic tracker input (time, left/right ankle x/y/z; empty cells = dropped)
synthetic_legs.bvh: the same legs computed again from the tracker CSV
cmu_16_15_phases.png: CMU 16_15's real ankle heights driving walking-in-place legs: phases, depths and side-view strip
cmu_16_15_legs.glb: walking-in-place legs from CMU 16_15's ankle heights (glTF 2.0)
cmu_16_15_frames.csv: per-frame state for CMU 16_15
cmu_16_15_legs.bvh: the same as BVH
cmu_16_15_keyframe.bvh: the key-frame baseline: a canned CMU walk cycle triggered by the same state machines
cmu_16_15_wip_vs_keyframe.mp4: side view, walking-in-place legs next to the key-frame baseline
eval_summary.png: step F1 (clean, noisy), depth correlation: method vs fixed thresholds vs key-frame baseline
eval_report.md: evaluation on the CMU walking trials: step precision/recall/F1, latency, depth correlation/RMS, baseline
eval_report.json: the same numbers, machine-readable
eval_16_15.png: one trial: detected vs true swings, generated vs real vs baseline foot depth
TXT
