#!/usr/bin/env bash
# Load benchmark for `legwork serve` on loopback (bounded; stops by itself):
# N replay clients at 90 Hz (bench/serve_load), doubling N until p99 > 5 ms
# or a frame goes unanswered, against
#   1. one server process pinned to one core (taskset -c 0), and
#   2. two server processes (cores 0 and 1) behind HAProxy (scripts/serve-cluster.sh).
# Prints the figures and writes OUT.json (default serve-bench.json).
#   scripts/serve-bench.sh [--out FILE] [--method ik|accent] [--db FILE] [--classes a,b] [--seconds S] [--max-clients N]
#                          [--build DIR] [--workers N (default 0)] [--aligned] [--one-only] [--search-interval S]
#                          [--start-spread S]
# --classes: the sessions' accent classes (default none: the server recognises the activity);
# --search-interval: the sessions' accent search interval in seconds (default: the server's, 0.044);
# --aligned: clients send at the same instant (default: spread over the frame period);
# --start-spread: seconds over which the clients' streams start (default 0: all in the first period);
# --one-only: skip the two-process HAProxy run.
# serve_load reports the servers' CPU per frame and their run-queue wait (CPU time other
# processes took from them): on a shared machine the latency figures include it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=serve-bench.json method=ik db="" seconds=5 max=1280 build="$root/build" workers=0 one_only=0
load_args=()
while [ $# -gt 0 ]; do
  case $1 in
    --out) out=$2; shift 2 ;;
    --method) method=$2; shift 2 ;;
    --db) db=$2; shift 2 ;;
    --seconds) seconds=$2; shift 2 ;;
    --max-clients) max=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    --workers) workers=$2; shift 2 ;;
    --classes) load_args+=(--classes "$2"); shift 2 ;;
    --search-interval) load_args+=(--search-interval "$2"); shift 2 ;;
    --aligned) load_args+=(--aligned); shift ;;
    --start-spread) load_args+=(--start-spread "$2"); shift 2 ;;
    --one-only) one_only=1; shift ;;
    *) echo "serve-bench: unknown option $1" >&2; exit 2 ;;
  esac
done
legwork="$build/apps/legwork/legwork" load="$build/bench/serve_load"
serve_args=(--max-sessions 5000 --max-rate 1000 --workers "$workers")
[ -n "$db" ] && serve_args+=(--db "$db")
work=$(mktemp -d)
trap '"$root/scripts/serve-cluster.sh" stop --dir "$work/c1" >/dev/null 2>&1 || true; "$root/scripts/serve-cluster.sh" stop --dir "$work/c2" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
ulimit -n 20000 2>/dev/null || true

# 1. One process on one core, clients direct (the load client runs on the other core).
"$root/scripts/serve-cluster.sh" start 1 --port "$(free_port)" --dir "$work/c1" --legwork "$legwork" --pin -- "${serve_args[@]}" >/dev/null
p1=$(grep -o '127.0.0.1:[0-9]*/' "$work/c1/serve-1.log" | head -1 | tr -dc '0-9:' | cut -d: -f2)
taskset -c 1 "$load" --port "$p1" --server-pids "$(cat "$work/c1/serve-1.pid")" --ramp --seconds "$seconds" --max-clients "$max" --method "$method" "${load_args[@]}" --label "1 process" --json "$work/one.json"
"$root/scripts/serve-cluster.sh" stop --dir "$work/c1" >/dev/null

if [ "$one_only" = 1 ]; then
  echo '{"sustained_avatars": 0, "skipped": true}' > "$work/two.json"
else
  # 2. Two processes (one per core) behind HAProxy.
  port=$(free_port)
  "$root/scripts/serve-cluster.sh" start 2 --port "$port" --dir "$work/c2" --legwork "$legwork" --pin -- "${serve_args[@]}" >/dev/null
  "$load" --port "$port" --server-pids "$(cat "$work/c2/serve-1.pid"),$(cat "$work/c2/serve-2.pid")" --ramp --seconds "$seconds" --max-clients "$max" --method "$method" "${load_args[@]}" --label "2 via haproxy" --json "$work/two.json"
  "$root/scripts/serve-cluster.sh" stop --dir "$work/c2" >/dev/null
fi

python3 - "$work/one.json" "$work/two.json" "$out" <<'PY'
import json, os, sys
one, two = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
res = {"machine_cores": os.cpu_count(), "one_process": one, "two_processes_haproxy": two,
       "scaling": (two["sustained_avatars"] / one["sustained_avatars"]) if one["sustained_avatars"] else None}
json.dump(res, open(sys.argv[3], "w"), indent=2)
print("serve-bench: 1 process %d avatars, 2 processes via haproxy %d avatars (x%s); wrote %s" % (
    one["sustained_avatars"], two["sustained_avatars"],
    "%.2f" % res["scaling"] if res["scaling"] else "-", sys.argv[3]))
PY
