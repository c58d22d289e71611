#!/usr/bin/env bash
# Walk-cycle generator demo: the three shipped walks (normal, sneak, double
# bounce) along a curved path - BVH + GLB, key-pose sheets, arcs, videos,
# top views with footprints, reports - and key poses extracted from a CMU walk.
# Env: LEGWORK (CLI binary), OUT (demo output dir), DATA (repo data/cmu).
set -euo pipefail
out="$OUT/walkcycle"
mkdir -p "$out"
walks="$(cd "$DATA/.." && pwd)/walks"
path="$walks/paths/quarter-turn.json"
have_ffmpeg=0
command -v ffmpeg >/dev/null 2>&1 && have_ffmpeg=1

for w in normal sneak double-bounce; do
  echo "walkcycle demo: $w" >&2
  video=()
  if [ "$have_ffmpeg" = 1 ]; then
    video=(--video "$out/${w}_path.mp4" --slide-video "$out/${w}_slide.mp4")
  fi
  "$LEGWORK" walkcycle --keys "$walks/$w.json" --path "$path" \
    --out "$out/${w}_path.bvh" --cycle-out "$out/${w}_cycle.glb" \
    --sheet "$out/${w}_keys.png" --arc LeftHand,LeftToeBase --arc-out "$out/${w}" \
    --top "$out/${w}_top.png" --report "$out/${w}_report.json" "${video[@]}"
  "$LEGWORK" walkcycle --keys "$walks/$w.json" --path "$path" --out "$out/${w}_path.glb" >/dev/null
  "$LEGWORK" walkcycle --keys "$walks/$w.json" --sheet "$out/${w}_keys.svg" --active down >/dev/null
  "$LEGWORK" walkcycle --keys "$walks/$w.json" --straight 8 --report "$out/${w}_straight_report.json" >/dev/null
done

# Root motion before/after (issue 14, item 1): the normal walk on the same
# path with document 001's pivoting root (lunges and stalls) and the smooth
# root with the feet held by leg IK (the default, as above).
pivot_video=()
[ "$have_ffmpeg" = 1 ] && pivot_video=(--video "$out/normal_path_pivot_root.mp4")
"$LEGWORK" walkcycle --keys "$walks/normal.json" --path "$path" --root pivot --top "$out/normal_pivot_root_top.png" \
  --report "$out/normal_pivot_root_report.json" "${pivot_video[@]}" >/dev/null

# Turning on the ball (issue 14, item 2): the same turn with the stance foot
# turning with the body (--stance-turn twist) against the default; compare the
# stance_heel/ball_slip and stance_twist figures of the two reports.
"$LEGWORK" walkcycle --keys "$walks/normal.json" --path "$path" --stance-turn twist \
  --report "$out/normal_stance_twist_report.json" >/dev/null

# Uneven ground (issue 14, item 3): the three walks over a hill, up a ramp and
# up a flight of stairs (height field, slope and stairs in the path files; the
# feet put on the ground by the legs' IK). The videos draw the ground under
# the walk (treads and risers, the ramp, the hill) - the normal walk in three
# quarter view and from the side, with a still of each from the side.
for w in normal sneak double-bounce; do
  for g in hill ramp stairs; do
    ground_video=()
    if [ "$have_ffmpeg" = 1 ] && [ "$w" = normal ]; then
      ground_video=(--video "$out/${w}_${g}.mp4")
      "$LEGWORK" walkcycle --keys "$walks/$w.json" --path "$walks/paths/$g.json" --video "$out/${w}_${g}_side.mp4" \
        --video-view side >/dev/null
      ffmpeg -loglevel error -y -ss 3.2 -i "$out/${w}_${g}_side.mp4" -frames:v 1 "$out/${w}_${g}_side.png"
    fi
    "$LEGWORK" walkcycle --keys "$walks/$w.json" --path "$walks/paths/$g.json" --out "$out/${w}_${g}.bvh" \
      --report "$out/${w}_${g}_report.json" "${ground_video[@]}" >/dev/null
  done
done

# Stairs before/after (issue 14): the walk's own stride (two treads a step,
# crouching; --stairs-stride keep) against the stride fitted to the treads
# (the default, one tread per step), from the side.
if [ "$have_ffmpeg" = 1 ]; then
  "$LEGWORK" walkcycle --keys "$walks/normal.json" --path "$walks/paths/stairs.json" --stairs-stride keep \
    --video "$out/normal_stairs_kept_stride_side.mp4" --video-view side >/dev/null
  ffmpeg -loglevel error -y -ss 3.2 -i "$out/normal_stairs_kept_stride_side.mp4" -frames:v 1 "$out/normal_stairs_kept_stride_side.png"
fi
"$LEGWORK" walkcycle --keys "$walks/normal.json" --path "$walks/paths/stairs.json" --stairs-stride keep \
  --report "$out/normal_stairs_kept_stride_report.json" >/dev/null

# From mocap: key poses of a real walk, ready to stylise, and the walk they make.
"$LEGWORK" walkcycle extract "$DATA/bvh/walking/16_15.bvh" --out "$out/16_15_keys.json" \
  --sheet "$out/16_15_keys.png" --report "$out/16_15_extract.json"
"$LEGWORK" walkcycle --keys "$out/16_15_keys.json" --svg-path "M 0 0 C 0 2 2 2 2 4 S 0 6 0 8" \
  --out "$out/16_15_s_curve.bvh" --top "$out/16_15_s_curve_top.png" --report "$out/16_15_s_curve_report.json"

