// Random numbers in the simulator: one generator per source (each vehicle's GPS,
// each camera's noise, the fire's ignitions, ...), each seeded from the scenario
// seed and the source's name, so adding a source never shifts another's stream.
#pragma once

#include <cstdint>
#include <random>
#include <string_view>

namespace fireswarm::sim2d {

using Rng = std::mt19937_64;

/// A generator for one named source. Same (scenario_seed, source, index) -> same stream.
/// `index` tells apart sources of one kind (e.g. the vehicle's receiver ID).
inline Rng MakeRng(std::uint64_t scenario_seed, std::string_view source, std::uint64_t index = 0) {
  // FNV-1a over the name, then splitmix64 to spread the bits.
  std::uint64_t h = 1469598103934665603ULL;
  for (const char c : source) {
    h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ULL;
  }
  std::uint64_t z = scenario_seed ^ h ^ (index * 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return Rng(z ^ (z >> 31));
}

}  // namespace fireswarm::sim2d
