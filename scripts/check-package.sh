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
rm -rf "$PREFIX"
echo "package check: find_package(legwork) consumer builds and runs"
