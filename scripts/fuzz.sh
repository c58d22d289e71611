#!/usr/bin/env bash
# Runs the libFuzzer targets for a bounded time: scripts/fuzz.sh [seconds]
# (default 60 in total: 3/4 for the BVH reader, 1/4 for the tracker CSV
# reader). Builds in build-fuzz/ with clang + ASan/UBSan; the BVH seed corpus
# is made from the repo's sample BVH files (headers + a few motion lines, plus
# truncated copies). Exits non-zero if a fuzzer finds a crash, leak,
# sanitizer error or timeout; the reproducer is left in build-fuzz/artifacts/.
set -euo pipefail
seconds="${1:-60}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LEGWORK_FUZZ_BUILD:-$root/build-fuzz}"
jobs="${LEGWORK_FUZZ_BUILD_JOBS:-2}"

CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DLEGWORK_FUZZ=ON -DLEGWORK_TESTS=OFF -DLEGWORK_BENCH=OFF -DLEGWORK_WERROR=OFF >/dev/null
ninja -C "$build" -j"$jobs" bvh_fuzz tracker_csv_fuzz
# -max_total_time=0 would mean "forever": every run gets at least a second.
bvh_seconds=$((seconds * 3 / 4 > 0 ? seconds * 3 / 4 : 1))
csv_seconds=$((seconds - bvh_seconds > 0 ? seconds - bvh_seconds : 1))

# Seed corpus: each sample trial cut to its hierarchy + 3 motion lines (with
# 'Frames: 3'), and the same cut mid-hierarchy and mid-motion.
seeds="$build/corpus-seed"
corpus="$build/corpus"
rm -rf "$seeds"
mkdir -p "$seeds" "$corpus" "$build/artifacts"
i=0
for f in "$root"/data/cmu/bvh/*/*.bvh "$root"/data/cmu/bvh_daz/*/*.bvh; do
  i=$((i + 1))
  awk 'BEGIN{m=0} /^Frames:/{print "Frames: 3"; next} {print} /^Frame Time:/{m=1; n=0; next} m{n++; if(n>=3) exit}' \
    "$f" >"$seeds/s$i.bvh"
  lines=$(wc -l <"$seeds/s$i.bvh")
  head -n $((lines / 3)) "$seeds/s$i.bvh" >"$seeds/s$i-cut1.bvh"
  head -c $(($(wc -c <"$seeds/s$i.bvh") - 17)) "$seeds/s$i.bvh" >"$seeds/s$i-cut2.bvh"
done
sed 's/$/\r/' "$seeds/s1.bvh" >"$seeds/crlf.bvh"

echo "fuzzing the BVH reader for ${bvh_seconds}s (corpus $corpus)" >&2
"$build/fuzz/bvh_fuzz" "$corpus" "$seeds" \
  -dict="$root/fuzz/bvh.dict" -max_total_time="$bvh_seconds" -max_len=16384 -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix="$build/artifacts/" -print_final_stats=1

csv_seeds="$build/corpus-csv-seed"
csv_corpus="$build/corpus-csv"
mkdir -p "$csv_seeds" "$csv_corpus"
printf 'time,head_x,head_y,head_z,head_qw,head_qx,head_qy,head_qz,lhand_x,lhand_y,lhand_z\n0,0,1.7,0,1,0,0,0,0.3,1,0.1\n0.1,0.01,1.69,0.02,0.7071068,0,0.7071068,0,,,\n0.2,0,1.7,0,1,0,0,0,nan,1,0.1\r\n' \
  >"$csv_seeds/tracker.csv"
echo "fuzzing the tracker CSV reader for ${csv_seconds}s" >&2
"$build/fuzz/tracker_csv_fuzz" "$csv_corpus" "$csv_seeds" \
  -max_total_time="$csv_seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix="$build/artifacts/" -print_final_stats=1
