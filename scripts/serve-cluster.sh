#!/usr/bin/env bash
# N `legwork serve` processes on loopback behind HAProxy (deploy/haproxy.cfg).
#
#   scripts/serve-cluster.sh start N [--port 8080] [--dir DIR] [--legwork BIN] [--pin] [--cpu-cap F] [-- serve options...]
#   scripts/serve-cluster.sh stop [--dir DIR]
#
# start: each server on a free loopback port (legwork serve --port 0), then
# HAProxy on 127.0.0.1:PORT with the shipped config's server lines replaced by
# those ports; prints the URL. --pin: server i runs on CPU (i-1) mod nproc.
# --cpu-cap F (0.1-1): each server gets at most F of a core (its own cgroup's
# CPU quota: 1 ms of CPU per 1/F ms). With it the scaling of N processes
# behind HAProxy can be measured on a machine with no spare cores for HAProxy
# and the clients (scripts/serve-bench.sh --cpu-cap). Needs a writable cgroup
# CPU controller (v1 /sys/fs/cgroup/cpu or v2 cpu.max; root in a container).
# stop: SIGINT to the servers (sessions close, recordings are written), then
# HAProxy. DIR (default .serve-cluster) holds the logs, pid files and config.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cmd=${1:-}; shift || true
n=0
if [ "$cmd" = start ]; then n=${1:?usage: serve-cluster.sh start N}; shift; fi
port=8080 dir=.serve-cluster legwork="$root/build/apps/legwork/legwork" pin=0 cap=""
while [ $# -gt 0 ]; do
  case $1 in
    --port) port=$2; shift 2 ;;
    --dir) dir=$2; shift 2 ;;
    --legwork) legwork=$2; shift 2 ;;
    --pin) pin=1; shift ;;
    --cpu-cap) cap=${2:-}; shift 2 || { echo "serve-cluster: --cpu-cap needs a value (a share of one core, 0.1-1)" >&2; exit 2; } ;;
    --) shift; break ;;
    *) echo "serve-cluster: unknown option $1" >&2; exit 2 ;;
  esac
done

# The CPU controller's root for --cpu-cap: cgroup v2 (cpu.max) or v1 (cfs quota).
cgroup_root() {
  if [ -e /sys/fs/cgroup/cgroup.controllers ]; then
    grep -qw cpu /sys/fs/cgroup/cgroup.subtree_control 2>/dev/null || echo +cpu > /sys/fs/cgroup/cgroup.subtree_control 2>/dev/null || return 1
    echo /sys/fs/cgroup
  elif [ -e /sys/fs/cgroup/cpu/cpu.cfs_quota_us ]; then
    echo /sys/fs/cgroup/cpu
  else
    return 1
  fi
}
# cap_process PID GROUP: PID (all its threads) into a new cgroup GROUP under $base limited to
# 1000 us of CPU per $period us (start sets both once, after checking --cpu-cap).
cap_process() {
  local g=$base/$2
  mkdir -p "$g" 2>/dev/null || return 1
  if [ -e "$g/cpu.max" ]; then
    echo "1000 $period" > "$g/cpu.max" || return 1
  else
    echo "$period" > "$g/cpu.cfs_period_us" && echo 1000 > "$g/cpu.cfs_quota_us" || return 1
  fi
  echo "$1" > "$g/cgroup.procs" || return 1
  echo "$g" >> "$dir/cgroups"
}

stop() {
  for f in "$dir"/serve-*.pid; do
    [ -e "$f" ] || continue
    kill -INT "$(cat "$f")" 2>/dev/null || true
  done
  for f in "$dir"/serve-*.pid; do
    [ -e "$f" ] || continue
    pid=$(cat "$f")
    for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.05; done
    kill -KILL "$pid" 2>/dev/null || true
    rm -f "$f"
  done
  if [ -e "$dir/haproxy.pid" ]; then
    kill -TERM "$(cat "$dir/haproxy.pid")" 2>/dev/null || true
    rm -f "$dir/haproxy.pid"
  fi
  if [ -e "$dir/cgroups" ]; then
    while read -r g; do rmdir "$g" 2>/dev/null || true; done < "$dir/cgroups"
    rm -f "$dir/cgroups"
  fi
}

