#!/usr/bin/env bash
# N `legwork serve` processes on loopback behind HAProxy (deploy/haproxy.cfg).
#
#   scripts/serve-cluster.sh start N [--port 8080] [--dir DIR] [--legwork BIN] [--pin] [-- serve options...]
#   scripts/serve-cluster.sh stop [--dir DIR]
#
# start: each server on a free loopback port (legwork serve --port 0), then
# HAProxy on 127.0.0.1:PORT with the shipped config's server lines replaced by
# those ports; prints the URL. --pin: server i runs on CPU (i-1) mod nproc.
# stop: SIGINT to the servers (sessions close, recordings are written), then
# HAProxy. DIR (default .serve-cluster) holds the logs, pid files and config.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cmd=${1:-}; shift || true
n=0
if [ "$cmd" = start ]; then n=${1:?usage: serve-cluster.sh start N}; shift; fi
port=8080 dir=.serve-cluster legwork="$root/build/apps/legwork/legwork" pin=0
while [ $# -gt 0 ]; do
  case $1 in
    --port) port=$2; shift 2 ;;
    --dir) dir=$2; shift 2 ;;
    --legwork) legwork=$2; shift 2 ;;
    --pin) pin=1; shift ;;
    --) shift; break ;;
    *) echo "serve-cluster: unknown option $1" >&2; exit 2 ;;
  esac
done

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
}

case $cmd in
  stop) stop; echo "serve-cluster: stopped" ;;
  start)
    command -v haproxy >/dev/null || { echo "serve-cluster: haproxy missing (scripts/setup.sh installs it)" >&2; exit 1; }
    [ "$n" -ge 1 ] || { echo "serve-cluster: N must be at least 1" >&2; exit 2; }
    mkdir -p "$dir"
    stop
    servers=""
    for i in $(seq "$n"); do
      run=("$legwork" serve --port 0 "$@")
      if [ "$pin" = 1 ]; then run=(taskset -c $(( (i - 1) % $(nproc) )) "${run[@]}"); fi
      "${run[@]}" > "$dir/serve-$i.log" 2>&1 &
      echo $! > "$dir/serve-$i.pid"
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
    echo "serve-cluster: $n servers behind http://127.0.0.1:$port/ (WebSocket ws://127.0.0.1:$port/ws); stop with: $0 stop --dir $dir"
    ;;
  *) echo "usage: serve-cluster.sh start N [--port P] [--dir DIR] [--legwork BIN] [--pin] [-- serve options] | stop [--dir DIR]" >&2; exit 2 ;;
esac
