#!/usr/bin/env bash
# Installs every Debian package legwork needs (idempotent) and builds it.
# Usage: [LEGWORK_BUILD_TARGETS="t1 t2"] scripts/setup.sh [BUILD_DIR] [extra cmake args...]   (default build dir: build)
set -euo pipefail
cd "$(dirname "$0")/.."

# Each dependency, and why.
PACKAGES=(
  g++ cmake ninja-build pkg-config git  # toolchain (C++20, CMake >= 3.25)
  libeigen3-dev                         # math (vectors, quaternions)
  libcairo2-dev                         # pictures (PNG/SVG stick figures, charts)
  ffmpeg                                # MP4 videos (the ffmpeg program)
  libcli11-dev                          # command line
  nlohmann-json3-dev                    # JSON reports and key-pose files
  libtinygltf-dev                       # glTF 2.0 (.glb) export
  libnanoflann-dev                      # KD-tree nearest neighbours (accentuation)
  libxxhash-dev                         # XXH3-64: the accent database checksum (20-40 GB/s, vs ~1 GB/s for the old FNV-1a)
  libgtest-dev libgmock-dev             # tests
  libbenchmark-dev                      # benchmarks
  libassimp-dev                         # benchmark baseline: assimp's BVH importer
  clang libclang-rt-14-dev              # libFuzzer target for the BVH reader
  python3-dev pybind11-dev python3-pybind11  # Python bindings (legwork package, built against Debian's /usr/bin/python3)
  python3-numpy                         # Python bindings: arrays in and out
  python3-pytest                        # Python binding tests (python/tests, compared with the CLI)
  python3-matplotlib                    # python/examples/plot_accent.py (run in CI)
  python3-setuptools python3-wheel python3-venv python3-pip  # offline `pip install --no-build-isolation .` (python/README.md)
  mono-mcs mono-runtime                 # C# binding (bindings/csharp): compiled and run against liblegwork.so in CI
  libboost-dev                          # legwork serve: Boost.Beast/Asio (header-only) HTTP + WebSocket, well kept, in Debian
  liblo-dev liblo-tools                 # legwork serve: VMC (OSC over UDP) with liblo; oscdump/oscsend check it in tests
  haproxy                               # legwork serve scale-out: the load balancer in front of several servers (deploy/haproxy.cfg)
  ccache                                # compiler cache: rebuilds (CI on the same machine, sanitizer builds) reuse objects
  chromium                              # headless browser for the viewer's end-to-end test (driven by playwright-core)
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""
  if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

BUILD=${1:-build}
shift || true
LAUNCHER=()
if command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}" CCACHE_NOHASHDIR=${CCACHE_NOHASHDIR:-true}
  LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release "${LAUNCHER[@]}" "$@" >/dev/null
# LEGWORK_BUILD_TARGETS limits the build (e.g. "legwork" for the CLI only).
# shellcheck disable=SC2086
ninja -C "$BUILD" -j"$(nproc)" ${LEGWORK_BUILD_TARGETS:-}
echo "setup: built legwork in $BUILD/ (CLI: $BUILD/apps/legwork/legwork)" >&2

# The browser viewer (web/, served by `legwork serve`): npm packages from the
# npm registry, pinned by web/package-lock.json:
#   three           - the 3D scene (WebGL renderer, GLTFLoader for walk-cycle GLBs, WebXR)
#   esbuild         - bundles web/src/*.js into web/dist/ (not committed)
#   playwright-core - drives Debian's chromium in the end-to-end test (no browser download)
#   ws              - WebSocket server of the test's mock of `legwork serve`
# LEGWORK_SKIP_WEB=1 skips it (C++-only machines).
if [ "${LEGWORK_SKIP_WEB:-0}" != 1 ]; then
  # node + npm run the bundler and the tests; Debian's only when none is installed
  # (a NodeSource nodejs already ships npm and conflicts with Debian's npm package).
  if ! command -v npm >/dev/null 2>&1; then
    echo "setup: installing nodejs npm" >&2
    SUDO=""
    if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null
  fi
  ( cd web && npm ci --no-audit --no-fund --loglevel=error && npm run build --silent )
  echo "setup: built the viewer in web/dist/ (test: cd web && npm test)" >&2
fi
