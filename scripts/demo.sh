#!/usr/bin/env bash
# The main job: builds fireswarm (installing what is missing) and runs it.
# Until the swarm mission lands, a tour of what is built: plan a search of a
# 27 km^2 forest block for 20 drones (30 min sorties), fly 100 simulated drones
# with thermal cameras over a burning area, and put 50 vehicles on one
# half-duplex radio channel.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/build.sh --target fireswarm
out=build/demo
rm -rf "$out" && mkdir -p "$out/qgc"

run() {
  echo
  echo "== fireswarm $* =="
  build/bin/fireswarm "$@"
}

run plan --area scenarios/areas/convex.geojson --drones 20 --altitude-m 60 \
  --speed-mps 10 --camera seed --out "$out/forest_plan.geojson" --qgc "$out/qgc"
echo "(plan written to $out/forest_plan.geojson, QGroundControl plans to $out/qgc/)"
run sim-bench --drones 100 --camera seed --area-km2 25 --seconds 120
run radio-bench --vehicles 50 --seconds 120 --mode slots
