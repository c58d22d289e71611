#!/usr/bin/env bash
# Runs the viewer's end-to-end test against a real `legwork serve` on a free port.
# Usage: web/test/e2e-serve.sh LEGWORK_BINARY [DB.lwdb]
#   without a database, one is built from data/cmu into a temporary folder.
# Needs web/node_modules and web/dist (scripts/setup.sh) and /usr/bin/chromium.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
legwork=${1:?usage: e2e-serve.sh LEGWORK_BINARY [DB.lwdb]}
tmp=$(mktemp -d)
pid=
cleanup() { [ -n "$pid" ] && kill "$pid" 2>/dev/null; wait 2>/dev/null || true; rm -rf "$tmp"; }
trap cleanup EXIT
db=${2:-}
if [ -z "$db" ]; then
  db="$tmp/sample.lwdb"
  "$legwork" accent build --data "$root/data/cmu" --out "$db" >/dev/null
fi
[ -f "$root/web/dist/index.html" ] || (cd "$root/web" && npm run build --silent)
"$legwork" serve --db "$db" --port 0 --web "$root/web/dist" --trials "$root/data/cmu/bvh" >"$tmp/serve.log" 2>&1 &
pid=$!
url=
for _ in $(seq 100); do
  url=$(grep -o 'http://127\.0\.0\.1:[0-9]*' "$tmp/serve.log" | head -1 || true)
  [ -n "$url" ] && break
  kill -0 "$pid" 2>/dev/null || { echo "e2e-serve: legwork serve exited:"; cat "$tmp/serve.log"; exit 1; }
  sleep 0.1
done
[ -n "$url" ] || { echo "e2e-serve: legwork serve printed no URL:"; cat "$tmp/serve.log"; exit 1; }
echo "e2e-serve: testing the viewer against $url"
cd "$root/web" && LEGWORK_URL="$url" npm test
