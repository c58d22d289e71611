#!/usr/bin/env bash
# scripts/wip-depth-analysis/depth_bound.py on the repository's walks (data/cmu/bvh/walking:
# 7 trials of 4 subjects, dumped by depth_dump), and its refusals of bad input by name.
# Usage: depth_bound_test.sh DEPTH_DUMP PYTHON SOURCE_DIR
set -u
dump_tool=$1 python=$2 src=$3
script=$src/scripts/wip-depth-analysis/depth_bound.py
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$dump_tool" "$src/data/cmu/bvh/walking" > "$work/dump.csv" || fail "depth_dump exited $?"

# A bad input is refused with a message naming the file (and line and field), exit 1, no traceback.
refuses() {  # refuses 'expected message' args...
  local want=$1; shift
  local out rc
  out=$("$python" "$script" "$@" 2>&1); rc=$?
  [ "$rc" -eq 1 ] || fail "depth_bound $* exited $rc (expected 1): $out"
  case $out in *Traceback*) fail "depth_bound $* printed a traceback: $out" ;; esac
  [ "$out" = "$want" ] || fail "depth_bound $*: got '$out', expected '$want'"
  echo "refused as expected: $want"
}
refuses "depth_bound: cannot read $work/none.csv: No such file or directory" "$work/none.csv"
printf 'a,b\n1,2\n' > "$work/columns.csv"
refuses "depth_bound: $work/columns.csv: not a depth_dump CSV (needs the columns trial, subject, leg, t, hL, hR, zL, zR, turn)" "$work/columns.csv"
# A field that is not a number (line 40's left ankle height) and one that is not finite (line 7's right depth).
awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "hL") c = i } NR == 40 { $c = "abc" } { print }' "$work/dump.csv" > "$work/word.csv"
refuses "depth_bound: $work/word.csv line 40: field 'hL' is 'abc', not a finite number" "$work/word.csv"
awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "zR") c = i } NR == 7 { $c = "nan" } { print }' "$work/dump.csv" > "$work/nan.csv"
refuses "depth_bound: $work/nan.csv line 7: field 'zR' is 'nan', not a finite number" "$work/nan.csv"
grep -E '^(trial|07_)' "$work/dump.csv" > "$work/one.csv"
refuses "depth_bound: $work/one.csv holds walks of 1 subject; leaving one subject out needs at least 2" "$work/one.csv"
rows=$(($(wc -l < "$work/dump.csv") - 1))
head -n 5 "$work/dump.csv" | tail -n 4 | cut -d, -f20,21 > "$work/short.csv"
refuses "depth_bound: $work/short.csv: 4 lines, the dump has $rows frames (depth_lab writes one line of 2 feet a frame)" "$work/dump.csv" --shipped "$work/short.csv"

# The shipped predictions are lined up with the dump by row: with the true depths themselves
# (zL, zR) as the "shipped" file the shipped row scores r 1 and RMS 0, also when the dump's
# trials are interleaved (a row of each trial in turn, each trial's rows still in time order;
# depth_lab's file follows the dump's rows whatever their order).
"$python" - "$work/dump.csv" "$work/mixed.csv" <<'PY' || fail "could not interleave the dump"
import sys
lines = open(sys.argv[1]).read().splitlines()
by_trial = {}
for line in lines[1:]:
    by_trial.setdefault(line.split(",")[0], []).append(line)
out = [lines[0]]
for i in range(max(len(v) for v in by_trial.values())):
    out += [v[i] for v in by_trial.values() if i < len(v)]
open(sys.argv[2], "w").write("\n".join(out) + "\n")
PY
[ "$(sed -n 2p "$work/mixed.csv" | cut -d, -f1)" != "$(sed -n 3p "$work/mixed.csv" | cut -d, -f1)" ] || fail "the dump was not interleaved"
tail -n +2 "$work/mixed.csv" | cut -d, -f20,21 > "$work/truth.csv"
sed -n 3p "$work/truth.csv" | grep -q '^-\?[0-9.]*,-\?[0-9.]*$' || fail "columns 20, 21 of the dump are not zL, zR"
sed '3s/.*/0.1,x/' "$work/truth.csv" > "$work/badline.csv"
refuses "depth_bound: $work/badline.csv line 3: '0.1,x' is not two finite numbers (depth_lab's left,right depths)" "$work/mixed.csv" --shipped "$work/badline.csv"

"$python" "$script" "$work/mixed.csv" --shipped "$work/truth.csv" --json "$work/bound.json" > "$work/out.txt" 2>&1 ||
  fail "depth_bound exited $?: $(cat "$work/out.txt")"
cat "$work/out.txt"
"$python" "$script" "$work/dump.csv" --json "$work/ordered.json" > "$work/ordered.txt" 2>&1 ||
  fail "depth_bound exited $?: $(cat "$work/ordered.txt")"
"$python" - "$work/bound.json" "$work/ordered.json" <<'PY' || exit 1
import json, math, sys
r = json.load(open(sys.argv[1]))
# the interleaved dump scores every predictor as the dump in its own order does
ordered = {(x["predictor"], x["protocol"]): x for x in json.load(open(sys.argv[2]))["results"]}
for x in r["results"]:
    if (x["predictor"], x["protocol"]) in ordered:
        y = ordered[(x["predictor"], x["protocol"])]
        assert abs(x["r"] - y["r"]) < 1e-9 and abs(x["rms_cm"] - y["rms_cm"]) < 1e-9, (x, y)
assert len(ordered) == 6, ordered.keys()  # without --shipped: the kNN, the kNN with the future, ridge; by subject and by trial
res = r["results"]
assert r["goal"] == {"r": 0.9, "rms_cm": 8.0}, r["goal"]
names = [(x["predictor"], x["protocol"]) for x in res]
# shipped, kNN causal, their mean, kNN with the future, ridge (by subject); the last three by trial
assert len(res) == 8, names
shipped = res[0]
assert shipped["predictor"].startswith("shipped"), names
assert abs(shipped["r"] - 1) < 1e-9 and shipped["rms_cm"] < 1e-9, shipped
assert sorted(shipped["per_subject"]) == ["05", "07", "10", "16"], shipped["per_subject"].keys()
n = shipped["samples"]
for x in res:
    assert x["samples"] == n, x  # every row scores the same frames (t >= 0.5 s, both feet)
    assert -1 <= x["r"] <= 1 and math.isfinite(x["rms_cm"]) and x["rms_cm"] > 0 or x is shipped, x
    assert sum(s["samples"] for s in x["per_subject"].values()) == n, x
# the mean of the truth and the causal kNN is nearer the truth than the kNN alone
mean = next(x for x in res if x["predictor"].startswith("mean"))
knn = next(x for x in res if x["predictor"].startswith("kNN k=20, both ankles' past") and x["protocol"] == "subject")
assert abs(mean["rms_cm"] - knn["rms_cm"] / 2) < 1e-6, (mean["rms_cm"], knn["rms_cm"])
print("depth_bound JSON: %d rows over %d samples; shipped = truth scores r %.3f RMS %.3f cm" % (len(res), n, shipped["r"], shipped["rms_cm"]))
PY
echo PASS
