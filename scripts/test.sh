#!/usr/bin/env bash
# Builds fireswarm (installing what is missing) and runs every test with CTest.
#   scripts/test.sh              -> the normal build (warnings are errors)
#   scripts/test.sh --sanitize   -> the same tests under AddressSanitizer + UBSan
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build
if [ "${1:-}" = "--sanitize" ]; then
  build_dir=build-asan
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
fi
bash scripts/build.sh "$@"
ctest --test-dir "$build_dir" --output-on-failure -j 2
