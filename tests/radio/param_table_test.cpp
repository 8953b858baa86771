// The parameter catalogue (radio/params.hpp): unique IDs and names, defaults
// inside their ranges, look-ups by wire ID and by name.
#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fireswarm/radio/params.hpp"

namespace fireswarm::radio {
namespace {

TEST(ParamTable, IdsAndNamesAreUniqueAndDefaultsInRange) {
  std::set<std::uint16_t> ids;
  std::set<std::string_view> names;
  for (const ParamSpec& spec : ParamTable()) {
    EXPECT_TRUE(ids.insert(static_cast<std::uint16_t>(spec.id)).second) << spec.name;
    EXPECT_TRUE(names.insert(spec.name).second) << spec.name;
    EXPECT_LE(spec.min, spec.default_value) << spec.name;
    EXPECT_LE(spec.default_value, spec.max) << spec.name;
    EXPECT_FALSE(spec.description.empty()) << spec.name;
  }
  EXPECT_EQ(ParamTable().size(), 36U + 5U + 6U + 1U + 4U + 1U);
}

TEST(ParamTable, FindsByIdAndByName) {
  const ParamSpec* by_id = FindParam(std::uint16_t{54});
  ASSERT_NE(by_id, nullptr);
  EXPECT_EQ(by_id->id, ParamId::kCrossTrackILimit);
  EXPECT_EQ(by_id->name, "pid.cross_track.i_limit");
  const ParamSpec* by_name = FindParam(std::string_view("investigate.radius_m"));
  ASSERT_NE(by_name, nullptr);
  EXPECT_EQ(by_name->id, ParamId::kLoiterRadiusM);
  EXPECT_EQ(&SpecOf(ParamId::kLoiterRadiusM), by_name);
  EXPECT_EQ(FindParam(std::uint16_t{7}), nullptr);
  EXPECT_EQ(FindParam(std::string_view("pid.roll")), nullptr);
  EXPECT_TRUE(SpecOf(ParamId::kFirmwareVersion).read_only);
  EXPECT_THROW(SpecOf(static_cast<ParamId>(999)), std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::radio
