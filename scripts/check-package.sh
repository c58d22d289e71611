#!/usr/bin/env bash
# Installs legwork from BUILD into a temporary prefix and builds + runs the
# example consumer project against it (find_package(legwork)).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build-tests}
PREFIX=$(mktemp -d)
cmake --install "$BUILD" --prefix "$PREFIX" >/dev/null
cmake -S examples/consumer -B "$BUILD/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$PREFIX" >/dev/null
ninja -C "$BUILD/consumer" >/dev/null
"$BUILD/consumer/consumer" data/cmu/bvh/walking/07_01.bvh
# The C example against the installed liblegwork.so and legwork.h.
cmake -S examples/c -B "$BUILD/example-c" -G Ninja -DCMAKE_PREFIX_PATH="$PREFIX" >/dev/null
ninja -C "$BUILD/example-c" >/dev/null
"$PREFIX/bin/legwork" accent build --data data/cmu --exclude bvh/walking/07_02.bvh --out "$PREFIX/sample.lwdb" >/dev/null 2>&1
LD_LIBRARY_PATH="$PREFIX/lib" "$BUILD/example-c/example_c" "$PREFIX/sample.lwdb" data/cmu/bvh/walking/07_02.bvh "$PREFIX/poses.csv"
rm -rf "$PREFIX"
echo "package check: find_package(legwork) consumers (C++ and C) build and run against the installed tree"
