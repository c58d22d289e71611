#!/usr/bin/env bash
# scripts/serve-bench.sh end to end at a tiny load: its option checks refuse bad
# values by name, and two rounds of its three ramps (one process direct, one behind
# HAProxy, two behind HAProxy; the second round starts with the second) write the
# JSON the docs quote: every run's steps, each round's order, the sustained counts
# and medians, the scaling. (The figures themselves are the
# benchmark's, not this test's.)
#   bench_script_test.sh BUILD_DIR
set -euo pipefail
build=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
for t in haproxy python3 curl taskset; do
  command -v $t >/dev/null || { echo "bench_script_test: SKIP: $t missing (scripts/setup.sh installs haproxy)"; exit 77; }
done
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
refuse() {  # refuse MESSAGE ARGS...
  local want=$1; shift
  if "$root/scripts/serve-bench.sh" --build "$build" --out "$dir/refused.json" "$@" > "$dir/out.txt" 2>&1; then
    echo "bench_script_test: FAIL: serve-bench.sh $* was accepted"; exit 1
  fi
  grep -qF -- "$want" "$dir/out.txt" || { echo "bench_script_test: FAIL: serve-bench.sh $* said:"; cat "$dir/out.txt"; exit 1; }
  [ ! -e "$dir/refused.json" ] || { echo "bench_script_test: FAIL: serve-bench.sh $* wrote its JSON"; exit 1; }
  echo "bench_script_test: refused as expected: $want"
}
refuse "--repeat 0: a count of rounds (1 or more) expected" --repeat 0
refuse "--repeat x: a count of rounds (1 or more) expected" --repeat x
refuse "--cooldown -1: whole seconds (0 or more) expected" --cooldown -1
refuse "--cpu-cap 3: a share of one core between 0.1 and 1 expected" --cpu-cap 3 --seconds 1 --max-clients 10
refuse "unknown option --bogus" --bogus

"$root/scripts/serve-bench.sh" --build "$build" --seconds 1 --max-clients 10 --repeat 2 --out "$dir/bench.json" | tee "$dir/out.txt"
grep -q "^serve-bench: 1 process [0-9]* avatars, 1 via haproxy [0-9]*, 2 processes via haproxy [0-9]*" "$dir/out.txt" ||
  { echo "bench_script_test: FAIL: no summary line"; exit 1; }
python3 - "$dir/bench.json" <<'PY'
import json, statistics, sys
r = json.load(open(sys.argv[1]))
assert len(r["rounds"]) == 2, r.keys()
# Each round starts with another run and goes round.
kinds = ["one_process", "one_process_haproxy", "two_processes_haproxy"]
assert r["rounds"][0]["order"] == kinds, r["rounds"][0]["order"]
assert r["rounds"][1]["order"] == kinds[1:] + kinds[:1], r["rounds"][1]["order"]
for key, rnd in ((k, x) for k in kinds for x in r["rounds"]):
    run = rnd[key]
    steps = run["steps"]
    assert steps and steps[0]["clients"] == 10 and steps[0]["frames_sent"] > 0, (key, steps)
    assert run["method"] == "ik", run["method"]
    assert steps[0]["client_cpu_us_per_frame"] > 0, (key, steps[0])
    # HAProxy's CPU is measured behind it (a pid given), and only there.
    assert (steps[0]["proxy_cpu_us_per_frame"] > 0) == (key != "one_process"), (key, steps[0])
    if rnd is r["rounds"][0]:
        assert r[key] == run, key  # the first round's figures at the top level, as before
for key, runs in (("one_process", "sustained_one_process"), ("one_process_haproxy", "sustained_one_process_haproxy"),
                  ("two_processes_haproxy", "sustained_two_processes")):
    assert r[runs] == [x[key]["sustained_avatars"] for x in r["rounds"]], runs
    assert r[runs + "_median"] == statistics.median(r[runs]), runs
one, two = r["sustained_one_process_median"], r["sustained_two_processes_median"]
assert r["scaling"] == (two / one if one else None), r["scaling"]
assert r["cpu_cap_per_process"] is None and r["machine_cores"] >= 1
print("bench_script_test: JSON ok (sustained %s / %s / %s)" % (one, r["sustained_one_process_haproxy_median"], two))
PY
echo "bench_script_test: ok"
