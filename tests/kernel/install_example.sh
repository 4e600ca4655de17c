#!/bin/sh
# Installs the build tree into a temporary prefix, builds examples/hello_plugin out of tree
# against it with find_package(medax), and runs the installed `medax` with the example stage.
# usage: install_example.sh BUILD_DIR SOURCE_DIR TEST_PLUGIN_DIR WORK_DIR
set -eu
abs() { mkdir -p "$1" && (cd "$1" && pwd); }
build=$(abs "$1") source=$(abs "$2") test_plugins=$(abs "$3") work=$(abs "$4")
prefix=$work/prefix example=$work/example-build

fail() { echo "install_example: $*" >&2; exit 1; }
# metric FILE NAME: the value of "NAME": in a metrics.json
metric() { sed -n "s/^ *\"$2\": \([^,]*\),*$/\1/p" "$1"; }

rm -rf "$work"
mkdir -p "$work"

cmake --install "$build" --prefix "$prefix" > "$work/install.log" || { cat "$work/install.log"; fail "cmake --install failed"; }
[ -x "$prefix/bin/medax" ] || fail "no bin/medax in the installed tree"
[ -f "$prefix/lib/cmake/medax/medaxConfig.cmake" ] || fail "no package config in the installed tree"
# Installed targets carry the names used in tree (medax::medax, medax::testing).
grep -q "add_library(medax::testing SHARED IMPORTED)" "$prefix/lib/cmake/medax/medaxTargets.cmake" \
  || fail "the installed package has no medax::testing target"

medax=$prefix/bin/medax

# The installed medax loads every built-in plugin: each finds the kernel libraries in the prefix
# through its run path (the README's install route), with nothing from the build tree.
MEDAX_PLUGIN_PATH= "$medax" plugins > "$work/plugins.txt" 2> "$work/plugins.err" \
  || { cat "$work/plugins.err"; fail "the installed medax plugins failed"; }
[ ! -s "$work/plugins.err" ] || { cat "$work/plugins.err"; fail "the installed medax cannot load its own plugins"; }
for stage in repair normalize sample voronoi dey_zhao vmas erosion_thickness durix reconstruction; do
  grep -q "$stage" "$work/plugins.txt" || fail "the installed medax does not list the built-in stage $stage"
done
# ... and runs a shipped pipeline with them.
MEDAX_PLUGIN_PATH= "$medax" run "$source/pipelines/dey_zhao.yaml" --input "$source/tests/data/ellipsoid.off" \
  --out "$work/run-dey-zhao" --quiet > /dev/null || fail "the installed medax cannot run pipelines/dey_zhao.yaml"
[ -s "$work/run-dey-zhao/medial.ma" ] || fail "the installed run wrote no medial.ma"

# The example sees only the installed tree: no medax source or build folder on its paths.
launcher=
command -v ccache > /dev/null && launcher=-DCMAKE_CXX_COMPILER_LAUNCHER=ccache
cmake -S "$source/examples/hello_plugin" -B "$example" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" $launcher > "$work/configure.log" 2>&1 \
  || { cat "$work/configure.log"; fail "configuring the example against $prefix failed"; }
cmake --build "$example" -j2 > "$work/build.log" 2>&1 || { cat "$work/build.log"; fail "building the example failed"; }
[ -f "$example/libmedax_hello.so" ] || fail "the example did not produce libmedax_hello.so"

# The stage shows up with its documented parameter.
MEDAX_PLUGIN_PATH=$example "$medax" describe hello_volume > "$work/describe.txt"
grep -q "min_radius" "$work/describe.txt" || fail "describe hello_volume does not list min_radius"
# The example's README holds the parameter block its declaration makes.
MEDAX_PLUGIN_PATH=$example "$medax" describe hello_volume --markdown > "$work/block.md"
grep -qxFf "$work/block.md" "$source/examples/hello_plugin/README.md" \
  && [ "$(grep -cxFf "$work/block.md" "$source/examples/hello_plugin/README.md")" -eq "$(wc -l < "$work/block.md")" ] \
  || { cat "$work/block.md"; fail "examples/hello_plugin/README.md does not hold the current parameter block"; }

# 1. The example's own pipeline (a ready-made medial axis: the unit sphere in the cube [-1,1]^3).
MEDAX_PLUGIN_PATH=$example "$medax" run "$source/examples/hello_plugin/hello.yaml" --out "$work/run-hello" --quiet \
  > /dev/null || fail "medax run hello.yaml failed"
m=$work/run-hello/metrics.json
[ "$(metric "$m" mesh_volume)" = "8.0" ] || fail "hello.yaml: mesh_volume is not 8.0 in $m"
case "$(metric "$m" sphere_volume_sum)" in 4.18879020478639*) ;; *) fail "hello.yaml: sphere_volume_sum is not 4π/3 in $m";; esac

# 2. The example stage after an extraction stage from another plugin folder.
cat > "$work/extract.yaml" << YAML
input: $source/tests/data/cube.off
stages:
  - plugin: test_centroid
  - {plugin: hello_volume, id: hello}
YAML
MEDAX_PLUGIN_PATH=$example:$test_plugins "$medax" run "$work/extract.yaml" --out "$work/run-extract" --quiet \
  > /dev/null || fail "medax run with test_centroid + hello_volume failed"
m=$work/run-extract/metrics.json
grep -q '"hello": {' "$m" || fail "no metrics of stage 'hello' in $m"
# The centroid sphere of the cube has radius √3: volume 4π√3 = 21.765592...
case "$(metric "$m" sphere_volume_sum)" in 21.7655923*) ;; *) fail "extract.yaml: wrong sphere_volume_sum in $m";; esac
# 3. The example built against the build tree itself (-Dmedax_DIR), without installing, and
#    loaded by the build tree's medax.
tree_example=$work/example-build-tree
cmake -S "$source/examples/hello_plugin" -B "$tree_example" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -Dmedax_DIR="$build" $launcher > "$work/configure-tree.log" 2>&1 \
  || { cat "$work/configure-tree.log"; fail "configuring the example against the build tree $build failed"; }
cmake --build "$tree_example" -j2 > "$work/build-tree.log" 2>&1 \
  || { cat "$work/build-tree.log"; fail "building the example against the build tree failed"; }
MEDAX_PLUGIN_PATH=$tree_example "$build/bin/medax" run "$source/examples/hello_plugin/hello.yaml" \
  --out "$work/run-hello-tree" --quiet > /dev/null || fail "the build tree's medax cannot run the example built against it"
[ "$(metric "$work/run-hello-tree/metrics.json" mesh_volume)" = "8.0" ] || fail "build-tree example: mesh_volume is not 8.0"
echo "install_example: ok"
