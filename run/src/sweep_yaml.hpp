// The scenario YAML of one sweep run: the base scenario with keys set. Private to
// the run library (sweep.cpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fireswarm::run::internal {

/// A key path that cannot be set in the base scenario (it goes through a value
/// that is not a mapping).
class OverrideError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// `node` as one line of YAML flow text ("5", "[1, 2]", "{lat: 1, lon: 2}").
std::string FlowYaml(const YAML::Node& node);

/// `base_text` with `seed` set (when given) and each dotted key path of `keys` set
/// to the YAML flow text of the same index in `values` (mappings on the way are
/// created when missing). With `geojson_dir`, the relative GeoJSON paths
/// (area.geojson, a file name as no_fly) are made absolute against it.
/// Precondition: `base_text` is valid YAML (a parsed scenario's). Throws
/// OverrideError naming the key when a path goes through a list or a value.
std::string OverriddenScenarioYaml(std::string_view base_text, std::optional<std::uint64_t> seed,
                                   const std::vector<std::string>& keys,
                                   const std::vector<std::string>& values,
                                   const std::optional<std::filesystem::path>& geojson_dir);

}  // namespace fireswarm::run::internal
