#!/usr/bin/env bash
# WebSocket sessions through HAProxy: scripts/serve-cluster.sh starts 2 servers
# behind deploy/haproxy.cfg on free loopback ports; 6 replay clients stream for
# a second through HAProxy; most frames must be answered, both servers must
# have taken sessions, and stop must leave no process behind.
#   cluster_test.sh LEGWORK SERVE_LOAD
set -euo pipefail
legwork=$1 load=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
for t in haproxy python3 curl; do
  command -v $t >/dev/null || { echo "cluster_test: SKIP: $t missing (scripts/setup.sh installs haproxy)"; exit 77; }
done
dir=$(mktemp -d)
trap '"$root/scripts/serve-cluster.sh" stop --dir "$dir" >/dev/null 2>&1 || true; rm -rf "$dir"' EXIT
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
"$root/scripts/serve-cluster.sh" start 2 --port "$port" --dir "$dir" --legwork "$legwork" -- --verbose
pids=$(cat "$dir"/serve-*.pid "$dir/haproxy.pid")
"$load" --port "$port" --clients 6 --seconds 1 --start-spread 0.3 --label haproxy | tee "$dir/load.txt"
# Sessions flow through the proxy end to end. Not "every frame": a server
# under load drops stale frames by design (latest sample wins, docs/protocol.md),
# and CI runs this beside other tests (the clients start over 0.3 s, --start-spread,
# as users joining at different moments); the latency/throughput figures are the
# benchmark's (scripts/serve-bench.sh). Most frames must still come back.
share=$(grep -o "answered *[0-9.]* %" "$dir/load.txt" | head -1 | grep -o "[0-9.]*")
[ -n "$share" ] || { echo "cluster_test: FAIL: the load client reported nothing through haproxy"; exit 1; }
python3 -c "import sys; sys.exit(0 if float('$share') >= 50 else 1)" ||
  { echo "cluster_test: FAIL: only $share % of frames answered through haproxy"; exit 1; }
for i in 1 2; do
  n=$(grep -c "hello method" "$dir/serve-$i.log" || true)
  [ "$n" -ge 1 ] || { echo "cluster_test: FAIL: server $i took no session (leastconn should spread 6)"; exit 1; }
  echo "cluster_test: server $i took $n sessions"
done
"$root/scripts/serve-cluster.sh" stop --dir "$dir"
sleep 0.2
for p in $pids; do
  if kill -0 "$p" 2>/dev/null && ! grep -q zombie "/proc/$p/status" 2>/dev/null; then
    echo "cluster_test: FAIL: process $p still running after stop"; exit 1
  fi
done
echo "cluster_test: ok"
