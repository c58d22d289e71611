#!/usr/bin/env bash
# Foundation demo: inspect a CMU walk, draw it (contact sheet, trajectory,
# video) and convert it to glTF.
set -euo pipefail
D="$OUT/foundation"
mkdir -p "$D"
WALK="$DATA/bvh/walking/07_01.bvh"
"$LEGWORK" info "$WALK" > "$D/07_01_info.txt"
"$LEGWORK" info "$WALK" --json > "$D/07_01_info.json"
head -6 "$D/07_01_info.txt"
"$LEGWORK" convert "$WALK" "$D/07_01.glb" --frames 1:
"$LEGWORK" convert "$WALK" "$D/07_01_mirrored_90hz.bvh" --frames 1: --mirror --rate 90
"$LEGWORK" render "$WALK" --frames 1:120 --out "$D/07_01_sheet.png"
"$LEGWORK" render "$WALK" --frames 1: --trace LeftFoot --view side --out "$D/07_01_leftfoot_arc.svg"
"$LEGWORK" render "$WALK" --frames 1: --view three-quarter --out "$D/07_01.mp4"
cat > "$D/README.txt" <<'TXT'
07_01_sheet.png: CMU 07_01 walk, frames 1-120 as a contact sheet (front and side views)
07_01_leftfoot_arc.svg: the left ankle's path over the walk, side view
07_01.mp4: the walk as a three-quarter-view video
07_01.glb: the walk as glTF 2.0 (open in Blender or three.js)
07_01_mirrored_90hz.bvh: mirrored (left/right swapped) and resampled to 90 Hz
07_01_info.json: joints, roles, frames, rate, duration and height
TXT
