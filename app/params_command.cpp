// `fireswarm params`: the vehicle's parameter table (the seed's GCS config tab,
// seed 3.3) with each parameter's wire ID, name, default, range and unit; with
// --file, the values a vehicle's parameter file holds (the seed's EEPROM).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/agents/params.hpp"
#include "fireswarm/radio/params.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;
using Json = nlohmann::ordered_json;

}  // namespace

int RunParams(const std::vector<std::string>& args) {
  std::string file;
  bool json = false;
  po::options_description options("options");
  options.add_options()("file", po::value(&file),
                        "a vehicle's parameter file (fireswarm vehicle --param-file): show "
                        "its values beside the defaults")(
      "json", po::bool_switch(&json), "one JSON object per parameter, a line each");
  po::variables_map values;
  if (!ParseCommandLine("params", "[--file PATH] [--json]", options, {}, args, values)) {
    return kExitOk;
  }
  // ParamStore reads the file as the vehicle does, with the same checks; any
  // vehicle's file is accepted here (receiver ID 0).
  std::optional<agents::ParamStore> store;
  if (!file.empty()) {
    if (!std::filesystem::exists(file)) {
      throw UsageError("fireswarm params: --file '" + file + "' does not exist");
    }
    try {
      store.emplace(file, 0);
    } catch (const std::runtime_error& error) {
      throw UsageError(std::string("fireswarm params: ") + error.what());
    }
  }
  if (!json) {
    std::printf("%5s  %-28s %10s %10s %10s %s  %s\n", "id", "name", store ? "value" : "default",
                "min", "max", "unit", "description");
  }
  for (const radio::ParamSpec& spec : radio::ParamTable()) {
    const auto id = static_cast<std::uint16_t>(spec.id);
    const float value = store ? store->Get(spec.id) : spec.default_value;
    if (json) {
      Json line{{"id", id},
                {"name", spec.name},
                {"default", spec.default_value},
                {"min", spec.min},
                {"max", spec.max},
                {"unit", spec.unit},
                {"read_only", spec.read_only},
                {"description", spec.description}};
      if (store) line["value"] = value;
      std::cout << line.dump() << "\n";
    } else {
      std::printf("%5u  %-28.*s %10g %10g %10g %.*s%s  %.*s\n", id,
                  static_cast<int>(spec.name.size()), spec.name.data(), static_cast<double>(value),
                  static_cast<double>(spec.min), static_cast<double>(spec.max),
                  static_cast<int>(spec.unit.size()), spec.unit.data(),
                  spec.read_only ? " (read-only)" : "", static_cast<int>(spec.description.size()),
                  spec.description.data());
    }
  }
  return kExitOk;
}

}  // namespace fireswarm::app
