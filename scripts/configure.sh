#!/usr/bin/env bash
# Configures a build folder the one way every script here does: Ninja when it is installed
# (it compiles the test files while the library still builds; Make waits for each target), and a
# fresh folder when an old one was made by another generator (CMake refuses to switch).
#   scripts/configure.sh SOURCE_DIR BUILD_DIR [CMAKE_ARGS ...]
set -euo pipefail
source_dir=$1
build_dir=$2
shift 2
generator="Unix Makefiles"
command -v ninja >/dev/null && generator=Ninja
if [[ -f "$build_dir/CMakeCache.txt" ]] &&
   ! grep -qx "CMAKE_GENERATOR:INTERNAL=$generator" "$build_dir/CMakeCache.txt"; then
  rm -rf "$build_dir"
fi
cmake -S "$source_dir" -B "$build_dir" -G "$generator" "$@" >/dev/null
