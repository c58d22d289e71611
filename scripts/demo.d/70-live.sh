#!/usr/bin/env bash
# The live path without a headset: `legwork serve` with a sample database, a
# CMU trial's head and hands replayed by the browser viewer through the
# server's WebSocket (accentuated body, IK baseline and ground truth side by
# side), captured in headless Chromium as a screenshot and a short MP4; and a
# recorded session (tracker CSV in, BVH out) written by the server.
# Env: LEGWORK (CLI binary), OUT (demo output dir), DATA (repo data/cmu).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
out="$OUT/live"
mkdir -p "$out"
if [ ! -f "$root/web/dist/index.html" ] || [ ! -x /usr/bin/chromium ] || [ ! -d "$root/web/node_modules" ]; then
  echo "live demo skipped: the viewer (web/dist, web/node_modules) or chromium is missing (LEGWORK_SKIP_WEB?)"
  exit 0
fi
tmp=$(mktemp -d)
pid=
cleanup() { [ -n "$pid" ] && kill "$pid" 2>/dev/null; wait 2>/dev/null || true; rm -rf "$tmp"; }
trap cleanup EXIT
"$LEGWORK" accent build --data "$DATA" --exclude bvh/walking/07_02.bvh --out "$tmp/sample.lwdb" >/dev/null 2>&1
mkdir -p "$out/recordings"
"$LEGWORK" serve --db "$tmp/sample.lwdb" --port 0 --web "$root/web/dist" --trials "$DATA/bvh" \
  --record "$out/recordings" >"$tmp/serve.log" 2>&1 &
pid=$!
url=
for _ in $(seq 200); do
  url=$(grep -o 'http://127\.0\.0\.1:[0-9]*' "$tmp/serve.log" | head -1 || true)
  [ -n "$url" ] && break
  kill -0 "$pid" 2>/dev/null || { cat "$tmp/serve.log"; exit 1; }
  sleep 0.1
done
[ -n "$url" ] || { echo "legwork serve printed no URL"; cat "$tmp/serve.log"; exit 1; }
echo "live demo: legwork serve at $url"
node "$root/scripts/screenshot.mjs" --url "$url" --trial walking/07_02 --out "$out/replay_07_02.png"
node "$root/scripts/screenshot.mjs" --url "$url" --trial walking/07_02 --seq 40 --interval-ms 80 --out "$tmp/frame.png"
if command -v ffmpeg >/dev/null 2>&1; then
  # A time-lapse: software WebGL takes about a second (more on a busy machine) per screenshot;
  # played at 10 fps, and the README says how far apart the frames really were.
  ffmpeg -loglevel error -y -framerate 10 -i "$tmp/frame-%03d.png" -pix_fmt yuv420p -vf "scale=trunc(iw/2)*2:trunc(ih/2)*2" \
    "$out/replay_07_02.mp4"
fi
kill "$pid"
wait "$pid" 2>/dev/null || true
pid=
cat > "$out/README.txt" <<'TXT'
replay_07_02.png: the browser viewer served by `legwork serve`, replaying held-out CMU walk 07_02's head and hands through the server's WebSocket: accentuated body (left), IK baseline (middle), ground truth (right)
recordings/: what the server recorded of those sessions (input as tracker CSV, output as BVH)
TXT
if [ -f "$tmp/frame-fps.txt" ] && [ -f "$out/replay_07_02.mp4" ]; then
  echo "replay_07_02.mp4: the same replay as a time-lapse: 40 headless-Chromium screenshots taken $(awk '{printf "%.1f", 1 / $1}' "$tmp/frame-fps.txt") s apart (software WebGL), played at 10 fps" >>"$out/README.txt"
fi
echo "live demo: wrote $out"