# A summary table of the figures every report carries.
if command -v python3 >/dev/null 2>&1; then
{
  echo "# Walk-cycle demo figures"
  echo
  echo "| walk | run | root | ground | steps | frames | stance slip max (mm) | feet below the ground (mm) | root speed min-max (m/s) | peak root acceleration (m/s^2) | loop seam (m) | net / total turning (deg) | max path deviation (m) | end distance (m) | floor lift (mm) | pelvis drop (mm) | pelvis vertical speed (m/s) / acceleration (m/s^2) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for f in "$out"/*_report.json; do
    python3 - "$f" <<'PY'
import json, os, sys
r = json.load(open(sys.argv[1]))
name = os.path.basename(sys.argv[1]).replace('_report.json', '')
print(f"| {r.get('walk')} | {name} | {r.get('root_motion')} | {r.get('ground')} | {r.get('steps')} | {r.get('frames')} | {r.get('stance_slip_mm_max'):.1e} | "
      f"{r.get('ground_penetration_mm_max', 0):.1f} | "
      f"{r.get('root_speed_min_mps', 0):.2f}-{r.get('root_speed_max_mps', 0):.2f} | {r.get('root_accel_max_mps2', 0):.1f} | "
      f"{r.get('loop_seam_error_m', 0):.2e} | {r.get('turning_deg', 0):.1f} / {r.get('turning_abs_deg', 0):.1f} | "
      f"{r.get('max_path_deviation_m', 0):.3f} | {r.get('end_distance_m', 0):.3f} | {r.get('floor_lift_mm_max', 0):.1f} | "
      f"{1e3 * r.get('pelvis_drop_max_m', 0):.0f} | {r.get('pelvis_vertical_speed_max_mps', 0):.2f} / {r.get('pelvis_vertical_accel_max_mps2', 0):.1f} |")
PY
  done
} > "$out/figures.md"
fi

{
  for w in normal sneak double-bounce; do
    echo "${w}_keys.png: '$w' walk: the five key poses of a step (contact, down, pass, up, mirrored contact), front and side"
    echo "${w}_keys.svg: '$w' key poses as SVG, the down pose active and the others x-ray"
    echo "${w}_arc_LeftHand.png: '$w' left wrist arc over the cycle (side and front), key frames marked C D P U"
    echo "${w}_arc_LeftHand.svg: the same arc as SVG"
    echo "${w}_arc_LeftToeBase.png: '$w' left toe arc over the cycle (the animators' figure-eight check)"
    echo "${w}_arc_LeftToeBase.svg: the same toe arc as SVG"
    echo "${w}_top.png: '$w' walking a 90-degree turn, from above: path (grey), root (green), footprints (left blue, right orange)"
    echo "${w}_path.mp4: '$w' walking the 90-degree turn without foot slip (smooth root, legs by IK), left toe traced"
    echo "${w}_slide.mp4: '$w' model sliding through its translucent key poses"
    echo "${w}_cycle.glb: '$w' in-place loop (glTF)"
    echo "${w}_path.glb: '$w' along the turn (glTF)"
    echo "${w}_report.json: '$w' along the turn: stance slip, loop seam, steps, frames, arcs, footsteps"
    echo "${w}_straight_report.json: '$w' 8 m straight: the same figures"
  done
  echo "normal_path_pivot_root.mp4: before/after: the normal walk on the same turn with document 001's pivoting root (the pelvis lunges and stalls); compare normal_path.mp4"
  echo "normal_pivot_root_top.png: its top view (root marks bunch and spread every step)"
  echo "normal_stance_twist_report.json: the turn with the stance foot turning with the body (--stance-turn twist): heel/ball slip and flat-foot twist against normal_report.json's"
  echo "normal_pivot_root_report.json: its report (root speed 0.15-3.08 m/s against the smooth root's even speed)"
  for w in normal sneak double-bounce; do
    echo "${w}_hill.bvh / ${w}_hill_report.json: '$w' over a hill (height field, 10 % grades): feet on the ground, slip and penetration in the report"
    echo "${w}_ramp.bvh / ${w}_ramp_report.json: '$w' up a 12 % ramp"
    echo "${w}_stairs.bvh / ${w}_stairs_report.json: '$w' up five stairs (0.15 m rise, 0.36 m run): one tread per step (the stride fitted to the treads), feet planted flat on them"
  done
  echo "normal_stairs_kept_stride_side.mp4 / .png / _report.json: before/after: the normal walk up the same stairs with its own stride (--stairs-stride keep: two treads a step, the pelvis drops ~18 cm to reach); compare normal_stairs_side.mp4 (one tread a step)"
  for g in hill ramp stairs; do
    echo "normal_${g}.mp4 / normal_${g}_side.mp4: the normal walk on the $g with the ground drawn (three-quarter view / from the side)"
    echo "normal_${g}_side.png: a still of it from the side (3.2 s in): the feet on the ground, the toe's path (green)"
  done
  echo "16_15_keys.png: key poses extracted from CMU 16_15 (a real walk), averaged over its steady steps"
  echo "16_15_keys.json: the extracted key-pose file, ready to stylise"
  echo "16_15_extract.json: detected steps (contact, down, pass, up) and the re-synthesis error"
  echo "16_15_s_curve_top.png: the extracted walk along an S-curve (SVG path), from above"
  echo "16_15_s_curve_report.json: its report"
  echo "figures.md: slip, seam, steps and turning of every walk above"
} > "$out/README.txt"
echo "walkcycle demo: $(ls "$out" | wc -l) files in $out"
