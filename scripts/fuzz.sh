#!/usr/bin/env bash
# Runs the libFuzzer targets built with clang + ASan/UBSan: BVH, tracker CSV,
# GLB, walk files (key-pose JSON), floor paths (JSON + SVG), the accent
# database file, the serve protocol's messages, the VMC (OSC) input and
# learned walking-in-place tables.
#   scripts/fuzz.sh [SECONDS]     bounded run, SECONDS in total (default 45),
#                                 shared out by the weights in `targets` below
#   scripts/fuzz.sh --long [RUNS] each target until RUNS executions (default
#                                 10,000,000), at most LEGWORK_FUZZ_LONG_HOURS
#                                 hours each (default 6); the corpus persists
#                                 in build-fuzz/corpus-*/ between runs; on a
#                                 shared machine LEGWORK_FUZZ_TIMEOUT=60 (s, wall
#                                 clock; default 10) keeps a starved process from
#                                 reporting false timeouts
#   scripts/fuzz.sh --long RUNS TARGET...  only those targets (e.g. vmc walk_keys)
#   LEGWORK_FUZZ_FORK=N (with --long; default 1): one run in libFuzzer's fork
#                                 mode, N worker processes sharing one corpus,
#                                 RUNS counted over all of them; timeouts and
#                                 out-of-memory still stop it (-ignore_timeouts=0
#                                 -ignore_ooms=0), as they stop a single process
# Each target goes past parsing into the code that consumes the result: BVH
# and GLB into forward kinematics and the writer; tracker CSV into
# io::frames_from_table, the frame clock and usable(); walk files into the
# cycle builder and a walk; paths into arc-length queries and a walk along
# them; the database into its KD-trees and accent::update(); protocol and VMC
# frames into a full-body IK avatar; learned tables into a walking-in-place
# model driven over a real walk (fuzz/*_fuzz.cpp say what each checks).
# Seed corpora come from the repo's real files (data/, fuzz/corpus/), with a
# dictionary per target (fuzz/*.dict).
# Exits non-zero if a fuzzer finds a crash, leak, sanitizer error, timeout or
# out-of-memory; the reproducer is left in build-fuzz/artifacts/. The last
# line of each run's stats (executions, exec/s) is printed as "fuzz: ...".
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LEGWORK_FUZZ_BUILD:-$root/build-fuzz}"
jobs="${LEGWORK_FUZZ_BUILD_JOBS:-2}"
long=0
only=()
if [ "${1:-}" = "--long" ]; then
  long=1
  runs="${2:-10000000}"
  only=("${@:3}")
else
  seconds="${1:-45}"
fi

timeout="${LEGWORK_FUZZ_TIMEOUT:-10}"
if ! [[ "$timeout" =~ ^[1-9][0-9]{0,4}$ ]]; then
  echo "fuzz.sh: LEGWORK_FUZZ_TIMEOUT is '$timeout'; expected whole seconds from 1 to 99999" >&2
  exit 2
fi
fork="${LEGWORK_FUZZ_FORK:-1}"
if ! [[ "$fork" =~ ^[1-9][0-9]?$ ]]; then
  echo "fuzz.sh: LEGWORK_FUZZ_FORK is '$fork'; expected a number of worker processes from 1 to 99" >&2
  exit 2
fi
if [ "$fork" != 1 ] && [ $long = 0 ]; then
  echo "fuzz.sh: LEGWORK_FUZZ_FORK=$fork applies to --long runs only (a bounded run is one process)" >&2
  exit 2
fi
# name:weight(% of the bounded run):max_len; the seeds of each are set up below.
targets=(bvh:15:16384 tracker_csv:10:8192 glb:15:131072 walk_keys:10:16384 path:10:4096 accent_db:15:262144
  protocol:10:4096 vmc:10:4096 wip_table:5:32768)
