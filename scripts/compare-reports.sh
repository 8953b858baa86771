#!/usr/bin/env bash
# Shows that a change left every simulated mission as it was: runs `fireswarm run`
# on every scenarios/*.yaml and compares each report with one recorded before the
# change, wall-clock fields aside (build/bin/report_diff).
#   scripts/compare-reports.sh record DIR   -> DIR/<scenario>.json from this build
#   scripts/compare-reports.sh check DIR    -> run again, compare with DIR/<scenario>.json
# FIRESWARM=/path/to/fireswarm picks another binary (e.g. a build of the old commit).
# Exit 0 when every report is the same, 1 when one differs, 2 on bad use.
set -euo pipefail
cd "$(dirname "$0")/.."

mode=${1:-}
dir=${2:-}
if [ -z "$mode" ] || [ -z "$dir" ] || { [ "$mode" != record ] && [ "$mode" != check ]; }; then
  echo "usage: scripts/compare-reports.sh record|check DIR" >&2
  exit 2
fi
fireswarm=${FIRESWARM:-build/bin/fireswarm}
diff_tool=build/bin/report_diff
tools=("$fireswarm")
[ "$mode" = check ] && tools+=("$diff_tool")
for tool in "${tools[@]}"; do
  [ -x "$tool" ] || { echo "compare-reports: $tool is missing: build first (scripts/build.sh)" >&2; exit 2; }
done
mkdir -p "$dir"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

differ=0
for scenario in scenarios/*.yaml; do
  name=$(basename "$scenario" .yaml)
  out="$scratch/$name.json"
  # Exit 1 (an expectation failed) is still a report to compare; 2 is bad input.
  status=0
  "$fireswarm" run "$scenario" --report "$out" >/dev/null 2>&1 || status=$?
  if [ "$status" -ge 2 ]; then
    echo "$name: fireswarm run exited $status" >&2
    exit 2
  fi
  if [ "$mode" = record ]; then
    cp "$out" "$dir/$name.json"
    echo "$name: recorded (exit $status)"
  elif "$diff_tool" "$dir/$name.json" "$out" >"$scratch/$name.diff"; then
    echo "$name: same"
  else
    echo "$name: DIFFERS"
    sed 's/^/  /' "$scratch/$name.diff"
    differ=1
  fi
done
exit "$differ"
