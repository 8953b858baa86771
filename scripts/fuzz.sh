#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang++ with ASan + UBSan) in build-fuzz/ and
# runs each on its seed corpus for a while; any finding fails the script (exit 1)
# and leaves the input in build-fuzz/artifacts/.
#   scripts/fuzz.sh                        -> every target, 25 s each (CI)
#   scripts/fuzz.sh 600 frame_parser       -> one target for 10 minutes
# Installs Debian's clang when it is missing (as root, like install-deps.sh) and
# fails loudly when it cannot: a fuzz step that silently skips would prove nothing.
# New inputs the fuzzer finds go to build-fuzz/corpus/<target>/, not to the tree;
# copy a crash reproducer into fuzz/corpus/<target>/ so the replay ctest keeps it.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-25}
[ $# -gt 0 ] && shift
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

if ! fuzzer_works; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "fuzz: clang++ with libFuzzer is missing; install Debian's clang (apt-get install clang) or run as root" >&2
    exit 1
  fi
  echo "fuzz: installing clang"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends clang libclang-rt-dev >/dev/null
  if ! fuzzer_works; then
    echo "fuzz: clang++ -fsanitize=fuzzer still cannot link a fuzz target" >&2
    exit 1
  fi
fi

bash scripts/install-deps.sh
# No -Werror: the warnings are GCC's contract (scripts/build.sh); clang's are shown.
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DFIRESWARM_FUZZ=ON -DCMAKE_UNITY_BUILD=ON \
  -DFIRESWARM_BUILD_TESTS=OFF -DFIRESWARM_BUILD_BENCH=OFF >/dev/null
jobs=$(( $(nproc) < 2 ? 1 : 2 ))
cmake --build build-fuzz -j "$jobs" --target "${targets[@]/%/_fuzz}"

export ASAN_OPTIONS=abort_on_error=1:detect_leaks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
mkdir -p build-fuzz/artifacts
for target in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$target"
  echo "fuzz: $target for $seconds s"
  log="build-fuzz/$target.log"
  # -timeout: an input taking over 10 s is a finding (the parsers are linear).
  if ! build-fuzz/bin/"${target}_fuzz" -max_total_time="$seconds" -timeout=10 \
      -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="build-fuzz/artifacts/${target}-" \
      "build-fuzz/corpus/$target" "fuzz/corpus/$target" >"$log" 2>&1; then
    tail -n 60 "$log" >&2
    echo "fuzz: $target FAILED (log $log); reproduce with build-fuzz/bin/${target}_fuzz build-fuzz/artifacts/${target}-*" >&2
    exit 1
  fi
  grep -E '^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)' "$log" |
    sed "s/^/fuzz: $target /"
done
echo "fuzz: ${#targets[@]} targets, $seconds s each, no findings"
