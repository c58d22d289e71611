#!/usr/bin/env bash
# VMC round trip with liblo-tools (OSC tools legwork did not write).
#   vmc_test.sh ws  LEGWORK SERVE_LOAD   input over WebSocket (serve_load --still), output checked with oscdump
#   vmc_test.sh osc LEGWORK              input with oscsend (--vmc-in), output checked with oscdump
# Starts and stops its own processes on free loopback ports.
set -euo pipefail
mode=$1 legwork=$2 load=${3:-}
here=$(cd "$(dirname "$0")" && pwd)
for t in oscdump oscsend python3 curl; do
  command -v $t >/dev/null || { echo "vmc_test: SKIP: $t missing (scripts/setup.sh installs liblo-tools)"; exit 77; }
done
work=$(mktemp -d)
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT
free_udp() { python3 -c 'import socket; s=socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }

out_port=$(free_udp)
oscdump -L "$out_port" > "$work/dump.txt" 2> "$work/oscdump.err" &
pids+=($!)
args=(serve --port 0 --vmc-out "127.0.0.1:$out_port" --skeleton "$here/../../data/cmu/bvh/walking/07_01.bvh")
if [ "$mode" = osc ]; then in_port=$(free_udp); args+=(--vmc-in "$in_port"); fi
"$legwork" "${args[@]}" > "$work/serve.log" 2>&1 &
server=$!
pids+=($server)
for _ in $(seq 100); do grep -q listening "$work/serve.log" && break; sleep 0.05; done
port=$(grep -o '127.0.0.1:[0-9]*/' "$work/serve.log" | head -1 | tr -dc '0-9:' | cut -d: -f2)
[ -n "$port" ] || { cat "$work/serve.log"; echo "vmc_test: FAIL: server did not start"; exit 1; }

if [ "$mode" = ws ]; then
  # One WebSocket client replaying the first frame of walking/07_02 (standing still) for a second.
  "$load" --port "$port" --clients 1 --seconds 1 --still > "$work/load.txt"
  # Expected hands: that frame from the server's own replay API, converted to Unity's frame (x -> -x).
  read -r left right < <(curl -sf "http://127.0.0.1:$port/api/trial?name=walking/07_02&rate=90" | python3 -c '
import json, sys
f = json.load(sys.stdin)["frames"][0]
u = lambda p: "%f,%f,%f" % (-p[0], p[1], p[2])
print(u(f["left"]["p"]), u(f["right"]["p"]))')
else
  # A headset and two controllers in Unity coordinates (x right, y up, z forward), identity rotations;
  # the controller at x = -0.25 is on the user's left and must drive the left hand.
  for i in $(seq 40); do
    oscsend 127.0.0.1 "$in_port" /VMC/Ext/Hmd/Pos sfffffff HMD-1 0.0 1.60 0.0 0 0 0 1
    oscsend 127.0.0.1 "$in_port" /VMC/Ext/Con/Pos sfffffff CTRL-A 0.25 1.05 0.20 0 0 0 1
    oscsend 127.0.0.1 "$in_port" /VMC/Ext/Con/Pos sfffffff CTRL-B -0.25 1.05 0.20 0 0 0 1
    sleep 0.025
  done
  left=-0.25,1.05,0.20 right=0.25,1.05,0.20
fi
sleep 0.3
kill -INT "$server"
wait "$server" || { cat "$work/serve.log"; echo "vmc_test: FAIL: server did not stop cleanly on SIGINT"; exit 1; }
grep -q "stopped" "$work/serve.log" || { cat "$work/serve.log"; echo "vmc_test: FAIL: no clean shutdown"; exit 1; }
python3 "$here/check_vmc.py" "$work/dump.txt" "$left" "$right"