case $cmd in
  stop) stop; echo "serve-cluster: stopped" ;;
  start)
    command -v haproxy >/dev/null || { echo "serve-cluster: haproxy missing (scripts/setup.sh installs it)" >&2; exit 1; }
    [ "$n" -ge 1 ] || { echo "serve-cluster: N must be at least 1" >&2; exit 2; }
    if [ -n "$cap" ]; then
      python3 -c "import sys; c = float(sys.argv[1]); sys.exit(0 if 0.1 <= c <= 1 else 1)" "$cap" 2>/dev/null ||
        { echo "serve-cluster: --cpu-cap $cap: a share of one core between 0.1 and 1 expected" >&2; exit 2; }
      { base=$(cgroup_root) && mkdir "$base/legwork-probe-$$" && rmdir "$base/legwork-probe-$$"; } 2>/dev/null ||
        { echo "serve-cluster: --cpu-cap needs a writable cgroup CPU controller (/sys/fs/cgroup/cpu or cgroup v2 with cpu), e.g. root in a container" >&2; exit 1; }
      period=$(python3 -c "import sys; print(round(1000 / float(sys.argv[1])))" "$cap")  # us per 1000 us of CPU
    fi
    mkdir -p "$dir"
    stop
    servers=""
    for i in $(seq "$n"); do
      run=("$legwork" serve --port 0 "$@")
      if [ "$pin" = 1 ]; then run=(taskset -c $(( (i - 1) % $(nproc) )) "${run[@]}"); fi
      "${run[@]}" > "$dir/serve-$i.log" 2>&1 &
      echo $! > "$dir/serve-$i.pid"
      if [ -n "$cap" ] && ! cap_process "$!" "legwork-serve-$$-$i"; then
        stop; echo "serve-cluster: could not cap server $i at $cap of a core (cgroup not writable)" >&2; exit 1
      fi
      for _ in $(seq 200); do grep -q listening "$dir/serve-$i.log" && break; sleep 0.05; done
      p=$(grep -o '127.0.0.1:[0-9]*/' "$dir/serve-$i.log" | head -1 | tr -dc '0-9:' | cut -d: -f2)
      if [ -z "$p" ]; then cat "$dir/serve-$i.log" >&2; stop; echo "serve-cluster: server $i did not start" >&2; exit 1; fi
      servers+="    server s$i 127.0.0.1:$p check inter 2s\n"
    done
    # The shipped config with this run's port and servers.
    sed -e "s|^\( *bind \)127.0.0.1:[0-9]*|\1127.0.0.1:$port|" -e '/^ *server s[0-9]/d' "$root/deploy/haproxy.cfg" |
      awk -v s="$servers" '{ print } /# servers/ { printf "%s", s }' > "$dir/haproxy.cfg"
    haproxy -c -q -f "$dir/haproxy.cfg"
    haproxy -D -p "$dir/haproxy.pid" -f "$dir/haproxy.cfg"
    for _ in $(seq 100); do curl -sf "http://127.0.0.1:$port/api/info" > /dev/null && break; sleep 0.05; done
    curl -sf "http://127.0.0.1:$port/api/info" > /dev/null || { stop; echo "serve-cluster: haproxy does not answer on $port" >&2; exit 1; }
    if [ -n "$cap" ]; then echo "serve-cluster: each server capped at $cap of a core (cgroups: $(paste -sd' ' "$dir/cgroups"))"; fi
    echo "serve-cluster: $n servers behind http://127.0.0.1:$port/ (WebSocket ws://127.0.0.1:$port/ws); stop with: $0 stop --dir $dir"
    ;;
  *) echo "usage: serve-cluster.sh start N [--port P] [--dir DIR] [--legwork BIN] [--pin] [--cpu-cap F] [-- serve options] | stop [--dir DIR]" >&2; exit 2 ;;
esac