if [ ${#only[@]} -gt 0 ]; then
  chosen=()
  for name in "${only[@]}"; do
    found=""
    for t in "${targets[@]}"; do if [ "${t%%:*}" = "$name" ]; then chosen+=("$t"); found=1; fi; done
    if [ -z "$found" ]; then
      echo "fuzz.sh: no target '$name'; the targets are: $(for t in "${targets[@]}"; do printf '%s ' "${t%%:*}"; done)" >&2
      exit 2
    fi
  done
  targets=("${chosen[@]}")
fi
launcher=()
if command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=true
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" \
  -DLEGWORK_FUZZ=ON -DLEGWORK_TESTS=OFF -DLEGWORK_BENCH=OFF -DLEGWORK_WERROR=OFF -DCMAKE_UNITY_BUILD=ON >/dev/null
ninja -C "$build" -j"$jobs" $(for t in "${targets[@]}"; do printf '%s_fuzz ' "${t%%:*}"; done)
mkdir -p "$build/artifacts"

# BVH seeds: each sample trial cut to its hierarchy + 3 motion lines (with
# 'Frames: 3'), and the same cut mid-hierarchy and mid-motion.
seeds="$build/corpus-seed"
rm -rf "$seeds"
mkdir -p "$seeds"
i=0
for f in "$root"/data/cmu/bvh/*/*.bvh "$root"/data/cmu/bvh_daz/*/*.bvh "$root"/tests/wip/data/*.bvh; do
  i=$((i + 1))
  awk 'BEGIN{m=0} /^Frames:/{print "Frames: 3"; next} {print} /^Frame Time:/{m=1; n=0; next} m{n++; if(n>=3) exit}' \
    "$f" >"$seeds/s$i.bvh"
  lines=$(wc -l <"$seeds/s$i.bvh")
  head -n $((lines / 3)) "$seeds/s$i.bvh" >"$seeds/s$i-cut1.bvh"
  head -c $(($(wc -c <"$seeds/s$i.bvh") - 17)) "$seeds/s$i.bvh" >"$seeds/s$i-cut2.bvh"
done
sed 's/$/\r/' "$seeds/s1.bvh" >"$seeds/crlf.bvh"
cp "$root"/tests/io/data/*.bvh "$seeds/"

# Tracker CSV seeds: the repo's CSVs and fuzz/corpus/tracker_csv (sessions
# written by legwork from the sample trials).
csv_seeds="$build/corpus-csv-seed"
rm -rf "$csv_seeds"
mkdir -p "$csv_seeds"
cp "$root"/tests/wip/data/*.csv "$root"/fuzz/corpus/tracker_csv/* "$csv_seeds/"
printf 'time,head_x,head_y,head_z,head_qw,head_qx,head_qy,head_qz,left_hand_x,left_hand_y,left_hand_z\n0,0,1.7,0,1,0,0,0,0.3,1,0.1\n0.1,0.01,1.69,0.02,0.7071068,0,0.7071068,0,,,\n0.2,0,1.7,0,1,0,0,0,nan,1,0.1\r\n' \
  >"$csv_seeds/tracker.csv"

# Walk-file seeds: the repo's walks (data/walks/*.json). Paths, the
# database, protocol and VMC seeds are committed in fuzz/corpus/<target>/
# (see fuzz/corpus/README.md); GLB seeds are fuzz/corpus/glb (sample trials
# written by 'legwork convert', as .glb and split as JSON\0BIN, the form
# glb_fuzz wraps itself).
walk_seeds="$build/corpus-walk_keys-seed"
rm -rf "$walk_seeds"
mkdir -p "$walk_seeds"
cp "$root"/data/walks/*.json "$walk_seeds/"
path_seeds="$build/corpus-path-seed"
rm -rf "$path_seeds"
mkdir -p "$path_seeds"
cp "$root"/data/walks/paths/*.json "$root"/fuzz/corpus/path/* "$path_seeds/"
seed_dir() {
  case $1 in
    bvh) echo "$seeds" ;;
    tracker_csv) echo "$csv_seeds" ;;
    walk_keys) echo "$walk_seeds" ;;
    path) echo "$path_seeds" ;;
    *) echo "$root/fuzz/corpus/$1" ;;
  esac
}

summary=()
run() {  # name seeds dict max_len seconds|runs
  local name=$1 seed_dir=$2 dict=$3 max_len=$4 budget=$5
  local corpus="$build/corpus-$name" log="$build/fuzz-$name.log"
  mkdir -p "$corpus"
  local limit=(-max_total_time="$budget")
  if [ $long = 1 ]; then limit=(-runs="$budget" -max_total_time=$((${LEGWORK_FUZZ_LONG_HOURS:-6} * 3600))); fi
  if [ "$fork" != 1 ]; then limit+=(-fork="$fork" -ignore_timeouts=0 -ignore_ooms=0 -ignore_crashes=0); fi
  echo "fuzz: $name (${limit[*]})" >&2
  local rc=0
  "$build/fuzz/${name}_fuzz" "$corpus" "$seed_dir" -dict="$dict" "${limit[@]}" -max_len="$max_len" \
    -timeout="$timeout" -rss_limit_mb=2560 -artifact_prefix="$build/artifacts/$name-" -print_final_stats=1 2>"$log" || rc=$?
  local execs speed
  if [ "$fork" = 1 ]; then
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  else  # fork mode's parent prints only "#RUNS: cov: ... time: Ns ..." lines (their exec/s is the last job's)
    local last secs
    last=$(grep '^#[0-9]*: cov:' "$log" | tail -1 || true)
    execs=$(sed -n 's/^#\([0-9]*\): .*/\1/p' <<<"$last")
    secs=$(sed -n 's/.* time: \([0-9]*\)s .*/\1/p' <<<"$last")
    speed=$([ -n "$execs" ] && [ "${secs:-0}" -gt 0 ] && echo $((execs / secs)) || true)
  fi
  summary+=("fuzz: $name: ${execs:-?} executions, ${speed:-?} exec/s, corpus $(ls "$corpus" | wc -l) files, exit $rc")
  if [ $rc != 0 ]; then
    tail -60 "$log" >&2
    printf '%s\n' "${summary[@]}" >&2
    exit $rc
  fi
}
# -max_total_time=0 would mean "forever": every run gets at least a second.
share() { local s=$((seconds * $1 / 100)); echo $((s > 0 ? s : 1)); }
for t in "${targets[@]}"; do
  IFS=: read -r name weight max_len <<<"$t"
  if [ $long = 1 ]; then budget=$runs; else budget=$(share "$weight"); fi
  run "$name" "$(seed_dir "$name")" "$root/fuzz/$name.dict" "$max_len" "$budget"
done
printf '%s\n' "${summary[@]}"
