#!/usr/bin/env bash
# Load benchmark for `legwork serve` on loopback (bounded; stops by itself):
# N replay clients at 90 Hz (bench/serve_load), doubling N until p99 > 5 ms
# or a frame goes unanswered, against
#   1. one server process pinned to one core (taskset -c 0), the client on core 1,
#   2. the same behind HAProxy (scripts/serve-cluster.sh), and
#   3. two server processes (cores 0 and 1) behind HAProxy.
# Prints the figures and writes OUT.json (default serve-bench.json).
#   scripts/serve-bench.sh [--out FILE] [--method ik|accent] [--db FILE] [--classes a,b] [--seconds S] [--max-clients N]
#                          [--build DIR] [--workers N (default 0)] [--aligned] [--one-only] [--search-interval S]
#                          [--start-spread S] [--cpu-cap F] [--repeat R] [--cooldown S]
# --classes: the sessions' accent classes (default none: the server recognises the activity);
# --search-interval: the sessions' accent search interval in seconds (default: the server's, 0.044);
# --aligned: clients send at the same instant (default: spread over the frame period);
# --start-spread: seconds over which the clients' streams start (default 0: all in the first period);
# --one-only: skip the HAProxy runs (2 and 3).
# --cpu-cap F: each server process gets at most F (0.1-1) of its core (a cgroup CPU quota,
#   scripts/serve-cluster.sh --cpu-cap): on 2 cores, two servers capped at 0.5 leave a core's
#   worth to HAProxy and the clients, so the 2-process scaling can be measured; the avatar
#   counts are then those of F of a core, not of a whole one.
# --repeat R: R rounds of the three runs, alternating so that all see the host's moods; the
#   figures are the medians and the scaling their ratio (every round is in OUT.json, with
#   its order). Round r starts with the r-th run and goes round (one, one via HAProxy, two;
#   then one via HAProxy, two, one; ...): each run is as often first.
# --cooldown S: seconds idle before each run (default 0): each ramp ends overloaded, and on a
#   shared virtual machine the next run's first steps can pay for it.
# serve_load reports the servers' CPU per frame and their run-queue wait (CPU time other
# processes took from them): on a shared machine the latency figures include it; also its own
# CPU per frame and, behind HAProxy, HAProxy's.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=serve-bench.json method=ik db="" seconds=5 max=1280 build="$root/build" workers=0 one_only=0 cap="" repeat=1 cooldown=0
load_args=() cluster_args=()
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
    --cpu-cap) cap=$2; cluster_args+=(--cpu-cap "$2"); shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --cooldown) cooldown=$2; shift 2 ;;
    *) echo "serve-bench: unknown option $1" >&2; exit 2 ;;
  esac
done
case $repeat in ''|*[!0-9]*|0) echo "serve-bench: --repeat $repeat: a count of rounds (1 or more) expected" >&2; exit 2 ;; esac
case $cooldown in ''|*[!0-9]*) echo "serve-bench: --cooldown $cooldown: whole seconds (0 or more) expected" >&2; exit 2 ;; esac
legwork="$build/apps/legwork/legwork" load="$build/bench/serve_load"
serve_args=(--max-sessions 5000 --max-rate 1000 --workers "$workers")
[ -n "$db" ] && serve_args+=(--db "$db")
work=$(mktemp -d)
trap 'for c in "$work"/c*; do "$root/scripts/serve-cluster.sh" stop --dir "$c" >/dev/null 2>&1 || true; done; rm -rf "$work"' EXIT
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
ulimit -n 20000 2>/dev/null || true

# ramp N LABEL FILE [direct]: N server processes (one per core) behind HAProxy, the client
# unpinned; "direct": the client on core 1 talks to the one server itself, not through HAProxy.
ramp() {
  local port pids target=()
  sleep "$cooldown"
  port=$(free_port)
  "$root/scripts/serve-cluster.sh" start "$1" --port "$port" --dir "$work/c$1" --legwork "$legwork" --pin "${cluster_args[@]}" -- "${serve_args[@]}" >/dev/null
  pids=$(cat "$work/c$1"/serve-*.pid | paste -sd,)
  if [ "${4:-}" = direct ]; then
    port=$(grep -o '127.0.0.1:[0-9]*/' "$work/c$1/serve-1.log" | head -1 | tr -dc '0-9:' | cut -d: -f2)
    target=(taskset -c 1 "$load" --port "$port")
  else
    target=("$load" --port "$port" --proxy-pids "$(cat "$work/c$1/haproxy.pid")")
  fi
  "${target[@]}" --server-pids "$pids" --ramp --seconds "$seconds" --max-clients "$max" --method "$method" "${load_args[@]}" --label "$2" --json "$3"
  "$root/scripts/serve-cluster.sh" stop --dir "$work/c$1" >/dev/null
}

