#!/usr/bin/env bash
# The gallery as a browser sees it: a small gallery made here with the CLI
# (pictures, an SVG twin, a video, plain files, a nested folder) must load in
# headless Chromium with every picture and video and no broken link; after a
# linked file is removed, the checker must name it.
# Usage: tests/render/gallery_browser.sh LEGWORK_BINARY WORK_DIR   (exit 77 = skipped)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
bin="${1:?usage: gallery_browser.sh LEGWORK_BINARY WORK_DIR}"
work="${2:?usage: gallery_browser.sh LEGWORK_BINARY WORK_DIR}"
if [ ! -x /usr/bin/chromium ] || [ ! -d "$root/web/node_modules/playwright-core" ]; then
  echo "gallery browser test skipped: needs /usr/bin/chromium and web/node_modules (scripts/setup.sh)"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work/data" "$work/wip/eval"
export OUT="$work" LEGWORK_BIN="$bin"
lw="$root/scripts/demo-log.sh"
walk="$root/data/cmu/bvh/walking/07_01.bvh"
"$lw" render "$walk" --frames 1:60 --every 20 --out "$work/data/sheet.png" >/dev/null
"$lw" render "$walk" --frames 1:60 --every 20 --out "$work/data/sheet.svg" >/dev/null
"$lw" convert "$walk" "$work/data/walk.glb" --frames 1:30 >/dev/null
"$lw" render "$walk" --frames 1:30 --trace LeftFoot --out "$work/wip/eval/trial_a.png" >/dev/null
"$lw" render "$walk" --frames 31:60 --trace LeftFoot --out "$work/wip/eval/trial_b.png" >/dev/null
videos=0
if command -v ffmpeg >/dev/null 2>&1; then
  "$lw" render "$walk" --frames 1:30 --view three-quarter --out "$work/data/walk.mp4" >/dev/null
  videos=1
fi
printf 'A test gallery.\ndata/: Data - a walk\nwip/: Walking in place - per-trial plots below\n' > "$work/README.txt"
printf 'sheet.png: a contact sheet\nwalk.mp4: a video\nwalk.glb: glTF\n' > "$work/data/README.txt"
"$bin" gallery "$work" --title "gallery test" >/dev/null
out=$(node "$root/scripts/check-gallery.mjs" "$work/index.html")
echo "$out"
want="gallery check: 2 pages, 3 pictures, $videos videos ($videos posters)"
case "$out" in
  "$want"*) ;;
  *) echo "FAIL: expected '$want...'"; exit 1 ;;
esac
# The checker must fail on a broken link, naming it.
rm "$work/data/sheet.svg"
if out=$(node "$root/scripts/check-gallery.mjs" "$work/index.html" 2>&1); then
  echo "FAIL: the checker passed a gallery with a missing file"; exit 1
fi
case "$out" in
  *"index.html: broken link data/sheet.svg"*) echo "broken link named: ok" ;;
  *) echo "FAIL: the checker did not name the missing file:"; echo "$out"; exit 1 ;;
esac
