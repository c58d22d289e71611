#!/usr/bin/env bash
# Renderer demo: contact sheets, joint paths and videos of CMU clips.
# Env: LEGWORK (CLI binary), OUT (demo output dir), DATA (repo data/cmu).
set -euo pipefail
out="$OUT/render"
mkdir -p "$out"
walk="$DATA/bvh/walking/07_01.bvh"
run="$DATA/bvh/running/09_01.bvh"

"$LEGWORK" render "$walk" --drop-first --frames 0:240 --every 30 --out "$out/walk_sheet.png"
"$LEGWORK" render "$walk" --drop-first --frames 0:240 --every 30 --out "$out/walk_sheet.svg"
"$LEGWORK" render "$run" --drop-first --view three-quarter --out "$out/run_three_quarter.png"
"$LEGWORK" render "$walk" --drop-first --trace LeftFoot --out "$out/walk_left_foot_side.png"
"$LEGWORK" render "$walk" --drop-first --trace left_ankle --view top --footprints --out "$out/walk_left_ankle_top.png"
if command -v ffmpeg >/dev/null 2>&1; then
  "$LEGWORK" render "$walk" --drop-first --view three-quarter --trace LeftFoot --out "$out/walk_three_quarter.mp4"
  "$LEGWORK" render "$walk" --drop-first --view side --compare "$run" --width 960 --height 360 --out "$out/walk_vs_run.mp4"
fi

cat > "$out/README.txt" <<'TXT'
walk_sheet.png: CMU 07_01 walk, every 30th frame, front and side views (left side blue, right side orange; body turned to face +z)
walk_sheet.svg: the same contact sheet as SVG
run_three_quarter.png: CMU 09_01 run, six poses in the three-quarter view
walk_left_foot_side.png: left foot path over the whole walk (side view) with translucent figures at the marked frames
walk_left_ankle_top.png: the same path from above with rough footprints where the ankles rest (top view: forward to the right, the character's left up; left prints blue, right orange)
walk_three_quarter.mp4: the walk as a 30 fps video, three-quarter view, left foot path traced
walk_vs_run.mp4: walk (07_01) and run (09_01) side by side at the same scale
TXT
echo "render demo: $(ls "$out" | wc -l) files in $out"
