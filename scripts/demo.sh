#!/usr/bin/env bash
# The main job: builds fireswarm (installing what is missing) and runs it.
# Until the swarm mission lands, that is the radio benchmark: 50 simulated
# vehicles sharing one 57,600-baud half-duplex channel, poll and slot modes.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/build.sh --target fireswarm
for mode in poll slots; do
  echo
  echo "== fireswarm radio-bench --vehicles 50 --seconds 120 --mode $mode =="
  build/bin/fireswarm radio-bench --vehicles 50 --seconds 120 --mode "$mode"
done
