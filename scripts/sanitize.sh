#!/usr/bin/env bash
# Builds legwork with sanitizers and runs its tests there.
#   scripts/sanitize.sh            AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/), the whole ctest suite:
#                                  unit, CLI, README, Python and C# binding, server and protocol tests
#   scripts/sanitize.sh --ci       what ./run-tests runs: the same (--full too: kept for the notes that name it)
#   scripts/sanitize.sh --tsan     ThreadSanitizer (build-tsan/), the threaded tests only
#   scripts/sanitize.sh --tsan --ci ThreadSanitizer of the server's tests and the avatars sharing one
#                                  database (what ./run-tests runs), in build-tsan/
#   extra arguments after the mode go to ctest (e.g. -R Bvh)
# Any sanitizer report fails the run (-fno-sanitize-recover=all, halt_on_error).
# float-cast-overflow is added where the compiler has it (GCC's
# -fsanitize=undefined leaves it out, so it is asked for by name). Leaks in third-party libraries are suppressed by
# scripts/lsan.supp, each with its reason; nothing of legwork's is.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode=asan
ci=0
if [ "${1:-}" = "--tsan" ]; then mode=tsan; shift; fi
if [ "${1:-}" = "--ci" ]; then ci=1; shift; elif [ "${1:-}" = "--full" ]; then ci=2; shift; fi
# Nothing is left out: the tests over the whole shared CMU set (BvhSharedData.*,
# Extract.EverySharedCmuWalkingTrial, HeldOutSubject.*, ...) took 129 s in all with the libraries at -O1
# (docs/reliability.md), and the server's rate-limit tests count the frames' own timestamps, not the
# wall clock, so a slow sanitized client no longer fails them. --ci and --full stay as names.
jobs="${LEGWORK_SANITIZE_JOBS:-$(nproc)}"

# g++ by default: the project's compiler (Debian 12's clang 14 cannot build
# all of legwork's C++20, e.g. lambdas capturing structured bindings in
# src/eval/run.cpp). LEGWORK_SANITIZE_CXX=clang++ picks another.
cxx="${LEGWORK_SANITIZE_CXX:-g++}"
# Does the compiler know float-cast-overflow (GCC's -fsanitize=undefined leaves it out)?
extra=""
if echo 'int main(){}' | "$cxx" -x c++ -fsanitize=float-cast-overflow -o /dev/null - 2>/dev/null; then
  extra=",float-cast-overflow"
fi
preload=""
if [ "$mode" = asan ]; then
  build="${LEGWORK_SANITIZE_BUILD:-$root/build-asan}"
  flags="-fsanitize=address,undefined${extra} -fno-sanitize-recover=all -fno-omit-frame-pointer"
  # python3 and mono are not built with ASan: the runtime is preloaded into
  # them for the Python and C# binding tests (CMakeLists.txt, legwork_interpreter_tests),
  # with libstdc++ (neither links it: ASan's __cxa_throw interceptor finds
  # nothing to forward to at start-up, and the first exception legwork throws
  # inside mono stops with "CHECK failed: ... real___cxa_throw").
  asan_rt="$("$cxx" -print-file-name=libasan.so)" cxx_rt="$("$cxx" -print-file-name=libstdc++.so.6)"
  if [ -f "$asan_rt" ] && [ -f "$cxx_rt" ]; then preload="$asan_rt $cxx_rt"; fi
else
  build="${LEGWORK_SANITIZE_BUILD:-$root/build-tsan}"
  flags="-fsanitize=thread -fno-omit-frame-pointer -g"
fi
# A build dir configured with another compiler cannot be reused.
if [ -f "$build/CMakeCache.txt" ] &&
  ! grep -q "^CMAKE_CXX_COMPILER:[A-Z]*=$(command -v "$cxx")\$" "$build/CMakeCache.txt"; then
  rm -rf "$build"
