// report_diff A.json B.json: compares two `fireswarm run` reports with the
// wall-clock fields (wall_seconds, real_time_factor) left out. Prints the first
// differing key path and both values, or "same". Exit 0 when the same, 1 when they
// differ, 2 on bad input (a file that cannot be read or is not JSON).
// scripts/compare-reports.sh uses it to show that a refactoring changed no run.
#include <array>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace {

using Json = nlohmann::json;

// Keys whose values depend on the machine, not on the simulation.
constexpr std::array<std::string_view, 2> kWallClockKeys = {"wall_seconds", "real_time_factor"};

std::optional<Json> Load(const char* path) {
  std::ifstream in(path);
  if (!in) {
    std::cerr << "report_diff: " << path << ": cannot be read\n";
    return std::nullopt;
  }
  try {
    Json j = Json::parse(in);
    if (j.is_object()) {
      for (std::string_view key : kWallClockKeys) {
        j.erase(std::string(key));
      }
    }
    return j;
  } catch (const Json::parse_error& e) {
    std::cerr << "report_diff: " << path << ": not JSON: " << e.what() << "\n";
    return std::nullopt;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: report_diff A.json B.json\n";
    return 2;
  }
  const auto a = Load(argv[1]);
  const auto b = Load(argv[2]);
  if (!a || !b) {
    return 2;
  }
  const Json patch = Json::diff(*a, *b);
  if (patch.empty()) {
    std::cout << "same\n";
    return 0;
  }
  const Json& first = patch.front();
  const std::string path = first.value("path", "");
  std::cout << patch.size() << " difference(s); first: " << first.value("op", "") << " " << path
            << "\n";
  const Json::json_pointer pointer(path);
  std::cout << "  " << argv[1] << ": " << (a->contains(pointer) ? a->at(pointer).dump() : "(none)")
            << "\n  " << argv[2] << ": "
            << (b->contains(pointer) ? b->at(pointer).dump() : "(none)") << "\n";
  return 1;
}
