// The runner tests' small scenario: 800 m x 500 m of forest and two drones,
// with `extra` YAML appended (no fires, no expectations of its own).
#pragma once

#include <string>

#include "fireswarm/run/scenario.hpp"

namespace fireswarm::run::test {

// Everything of the small scenario but its name.
inline constexpr const char* kSmallAreaKeys = R"(seed: 3
duration_s: 60
area:
  polygon: [[7.0, 45.0], [7.010146, 45.0], [7.010146, 45.0045], [7.0, 45.0045]]
fleet:
  count: 2
  launch: {lat: 44.9995, lon: 7.005}
)";

inline Scenario SmallArea(const std::string& extra) {
  // Appended piece by piece: GCC 12 at -O2 reports a false -Warray-bounds on
  // std::string("...") + const char*.
  std::string text = "name: small_area\n";
  text += kSmallAreaKeys;
  text += extra;
  return ParseScenario(text, "small_area.yaml", ".");
}

}  // namespace fireswarm::run::test
