#!/usr/bin/env bash
# Installs Kiln from BUILD_DIR into a scratch prefix, then configures, builds and runs a consumer project that
# finds it with find_package(Kiln).
set -euo pipefail
build_dir=$1; source_dir=$2; work=$3
rm -rf "$work"; mkdir -p "$work"
cmake --install "$build_dir" --prefix "$work/prefix" > "$work/install.log"
test -x "$work/prefix/bin/kiln"
cmake -S "$source_dir/tests/install/consumer" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/build" -j2 > "$work/build.log"
"$work/build/consumer" "$source_dir/scenes/default.xml"
