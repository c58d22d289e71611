#!/usr/bin/env bash
# Draws the dependency graph of legwork's library targets (docs/targets.svg)
# from CMake's own graph: runtime targets (per-frame code) depend only on
# legwork::core and legwork::ik (combined: also wip and accent); offline targets on anything. Needs graphviz.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build-tests}
out=$(mktemp -d)
cat > "$out/CMakeGraphVizOptions.cmake" <<'OPT'
set(GRAPHVIZ_EXECUTABLES FALSE)
set(GRAPHVIZ_EXTERNAL_LIBS FALSE)
set(GRAPHVIZ_IGNORE_TARGETS "test_.*;legwork_header_check;legwork_testdata;.*_bench;.*fuzz.*;legwork_c_static;legwork_c_objects")
OPT
cp "$out/CMakeGraphVizOptions.cmake" "$BUILD/"
cmake --graphviz="$out/targets.dot" "$BUILD" >/dev/null
rm -f "$BUILD/CMakeGraphVizOptions.cmake"
# Colour runtime targets green, offline ones grey.
sed -E -e 's/label = "legwork_(core|ik|wip|walkcycle|accent|combined)\\n\(legwork::[a-z_]+\)"/label = "legwork::\1\\nruntime", style = filled, fillcolor = "#c8e6c9"/' \
       -e 's/label = "legwork_c\\n\(legwork::c\)"/label = "liblegwork.so\\n(legwork::c, C API)", style = filled, fillcolor = "#bbdefb"/' \
       -e 's/label = "legwork_([a-z_]+)\\n\(legwork::[a-z_]+\)"/label = "legwork::\1\\noffline", style = filled, fillcolor = "#eeeeee"/' \
       -e '/subgraph clusterLegend/,/^}/d' \
       "$out/targets.dot" > "$out/colored.dot"
dot -Tsvg "$out/colored.dot" -o docs/targets.svg
dot -Tpng -Gdpi=70 "$out/colored.dot" -o docs/targets.png
rm -rf "$out"
echo "wrote docs/targets.svg"