fi
launcher=()
if command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=true
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# Warnings are the Release build's job (-Werror there); here only the sanitizers judge.
# Everything at -O1 (the module libraries, the tests and the CLI), -g1 everywhere (line tables for the
# reports). At -O0 Eigen's expression templates are not inlined, and the whole suite's tests took hours
# (cli.eval_quick alone 418 s); with the libraries at -O1 the whole suite ran in 892 s of wall time at load 8
# (cli.eval_quick 44 s). The tests used to stay at -O0 (GCC compiles them 30-33 % faster there), but the
# Eigen functions a library does not inline are inline (COMDAT) functions, and the linker keeps the first
# copy it meets: the test's, at -O0. So the libraries ran much of their Eigen code at -O0 all the same
# (gdb samples of an accent test: Quaternion::_transformVector, evaluators and Matrix constructors as
# calls into -O0 copies; libraries at -O2 changed nothing, 66 s either way). With the tests at -O1 too,
# AccentShared.FeetNeverGoThroughTheFloorAndFeetPushedIntoItStand took 25 s instead of 66 s on the idle
# machine (session 35). LEGWORK_SANITIZE_OPT=-O0 builds the tests and the CLI at -O0 again;
# LEGWORK_SANITIZE_MODULE_OPT sets the libraries' own (empty: the same as the tests'). The load client
# bench/serve_load (the server tests' traffic, not code under test) is built at -O0: Boost.Beast at -O1
# under ASan took 132 CPU-s to compile, at -O0 78 (session 37). The analysis programs of
# scripts/wip-*-analysis, which no test runs, are left out (27 CPU-s; the Release build still compiles them).
# Unity build (CMake merges up to 8 sources of a target into one): each merged source parses
# gtest, Eigen and nlohmann-json once, not eight times. The render tests' first batch took 20.5 CPU s
# against 59.7 for its 8 sources apart; the whole suite's cold ASan build 17.8 CPU-min against ~40 (at -O0).
# (./run-tests' Release tree is a unity build too; ./run-demo's build/, the one developers rebuild, is not.)
CXX=$cxx cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_C_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="${LEGWORK_SANITIZE_OPT:--O1} -g1 -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="${LEGWORK_SANITIZE_OPT:--O1} -g1 -DNDEBUG" \
  -DLEGWORK_WERROR=OFF -DLEGWORK_BENCH=OFF -DLEGWORK_HEADER_CHECK=OFF -DLEGWORK_SANITIZER_PRELOAD="$preload" \
  -DLEGWORK_MODULE_OPT="${LEGWORK_SANITIZE_MODULE_OPT--O1}" -DLEGWORK_LOAD_CLIENT_OPT=-O0 -DLEGWORK_ANALYSIS_TOOLS=OFF \
  -DLEGWORK_TEST_TIMEOUT_SCALE=10 -DCMAKE_UNITY_BUILD=ON >/dev/null

export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:abort_on_error=0:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0"
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1"
start=$(date +%s)
if [ "$mode" = asan ]; then
  ninja -C "$build" -j"$jobs"
  echo "sanitize: ASan+UBSan build with $cxx took $(($(date +%s) - start)) s (load: $(cut -d' ' -f1-3 /proc/loadavg))" >&2
  ctest --test-dir "$build" --output-on-failure -j"$jobs" --timeout 1800 "$@"
elif [ $ci = 1 ]; then
  # CI: the server (network thread, worker threads, VMC receiver, sessions
  # opening and closing while others stream) and avatars sharing a database.
  ninja -C "$build" -j"$jobs" test_serve test_accent
  echo "sanitize: TSan build (CI subset) with $cxx took $(($(date +%s) - start)) s (load: $(cut -d' ' -f1-3 /proc/loadavg))" >&2
  # (not the single-threaded stream property tests: TSan has nothing to check there, ASan runs them)
  ctest --test-dir "$build" --output-on-failure -j"$jobs" --timeout 900 -L '^test_serve$' -E 'Streams\.' "$@"
  ctest --test-dir "$build" --output-on-failure -j"$jobs" --timeout 900 -L '^test_accent$' -R 'Thread' "$@"
else
  # The tests that run threads: many avatars over one database, the
  # evaluation's parallel trial loading and its CLI run.
  ninja -C "$build" -j"$jobs" test_accent test_eval legwork
  echo "sanitize: TSan build with $cxx took $(($(date +%s) - start)) s (load: $(cut -d' ' -f1-3 /proc/loadavg))" >&2
  ctest --test-dir "$build" --output-on-failure -j"$jobs" --timeout 1800 \
    -R 'Thread|Concurrent|EvalRun|cli\.eval_quick' "$@"
fi
echo "sanitize: $mode done in $(($(date +%s) - start)) s (load: $(cut -d' ' -f1-3 /proc/loadavg))" >&2
