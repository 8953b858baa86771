#!/usr/bin/env bash
# Builds fireswarm (installing what is missing) and runs every test with CTest.
#   scripts/test.sh              -> the normal build (warnings are errors)
#   scripts/test.sh --sanitize   -> the same tests under AddressSanitizer + UBSan,
#                                   but for the scenario files (label "scenario":
#                                   whole `fireswarm run` missions, 3-4 min of CPU
#                                   under the sanitizers), whose code the run/
#                                   and app/ suites drive under them already
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build
ctest_args=()
if [ "${1:-}" = "--sanitize" ]; then
  build_dir=build-asan
  ctest_args=(-LE scenario)
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
fi
bash scripts/build.sh "$@"
ctest --test-dir "$build_dir" --output-on-failure -j 2 "${ctest_args[@]}"
