#!/usr/bin/env bash
# Builds fireswarm (installing what is missing) and runs every test with CTest:
# the unit suites, the `fireswarm` executable's end-to-end tests, the scenario
# files (whole missions), the fuzz targets' seed corpora, every benchmark's smoke
# run and the command center's browser test.
#   scripts/test.sh             -> in the sanitizer build (build-asan/): AddressSanitizer
#                                  + UndefinedBehaviorSanitizer, warnings are errors;
#                                  then every libFuzzer target for 10 s (scripts/fuzz.sh).
#                                  This is the README's test command and CI's.
#   scripts/test.sh --release   -> in the normal build (build/, the demo's: -O2),
#                                  for a quicker run where the demo has built already;
#                                  no fuzzing
#
# One build, not two: on CI's 2 cores the normal build and its tests took 13 min
# and the sanitizer build and its tests 21 min, and CI must stay under 25. The
# sanitizer build checks more (every test also for memory errors, leaks and
# undefined behaviour) and compiles with the same warnings as errors; the -O2
# build is what scripts/demo.sh builds and runs.
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=build-asan
build_args=(--sanitize)
if [ "${1:-}" = "--release" ]; then
  build_dir=build
  build_args=()
elif [ -n "${1:-}" ]; then
  echo "scripts/test.sh: unknown argument '$1' (none, or --release)" >&2
  exit 2
fi
if [ "$build_dir" = build-asan ]; then
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
fi
bash scripts/build.sh "${build_args[@]}"

# The sanitizer build also fuzzes (issue 19): scripts/fuzz.sh builds the libFuzzer
# targets with clang in build-fuzz/ while the tests run, at the lowest CPU priority,
# so it takes only the time the tests leave idle; then each target runs for a while.
fuzz_seconds=10
fuzz_build_pid=
if [ "$build_dir" = build-asan ]; then
  mkdir -p build-fuzz
  # setsid: its own process group, so that a failing ctest stops the whole build.
  setsid nice -n 19 bash scripts/fuzz.sh --build --no-install >build-fuzz/build.log 2>&1 &
  fuzz_build_pid=$!
  trap 'kill -- "-$fuzz_build_pid" 2>/dev/null || true' EXIT
fi

# Four at once on two cores: many tests wait on the wall clock (a `fireswarm
# serve` mission over a pseudo-terminal, a paced run), not on the CPU. The
# sanitizer build's tests took 565 s of wall time at -j 4 and 971 s at -j 2 (one
# run each, the machine shared with another build).
ctest --test-dir "$build_dir" --output-on-failure -j 4

if [ -n "$fuzz_build_pid" ]; then
  if ! wait "$fuzz_build_pid"; then
    tail -n 40 build-fuzz/build.log >&2
    echo "test: the fuzz build failed (log build-fuzz/build.log)" >&2
    exit 1
  fi
  trap - EXIT
  bash scripts/fuzz.sh --no-install "$fuzz_seconds"
fi
