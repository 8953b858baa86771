// The planner's GeoJSON readers (planner/area_io.hpp) on any text: the search area
// (the input as area document; split at the first 0 byte, the rest as no-fly
// document) and launch sites. Property: each returns or throws
// std::invalid_argument naming the document; nothing else escapes.
#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fireswarm/planner/area_io.hpp"
#include "fuzz_check.hpp"

namespace {

constexpr std::string_view kAreaSource = "fuzz_area.geojson";
constexpr std::string_view kNoFlySource = "fuzz_no_fly.geojson";

bool NamesASource(const std::invalid_argument& error) {
  const std::string_view what = error.what();
  return what.find(kAreaSource) != std::string_view::npos ||
         what.find(kNoFlySource) != std::string_view::npos;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace planner = fireswarm::planner;
  using fireswarm::fuzz::Check;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::size_t split = text.find('\0');
  const planner::GeoJsonText area{text.substr(0, split), std::string(kAreaSource)};
  std::optional<planner::GeoJsonText> no_fly;
  if (split != std::string::npos) no_fly = {text.substr(split + 1), std::string(kNoFlySource)};
  try {
    const planner::SearchArea parsed = planner::ParseSearchArea(area, no_fly);
    (void)planner::DefaultLaunchPoint(parsed);
  } catch (const std::invalid_argument& error) {
    Check(NamesASource(error), "an area error that names no document");
  }
  try {
    (void)planner::ParseLaunchSites(area);
  } catch (const std::invalid_argument& error) {
    Check(NamesASource(error), "a launch-site error that names no document");
  }
  return 0;
}
