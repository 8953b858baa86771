// ReplayLog on real LCM log files written with lcm::LogFile.
#include "fireswarm/server/replay.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "command_center_messages.hpp"
#include "common/scratch_dir.hpp"

namespace fireswarm::server {
namespace {

namespace fs = std::filesystem;
using test::Flying;
using ::testing::HasSubstr;

fs::path TempPath(const std::string& name) {
  static const test_support::ScratchDir dir("replay_test");
  const fs::path path = dir.path() / name;
  fs::remove(path);
  return path;
}

template <typename Message>
void Write(lcm::LogFile& log, const std::string& channel, const Message& message) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  ASSERT_EQ(message.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  lcm::LogEvent event{};
  event.timestamp = 1'700'000'000'000'000;  // the writer's clock: not the replay's
  event.channel = channel;
  event.datalen = static_cast<std::int32_t>(bytes.size());
  event.data = bytes.data();
  ASSERT_EQ(log.writeEvent(&event), 0);
}

plan_t Plan(std::int64_t utime) {
  plan_t plan;
  plan.utime = utime;
  plan.mission_id = 1;
  plan.geojson = R"({"type": "FeatureCollection", "features": []})";
  return plan;
}

// A short mission: a plan, drone 1 flying east 10 m a second from 1 s to 5 s
// (written out of order, as two publishers may interleave), a fire track at 3 s,
// and a frame capture on a channel the command center does not read.
fs::path WriteMission(const std::string& name) {
  const fs::path path = TempPath(name);
  lcm::LogFile log(path.string(), "w");
  EXPECT_TRUE(log.good());
  Write(log, "FIRESWARM_PLAN", Plan(500'000));
  for (const int t : {1, 2, 4, 3, 5}) {
    Write(log, "FIRESWARM_VEHICLE_STATE", Flying(1, {10.0 * t, 0.0}, 50.0, t * 1'000'000));
  }
  Write(log, "FIRESWARM_FIRE_TRACKS",
        test::Tracks(3'000'000, {test::Track(2, fire_track_t::STATUS_TENTATIVE, {1})}));
  command_status_t status{};  // LCM's structs leave their numbers uninitialised
  status.utime = 4'500'000;
  status.command_id = 1;
  status.command = operator_command_t::RETURN_ALL;
  status.target_count = 1;
  status.target_ids = {1};
  status.target_states = {command_status_t::STATE_ACKNOWLEDGED};
  Write(log, "FIRESWARM_COMMAND_STATUS", status);
  Write(log, "RADIO_AIR", Plan(0));  // any payload: the channel is skipped, not decoded
  return path;
}

std::string LoadError(const fs::path& path) {
  try {
    ReplayLog::Load(path);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

TEST(ReplayLog, ReadsTheCommandCenterChannelsInTimeOrder) {
  const ReplayLog log = ReplayLog::Load(WriteMission("mission.lcmlog"));
  EXPECT_EQ(log.events().size(), 8U);
  EXPECT_EQ(log.skipped(), 1U);
  EXPECT_EQ(log.warning(), "");
  EXPECT_DOUBLE_EQ(log.start_s(), 0.5);
  EXPECT_DOUBLE_EQ(log.end_s(), 5.0);
  for (std::size_t i = 1; i < log.events().size(); ++i) {
    EXPECT_LE(log.events()[i - 1].time_s, log.events()[i].time_s) << i;
  }
}

TEST(ReplayLog, FeedsTheModelUpToATimeAndSeeksByRebuilding) {
  const ReplayLog log = ReplayLog::Load(WriteMission("feed.lcmlog"));
  CommandCenterConfig config;
  config.source = "replay";
  config.read_only = true;
  CommandCenter center(config);
  std::size_t next = log.Feed(center, 0, 2.5);
  nlohmann::json state = center.State();
  EXPECT_DOUBLE_EQ(state["time_s"].get<double>(), 2.0);
  EXPECT_EQ(state["plan"]["version"], 1);
  EXPECT_EQ(state["vehicles"][0]["trail"].size(), 2U);
  EXPECT_EQ(state["tracks"].size(), 0U);
  next = log.Feed(center, next, 10.0);
  EXPECT_EQ(next, log.events().size());
  state = center.State();
  EXPECT_DOUBLE_EQ(state["time_s"].get<double>(), 5.0);
  EXPECT_EQ(state["vehicles"][0]["trail"].size(), 5U);
  EXPECT_EQ(state["tracks"].size(), 1U);
  EXPECT_EQ(state["commands"][0]["kind"], "return_all");

  // Seek back to 3 s: a fresh model fed from the start.
  CommandCenter sought(config);
  log.Feed(sought, 0, 3.0);
  state = sought.State();
  EXPECT_DOUBLE_EQ(state["time_s"].get<double>(), 3.0);
  EXPECT_EQ(state["vehicles"][0]["trail"].size(), 3U);
  EXPECT_EQ(state["tracks"].size(), 1U);
  EXPECT_EQ(state["commands"].size(), 0U);
}

TEST(ReplayLog, ErrorsNameTheFile) {
  const fs::path missing = TempPath("missing.lcmlog");
  EXPECT_THAT(LoadError(missing), HasSubstr(missing.string() + ": cannot read the LCM log"));

  const fs::path text = TempPath("notes.txt");
  std::ofstream(text) << "these are not LCM events\n";
  EXPECT_THAT(LoadError(text), HasSubstr(text.string() + ": not an LCM log"));

  const fs::path wrong = TempPath("wrong_type.lcmlog");
  {
    lcm::LogFile log(wrong.string(), "w");
    Write(log, "FIRESWARM_VEHICLE_STATE", Plan(1));  // a plan_t where a vehicle_state_t goes
  }
  const std::string why = LoadError(wrong);
  EXPECT_THAT(why, HasSubstr(wrong.string() + ": event 0 on FIRESWARM_VEHICLE_STATE"));
  EXPECT_THAT(why, HasSubstr("does not decode as vehicle_state_t"));

  // A plan whose geojson length is INT32_MIN: refused, never given to the decode.
  const fs::path bad_plan = TempPath("bad_plan.lcmlog");
  {
    plan_t plan{};
    plan.geojson = "{}";
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(plan.getEncodedSize()));
    ASSERT_EQ(plan.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
              static_cast<int>(bytes.size()));
    bytes[kPlanStringsAt] = 0x80;
    bytes[kPlanStringsAt + 1] = bytes[kPlanStringsAt + 2] = bytes[kPlanStringsAt + 3] = 0;
    lcm::LogFile log(bad_plan.string(), "w");
    lcm::LogEvent event{};
    event.channel = kPlanChannel;
    event.datalen = static_cast<std::int32_t>(bytes.size());
    event.data = bytes.data();
    ASSERT_EQ(log.writeEvent(&event), 0);
  }
  EXPECT_THAT(LoadError(bad_plan),
              HasSubstr("event 0 on FIRESWARM_PLAN: the geojson string's length"));
}

TEST(ReplayLog, ALogCutShortReplaysItsWholeEventsAndSaysSo) {
  const fs::path path = WriteMission("cut.lcmlog");
  const std::uintmax_t size = fs::file_size(path);
  fs::resize_file(path, size - 10);  // the last event loses its tail
  const ReplayLog log = ReplayLog::Load(path);
  EXPECT_EQ(log.events().size() + log.skipped(), 8U);
  EXPECT_THAT(log.warning(), HasSubstr("bytes after event 8 hold no event"));
}

}  // namespace
}  // namespace fireswarm::server