# run KIND R: one ramp of round R.
#   one: one process on one core, clients direct (the load client runs on the other core);
#   one-haproxy: the same process behind HAProxy (the path of two, with one server);
#   two: two processes (one per core) behind HAProxy.
run() {
  case $1 in
    one) ramp 1 "1 process" "$work/one-$2.json" direct ;;
    one-haproxy) ramp 1 "1 via haproxy" "$work/one-haproxy-$2.json" ;;
    two) ramp 2 "2 via haproxy" "$work/two-$2.json" ;;
  esac
}
kinds=(one one-haproxy two)
[ "$one_only" = 1 ] && kinds=(one)
for r in $(seq "$repeat"); do
  # Round r starts with the r-th kind and goes round: each kind is as often first
  # (session 39 saw the first run of a round meet most of the host's slow moments).
  order=()
  for i in "${!kinds[@]}"; do order+=("${kinds[$(( (i + r - 1) % ${#kinds[@]} ))]}"); done
  [ "$repeat" -gt 1 ] && echo "serve-bench: round $r of $repeat (${order[*]})"
  printf '%s\n' "${order[@]}" > "$work/order-$r.txt"
  for k in "${order[@]}"; do run "$k" "$r"; done
  if [ "$one_only" = 1 ]; then
    echo '{"sustained_avatars": 0, "skipped": true}' > "$work/one-haproxy-$r.json"
    echo '{"sustained_avatars": 0, "skipped": true}' > "$work/two-$r.json"
  fi
done

python3 - "$work" "$repeat" "$out" "$cap" <<'PY'
import json, os, statistics, sys
work, repeat, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
cap = float(sys.argv[4]) if sys.argv[4] else None
kinds = ("one", "one-haproxy", "two")
names = {"one": "one_process", "one-haproxy": "one_process_haproxy", "two": "two_processes_haproxy"}
rounds = [{k: json.load(open("%s/%s-%d.json" % (work, k, r))) for k in kinds} for r in range(1, repeat + 1)]
counts = {k: [x[k]["sustained_avatars"] for x in rounds] for k in kinds}
med = {k: statistics.median(v) for k, v in counts.items()}
ratio = lambda a, b: (a / b) if b else None
# The first round's full figures (as before), every round's, and the scaling of the medians:
# against the one process reached directly, and against it behind the same HAProxy path.
res = {"machine_cores": os.cpu_count(), "cpu_cap_per_process": cap,
       **{names[k]: rounds[0][k] for k in kinds},
       "rounds": [{**{names[k]: x[k] for k in kinds}, "order": [names[k] for k in open("%s/order-%d.txt" % (work, r)).read().split()]}
                  for r, x in enumerate(rounds, 1)],
       "sustained_one_process": counts["one"], "sustained_one_process_haproxy": counts["one-haproxy"],
       "sustained_two_processes": counts["two"],
       "sustained_one_process_median": med["one"], "sustained_one_process_haproxy_median": med["one-haproxy"],
       "sustained_two_processes_median": med["two"],
       "scaling": ratio(med["two"], med["one"]), "scaling_vs_one_haproxy": ratio(med["two"], med["one-haproxy"])}
json.dump(res, open(out, "w"), indent=2)
f = lambda x: "%.2f" % x if x else "-"
each = "" if repeat == 1 else " (medians of %d rounds: %s)" % (
    repeat, "; ".join("%s %s" % (k.replace("-", " via "), ", ".join(map(str, counts[k]))) for k in kinds))
print("serve-bench: 1 process %g avatars, 1 via haproxy %g, 2 processes via haproxy %g (x%s against 1 process, x%s against 1 via haproxy)%s%s; wrote %s" % (
    med["one"], med["one-haproxy"], med["two"], f(res["scaling"]), f(res["scaling_vs_one_haproxy"]), each,
    ", each process capped at %g of a core" % cap if cap else "", out))
PY
