#!/usr/bin/env bash
# Installs missing dependencies, then configures and builds fireswarm.
#   scripts/build.sh              -> build/      (RelWithDebInfo, warnings are errors)
#   scripts/build.sh --sanitize   -> build-asan/ (AddressSanitizer + UndefinedBehaviorSanitizer)
# Further arguments are passed to `cmake --build` (e.g. --target fireswarm).
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build
cmake_args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DFIRESWARM_WERROR=ON)
if [ "${1:-}" = "--sanitize" ]; then
  shift
  build_dir=build-asan
  cmake_args=(-DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DFIRESWARM_WERROR=ON
              -DFIRESWARM_SANITIZE=ON)
fi

bash scripts/install-deps.sh
# Two parallel jobs keep a full build within a 2-core, small-memory machine.
jobs=$(( $(nproc) < 2 ? 1 : 2 ))
cmake -S . -B "$build_dir" "${cmake_args[@]}" >/dev/null
cmake --build "$build_dir" -j "$jobs" "$@"
