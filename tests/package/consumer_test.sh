#!/usr/bin/env bash
# The CMake package end to end: `cmake --install` of this build tree into a fresh prefix, the
# out-of-tree consumer of examples/consumer built against that prefix alone and run, none of
# our warning flags on its compile lines, the installed CLI and scripts; and a project that
# adds dynmesh with add_subdirectory gets the library and the CLI, no tests or benchmarks.
# usage: consumer_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
src=$1 build=$2 work=$3
fail() { echo "consumer_test: $*" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work"
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" > "$work/install.log" || fail "cmake --install failed: $(tail -3 "$work/install.log")"
for f in lib/libdynmesh.a include/dynmesh/version.hpp include/dynmesh/mesh/surface_mesh.hpp \
         lib/cmake/dynmesh/dynmeshConfig.cmake lib/cmake/dynmesh/dynmeshConfigVersion.cmake \
         lib/cmake/dynmesh/dynmeshTargets.cmake bin/dynmesh share/dynmesh/scripts/plot_skin.py; do
    [ -e "$prefix/$f" ] || fail "$f is not installed"
done
"$prefix/bin/dynmesh" --version | grep -q "^dynmesh [0-9]" || fail "the installed CLI does not print its version"

# The Python module, when it was built: importable from the prefix alone.
if compgen -G "$build/python/dynmesh*.so" > /dev/null; then
    site=$(find "$prefix" -name 'dynmesh*.so' -path '*dist-packages*' -printf '%h\n' | head -1)
    [ -n "$site" ] || fail "the Python module is not installed"
    v=$(cd "$work" && PYTHONPATH="$site" /usr/bin/python3 -c "import dynmesh; print(dynmesh.__version__)") \
        || fail "the installed Python module does not import"
    [ "$v" = "$("$prefix/bin/dynmesh" --version | cut -d' ' -f2)" ] || fail "the Python module's version $v differs from the CLI's"
fi

cmake -S "$src/examples/consumer" -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON > "$work/consumer.log" \
    || fail "configuring the consumer failed: $(tail -5 "$work/consumer.log")"
grep -q -- "-Wpedantic\|-fsanitize" "$work/consumer/compile_commands.json" && fail "our warning or sanitizer flags leak into the consumer"
grep -q -- "$src/include" "$work/consumer/compile_commands.json" && fail "the consumer includes the source tree, not the prefix"
cmake --build "$work/consumer" >> "$work/consumer.log" 2>&1 || fail "building the consumer failed: $(tail -5 "$work/consumer.log")"
out=$("$work/consumer/consumer") || fail "the consumer failed: $out"
echo "$out"
echo "$out" | grep -q "^dynmesh [0-9.]*: [0-9]* vertices" || fail "unexpected consumer output: $out"

# add_subdirectory: the library and the CLI, nothing of our tests, benchmarks or examples, and
# none of our flags on the compile line of the project's own target.
mkdir -p "$work/sub"
cat > "$work/sub/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.25)
project(sub LANGUAGES CXX)
add_subdirectory("$src" dynmesh)
add_executable(user "$src/examples/consumer/main.cpp")
target_link_libraries(user PRIVATE dynmesh::dynmesh)
CMAKE
cmake -S "$work/sub" -B "$work/sub/build" -G Ninja -DCMAKE_EXPORT_COMPILE_COMMANDS=ON > "$work/sub.log" 2>&1 \
    || fail "add_subdirectory failed: $(tail -5 "$work/sub.log")"
/usr/bin/python3 - "$work/sub/build/compile_commands.json" <<'PY' || fail "add_subdirectory: our warning flags leak into the project's target"
import json, sys
entries = [e for e in json.load(open(sys.argv[1])) if e["file"].endswith("consumer/main.cpp")]
sys.exit(0 if entries and not any("-Wpedantic" in e["command"] for e in entries) else 1)
PY
targets=$(cmake --build "$work/sub/build" --target help)
echo "$targets" | grep -q "^dynmesh:" || fail "add_subdirectory: no dynmesh target"
for t in skin_tests mesh_tests flip_smoothing skin_vs_cgal_bench; do
    echo "$targets" | grep -q "^$t:" && fail "add_subdirectory builds $t"
done
echo "consumer_test: ok"
