#!/usr/bin/env bash
# Runs the BVH libFuzzer target for a bounded time: scripts/fuzz.sh [seconds]
# (default 60). Builds in build-fuzz/ with clang + ASan/UBSan; the seed corpus
# is made from the repo's sample BVH files (headers + a few motion lines, plus
# truncated copies). Exits non-zero if the fuzzer finds a crash, leak,
# sanitizer error or timeout; the reproducer is left in build-fuzz/artifacts/.
set -euo pipefail
seconds="${1:-60}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LEGWORK_FUZZ_BUILD:-$root/build-fuzz}"
jobs="${LEGWORK_FUZZ_BUILD_JOBS:-2}"

CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DLEGWORK_FUZZ=ON -DLEGWORK_TESTS=OFF -DLEGWORK_BENCH=OFF -DLEGWORK_WERROR=OFF >/dev/null
ninja -C "$build" -j"$jobs" bvh_fuzz

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

echo "fuzzing the BVH reader for ${seconds}s (corpus $corpus)" >&2
"$build/fuzz/bvh_fuzz" "$corpus" "$seeds" \
  -dict="$root/fuzz/bvh.dict" -max_total_time="$seconds" -max_len=16384 -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix="$build/artifacts/" -print_final_stats=1
