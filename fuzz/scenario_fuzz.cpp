// The scenario loader (run/scenario.hpp) on any text. Property: ParseScenario
// returns or throws ScenarioError naming the file; nothing else escapes. Relative
// GeoJSON paths resolve against a directory that does not exist.
#include <string>
#include <string_view>

#include "fireswarm/run/scenario.hpp"
#include "fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace run = fireswarm::run;
  using fireswarm::fuzz::Check;
  constexpr std::string_view kSource = "fuzz_scenario.yaml";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)run::ParseScenario(text, std::string(kSource), "/nonexistent-fireswarm-fuzz");
  } catch (const run::ScenarioError& error) {
    Check(std::string_view(error.what()).starts_with(kSource),
          "a scenario error that does not begin with the file name");
  }
  return 0;
}
