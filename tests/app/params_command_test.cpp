// `fireswarm params`: the parameter table, and a vehicle's parameter file.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/run_fireswarm.hpp"
#include "fireswarm/agents/params.hpp"
#include "fireswarm/radio/params.hpp"

namespace fireswarm::app {
namespace {

using ParamsCommand = CommandTest;

// The JSON lines of a run, parsed.
std::vector<nlohmann::json> JsonLines(const RunResult& run) {
  std::vector<nlohmann::json> lines;
  for (const std::string& line : run.lines) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

TEST_F(ParamsCommand, ListsEveryParameterWithItsRange) {
  const RunResult run = RunFireswarm("params --json");
  ASSERT_EQ(run.exit_code, 0);
  const std::vector<nlohmann::json> lines = JsonLines(run);
  ASSERT_EQ(lines.size(), radio::ParamTable().size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const radio::ParamSpec& spec = radio::ParamTable()[i];
    EXPECT_EQ(lines[i]["id"], static_cast<int>(spec.id));
    EXPECT_EQ(lines[i]["name"], std::string(spec.name));
    EXPECT_FLOAT_EQ(lines[i]["default"].get<float>(), spec.default_value);
    EXPECT_FLOAT_EQ(lines[i]["min"].get<float>(), spec.min);
    EXPECT_FLOAT_EQ(lines[i]["max"].get<float>(), spec.max);
    EXPECT_FALSE(lines[i].contains("value"));
  }
  const RunResult table = RunFireswarm("params");
  EXPECT_EQ(table.exit_code, 0);
  EXPECT_EQ(table.lines.size(), radio::ParamTable().size() + 1);  // a header line
}

TEST_F(ParamsCommand, ShowsTheValuesOfAVehiclesFile) {
  const std::string file = PathOf("vehicle_3.json");
  {
    agents::ParamStore store(file, 3);
    ASSERT_EQ(store.Write(static_cast<std::uint16_t>(radio::ParamId::kCruiseSpeedMps), 5.5F).status,
              radio::ParamStatus::kOk);
  }
  const RunResult run = RunFireswarm("params --json --file '" + file + "'");
  ASSERT_EQ(run.exit_code, 0);
  int checked = 0;
  for (const nlohmann::json& line : JsonLines(run)) {
    const float expected =
        line["name"] == "nav.cruise_speed_mps" ? 5.5F : line["default"].get<float>();
    EXPECT_FLOAT_EQ(line["value"].get<float>(), expected) << line["name"];
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(radio::ParamTable().size()));
}

TEST_F(ParamsCommand, ABadFileExitsTwoNamingIt) {
  const std::string file = PathOf("corrupt.json");
  std::ofstream(file)
      << R"({"format":"fireswarm-params","version":1,"vehicle":3,"params":{"pid.roll.kp":"x"}})";
  const RunResult corrupt = RunFireswarm("params --file '" + file + "'");
  EXPECT_EQ(corrupt.exit_code, 2);
  ASSERT_FALSE(corrupt.lines.empty());
  EXPECT_NE(corrupt.lines.back().find(file), std::string::npos) << corrupt.lines.back();
  EXPECT_NE(corrupt.lines.back().find("pid.roll.kp"), std::string::npos) << corrupt.lines.back();
  const RunResult missing = RunFireswarm("params --file '" + PathOf("none.json") + "'");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.lines.back().find("--file"), std::string::npos);
}

}  // namespace
}  // namespace fireswarm::app
