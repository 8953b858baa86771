#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang++ with ASan + UBSan) in build-fuzz/ and
# runs each on its seed corpus for a while; any finding fails the script (exit 1)
# and leaves the input in build-fuzz/artifacts/.
#   scripts/fuzz.sh                        -> every target, 25 s each
#   scripts/fuzz.sh 600 frame_parser       -> one target for 10 minutes
#   scripts/fuzz.sh --build                -> only build them (scripts/test.sh does,
#                                             while the tests run, then runs them)
#   --no-install                           -> skip scripts/install-deps.sh (test.sh
#                                             has run it)
# Fails loudly when clang's libFuzzer is missing: a fuzz step that silently skips
# would prove nothing.
# New inputs the fuzzer finds go to build-fuzz/corpus/<target>/, not to the tree;
# copy a crash reproducer into fuzz/corpus/<target>/ so the replay ctest keeps it.
set -euo pipefail
cd "$(dirname "$0")/.."

build_only=false
install=true
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build_only=true ;;
    --no-install) install=false ;;
    *) break ;;
  esac
  shift
done
seconds=${1:-25}
[ $# -gt 0 ] && shift
case "$seconds" in
  '' | *[!0-9]*)
    echo "fuzz: '$seconds' is not a number of seconds (scripts/fuzz.sh [--build] [--no-install] [SECONDS [TARGET...]])" >&2
    exit 2
    ;;
esac
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(frame_parser payload geojson_area scenario journal operator_command web_command)
fi

# libFuzzer comes with clang (libclang-rt-14-dev holds its runtime).
fuzzer_works() {
  command -v clang++ >/dev/null 2>&1 || return 1
  local probe
  probe=$(mktemp -d)
  printf '%s\n' '#include <cstddef>' '#include <cstdint>' \
    'extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }' \
    > "$probe/probe.cpp"
  clang++ -fsanitize=fuzzer,address,undefined "$probe/probe.cpp" -o "$probe/probe" \
    >/dev/null 2>&1
  local status=$?
  rm -rf "$probe"
  return $status
}

# install-deps.sh installs Debian's clang with the rest.
$install && bash scripts/install-deps.sh
if ! fuzzer_works; then
  echo "fuzz: clang++ -fsanitize=fuzzer cannot link a fuzz target; install Debian's" \
       "clang and libclang-rt-dev (scripts/install-deps.sh, as root)" >&2
  exit 1
fi
# No -Werror: the warnings are GCC's contract (scripts/build.sh); clang's are shown.
# -g0: a finding's stack trace names functions, not lines (configure a build of
# your own with -g1 to debug one); CI builds this on every run.
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g0" -DFIRESWARM_FUZZ=ON -DCMAKE_UNITY_BUILD=ON \
  -DFIRESWARM_BUILD_TESTS=OFF -DFIRESWARM_BUILD_BENCH=OFF >/dev/null
jobs=$(( $(nproc) < 2 ? 1 : 2 ))
cmake --build build-fuzz -j "$jobs" --target "${targets[@]/%/_fuzz}"
if $build_only; then
  exit 0
fi

export ASAN_OPTIONS=abort_on_error=1:detect_leaks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
mkdir -p build-fuzz/artifacts
# Runs one target for $seconds; prints its figures, or its log's end and how to
# reproduce the finding (status 1).
fuzz_one() {
  local target=$1
  local log="build-fuzz/$target.log"
  # -timeout: an input taking over 10 s is a finding (the parsers are linear).
  if ! build-fuzz/bin/"${target}_fuzz" -max_total_time="$seconds" -timeout=10 \
      -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="build-fuzz/artifacts/${target}-" \
      "build-fuzz/corpus/$target" "fuzz/corpus/$target" >"$log" 2>&1; then
    tail -n 60 "$log" >&2
    echo "fuzz: $target FAILED (log $log); reproduce with build-fuzz/bin/${target}_fuzz build-fuzz/artifacts/${target}-*" >&2
    return 1
  fi
  grep -E '^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)' "$log" |
    sed "s/^/fuzz: $target /"
}
# One target per core at a time: each still fuzzes on a core of its own for
# $seconds, and CI's 7 targets take 4 x 10 s of its 2 cores instead of 7 x 10 s.
parallel=$(nproc)
running=0
failed=0
for target in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$target"
  if [ "$running" -ge "$parallel" ]; then
    wait -n || failed=1
    running=$((running - 1))
  fi
  echo "fuzz: $target for $seconds s"
  fuzz_one "$target" &
  running=$((running + 1))
done
while [ "$running" -gt 0 ]; do
  wait -n || failed=1
  running=$((running - 1))
done
if [ "$failed" -ne 0 ]; then
  echo "fuzz: a target failed or found something (above)" >&2
  exit 1
fi
echo "fuzz: ${#targets[@]} targets, $seconds s each, no findings"
