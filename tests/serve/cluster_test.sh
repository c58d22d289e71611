#!/usr/bin/env bash
# WebSocket sessions through HAProxy: scripts/serve-cluster.sh starts 2 servers
# behind deploy/haproxy.cfg on free loopback ports; 6 replay clients stream for
# a second through HAProxy; most frames must be answered, both servers must
# have taken sessions, and stop must leave no process behind. --cpu-cap: a bad
# share is refused by name; where the cgroup CPU controller is writable (root,
# as in CI) the servers run capped at half a core, each in its own cgroup with
# that quota, and stop removes the cgroups; where it is not, the refusal names it.
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
expect_refusal() {  # expect_refusal MESSAGE ARGS...: start refuses with MESSAGE on stderr and starts nothing
  local want=$1; shift
  if "$root/scripts/serve-cluster.sh" start 1 --port "$port" --dir "$dir/refused" --legwork "$legwork" "$@" > "$dir/refusal.txt" 2>&1; then
    echo "cluster_test: FAIL: start $* was accepted"; exit 1
  fi
  grep -qF -- "$want" "$dir/refusal.txt" || { echo "cluster_test: FAIL: start $* said:"; cat "$dir/refusal.txt"; exit 1; }
  ! ls "$dir"/refused/serve-*.pid >/dev/null 2>&1 || { echo "cluster_test: FAIL: start $* left a server"; exit 1; }
  echo "cluster_test: refused as expected: $(head -1 "$dir/refusal.txt")"
}
expect_refusal "--cpu-cap 2: a share of one core between 0.1 and 1 expected" --cpu-cap 2
expect_refusal "--cpu-cap 0.05: a share of one core between 0.1 and 1 expected" --cpu-cap 0.05
expect_refusal "--cpu-cap half: a share of one core between 0.1 and 1 expected" --cpu-cap half
expect_refusal "--cpu-cap needs a value" --cpu-cap
cap_args=()
cgroup=/sys/fs/cgroup/cpu
[ -e /sys/fs/cgroup/cgroup.controllers ] && cgroup=/sys/fs/cgroup
if { [ ! -e /sys/fs/cgroup/cgroup.controllers ] || grep -qw cpu /sys/fs/cgroup/cgroup.controllers; } &&
   mkdir "$cgroup/legwork-test-$$" 2>/dev/null; then
  rmdir "$cgroup/legwork-test-$$"
  cap_args=(--cpu-cap 0.5)
else
  expect_refusal "--cpu-cap needs a writable cgroup CPU controller" --cpu-cap 0.5
fi
"$root/scripts/serve-cluster.sh" start 2 --port "$port" --dir "$dir" --legwork "$legwork" "${cap_args[@]}" -- --verbose
if [ ${#cap_args[@]} -gt 0 ]; then
  # Each server in its own cgroup, 1 ms of CPU per 2 ms.
  [ "$(wc -l < "$dir/cgroups")" = 2 ] || { echo "cluster_test: FAIL: expected 2 cgroups, got:"; cat "$dir/cgroups"; exit 1; }
  for i in 1 2; do
    g=$(sed -n "${i}p" "$dir/cgroups") pid=$(cat "$dir/serve-$i.pid")
    grep -qx "$pid" "$g/cgroup.procs" || { echo "cluster_test: FAIL: server $i ($pid) is not in $g"; exit 1; }
    if [ -e "$g/cpu.max" ]; then quota=$(cat "$g/cpu.max"); else quota="$(cat "$g/cpu.cfs_quota_us") $(cat "$g/cpu.cfs_period_us")"; fi
    [ "$quota" = "1000 2000" ] || { echo "cluster_test: FAIL: server $i's quota is '$quota', expected '1000 2000'"; exit 1; }
    echo "cluster_test: server $i capped: $g, quota $quota"
  done
  cp "$dir/cgroups" "$dir/cgroups.started"
fi
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
if [ -e "$dir/cgroups.started" ]; then
  while read -r g; do [ ! -e "$g" ] || { echo "cluster_test: FAIL: stop left the cgroup $g"; exit 1; }; done < "$dir/cgroups.started"
fi
echo "cluster_test: ok"
