#include "sweep_yaml.hpp"

#include <string>

namespace fireswarm::run::internal {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> SplitKey(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    parts.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) return parts;
    start = dot + 1;
  }
}

// Sets root[a][b]...[z] = value. yaml-cpp nodes are handles: `node = node[k]`
// would assign through the handle, so the walk re-seats it with reset().
void SetPath(YAML::Node root, const std::string& key, const YAML::Node& value) {
  const std::vector<std::string> parts = SplitKey(key);
  YAML::Node node;
  node.reset(root);
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    if (parts[i].empty()) throw OverrideError("an empty part in the key path");
    YAML::Node child = node[parts[i]];
    if (!child.IsDefined() || child.IsNull()) {
      node[parts[i]] = YAML::Node(YAML::NodeType::Map);
      child.reset(node[parts[i]]);
    }
    if (!child.IsMap()) {
      std::string prefix = parts[0];
      for (std::size_t j = 1; j <= i; ++j) prefix += "." + parts[j];
      throw OverrideError(prefix + ": is not a mapping in the base scenario, so " + key +
                          " cannot be set");
    }
    node.reset(child);
  }
  if (parts.back().empty()) throw OverrideError("an empty part in the key path");
  node[parts.back()] = value;
}

// Absolute even when `dir` is not (a sweep file named relative to the working
// directory): a run's scenario lies elsewhere and is run from elsewhere.
void MakeAbsolute(YAML::Node node, const fs::path& dir) {
  if (!node.IsScalar()) return;
  const fs::path given(node.Scalar());
  if (given.is_absolute()) return;
  node = fs::absolute(dir / given).lexically_normal().string();
}

}  // namespace

std::string FlowYaml(const YAML::Node& node) {
  YAML::Emitter out;
  out << YAML::Flow << node;
  return out.c_str();
}

std::string OverriddenScenarioYaml(std::string_view base_text, std::optional<std::uint64_t> seed,
                                   const std::vector<std::string>& keys,
                                   const std::vector<std::string>& values,
                                   const std::optional<std::filesystem::path>& geojson_dir) {
  YAML::Node root = YAML::Load(std::string(base_text));
  if (seed) root["seed"] = *seed;
  for (std::size_t i = 0; i < keys.size(); ++i) SetPath(root, keys[i], YAML::Load(values[i]));
  // Looked up through a const handle: yaml-cpp's non-const operator[] may add the key.
  const YAML::Node& lookup = root;
  if (geojson_dir) {
    if (lookup["area"] && lookup["area"].IsMap() && lookup["area"]["geojson"]) {
      MakeAbsolute(root["area"]["geojson"], *geojson_dir);
    }
    if (lookup["no_fly"]) MakeAbsolute(root["no_fly"], *geojson_dir);
  }
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

}  // namespace fireswarm::run::internal
