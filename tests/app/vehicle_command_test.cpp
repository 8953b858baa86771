// End-to-end tests of `fireswarm vehicle`: the real executable flying its simulated
// vehicle behind a UDP link on 127.0.0.1, driven by a MasterScheduler (the server's
// radio core) on the wall clock in this process. Every wait has a deadline (poll()
// on the child's stdout, WaitReadable on the link); none sleeps.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "app/fireswarm_process.hpp"
#include "app/run_fireswarm.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/radio/mission_chunks.hpp"
#include "fireswarm/radio/udp_link.hpp"

namespace fireswarm::app {
namespace {

using common::Nanos;
using Clock = std::chrono::steady_clock;
using Json = nlohmann::json;
using std::chrono::seconds;

constexpr std::uint8_t kVehicleId = 3;
constexpr double kTelemetryHz = 5.0;
constexpr common::LatLon kLaunch{46.5, 7.5};
constexpr double kMissionAltitudeM = 60.0;
constexpr double kAirborneAltitudeM = 20.0;
constexpr double kStillAirborneM = 10.0;       // returning, not landed yet
constexpr auto kStartDeadline = seconds(10);   // until the process prints its port
constexpr auto kFlightDeadline = seconds(60);  // until the vehicle climbs past 20 m
constexpr auto kRequestDeadline = seconds(10);
constexpr auto kExitDeadline = seconds(10);

std::string Loopback(std::uint16_t port) {
  return "127.0.0.1:" + std::to_string(port);
}

// The server's radio core on the wall clock over its own UDP link.
class GroundStation {
 public:
  explicit GroundStation(const radio::SchedulerConfig& config)
      : link_("127.0.0.1:0", Loopback(9)), scheduler_(config), start_(Clock::now()) {}

  std::uint16_t port() const { return link_.local_port(); }
  void SendTo(std::uint16_t port) { link_.SetRemote(Loopback(port)); }
  radio::MasterScheduler& scheduler() { return scheduler_; }
  const std::optional<radio::Telemetry>& telemetry() const { return telemetry_; }

  /// Runs the exchange until `done()` holds after a step or `timeout` passes.
  bool RunUntil(const std::function<bool()>& done, Clock::duration timeout) {
    const auto deadline = Clock::now() + timeout;
    std::vector<std::uint8_t> bytes;
    while (Clock::now() < deadline) {
      bytes.clear();
      link_.Receive(Now(), bytes);
      const Nanos now = Now();
      for (const radio::Burst& burst : scheduler_.Step(now, bytes)) {
        link_.Transmit(now, burst.start, burst.bytes);
      }
      for (radio::SchedulerEvent& event : scheduler_.TakeEvents()) Record(event);
      if (done()) return true;
      const Nanos until_deadline = deadline - Clock::now();
      link_.WaitReadable(std::clamp(scheduler_.NextWakeup() - Now(), Nanos{0}, until_deadline));
    }
    return false;
  }

  /// Queues `command` and runs until it is acknowledged or fails; nullopt on timeout.
  std::optional<radio::RequestFinished> Request(const radio::Command& command) {
    const radio::RequestId id = scheduler_.SendCommand(kVehicleId, command);
    return RunUntilFinished(id);
  }

  std::optional<radio::RequestFinished> RunUntilFinished(radio::RequestId id) {
    std::optional<radio::RequestFinished> finished;
    RunUntil(
        [&] {
          for (const radio::RequestFinished& f : finished_) {
            if (f.id == id) finished = f;
          }
          return finished.has_value();
        },
        kRequestDeadline);
    return finished;
  }

 private:
  Nanos Now() const { return Clock::now() - start_; }
  void Record(const radio::SchedulerEvent& event) {
    if (const auto* t = std::get_if<radio::TelemetryReceived>(&event)) telemetry_ = t->telemetry;
    if (const auto* f = std::get_if<radio::RequestFinished>(&event)) finished_.push_back(*f);
  }

  radio::UdpLink link_;
  radio::MasterScheduler scheduler_;
  Clock::time_point start_;
  std::optional<radio::Telemetry> telemetry_;
  std::vector<radio::RequestFinished> finished_;
};

std::optional<radio::CommandResult> CommandResultOf(
    const std::optional<radio::RequestFinished>& finished) {
  if (!finished || finished->status != radio::RequestStatus::kCompleted || !finished->ack) {
    return std::nullopt;
  }
  const auto* ack = std::get_if<radio::CommandAck>(&*finished->ack);
  return ack ? std::optional(ack->result) : std::nullopt;
}

// Three waypoints 80 m around the launch point at the mission altitude.
std::vector<radio::Waypoint> MissionAroundLaunch() {
  const common::LocalFrame frame(kLaunch);
  std::vector<radio::Waypoint> waypoints;
  for (const common::EastNorth point : {common::EastNorth{80.0, 0.0}, common::EastNorth{80.0, 80.0},
                                        common::EastNorth{0.0, 80.0}}) {
    const common::LatLon position = frame.ToGeodetic(point);
    radio::Waypoint waypoint;
    waypoint.lat_deg = position.lat_deg;
    waypoint.lon_deg = position.lon_deg;
    waypoint.altitude_m = kMissionAltitudeM;
    waypoints.push_back(waypoint);
  }
  return waypoints;
}

struct LinkSettings {
  const char* mode;
  const char* checksum;
};

class VehicleCommandFlight : public ::testing::TestWithParam<LinkSettings> {};

TEST_P(VehicleCommandFlight, TakesOffOnAMissionAndAcceptsReturnToLaunch) {
  const LinkSettings settings = GetParam();
  radio::SchedulerConfig config;
  config.mode = *radio::ParseLinkMode(settings.mode);
  config.checksum = *radio::ParseChecksumMode(settings.checksum);
  GroundStation ground(config);
  ground.scheduler().AddVehicle(kVehicleId, kTelemetryHz);

  FireswarmProcess vehicle({"vehicle", "--id", "3", "--udp", "127.0.0.1:0", Loopback(ground.port()),
                            "--mode", settings.mode, "--checksum", settings.checksum, "--lat",
                            std::to_string(kLaunch.lat_deg), "--lon",
                            std::to_string(kLaunch.lon_deg), "--print-bound-port", "--speed", "4",
                            "--duration-s", "120"});
  const std::optional<std::string> port_line = vehicle.ReadLine(Clock::now() + kStartDeadline);
  ASSERT_TRUE(port_line.has_value()) << "no bound_port line";
  ASSERT_EQ(port_line->rfind("bound_port=", 0), 0U) << *port_line;
  ground.SendTo(static_cast<std::uint16_t>(std::stoi(port_line->substr(11))));

  // Telemetry with a GPS fix first: the vehicle refuses to start a mission without one.
  ASSERT_TRUE(ground.RunUntil(
      [&] {
        return ground.telemetry() &&
               (ground.telemetry()->flags & radio::telemetry_flags::kGpsFix) != 0;
      },
      kFlightDeadline))
      << "no telemetry with a GPS fix";

  constexpr std::uint16_t kMissionId = 7;
  std::optional<radio::RequestFinished> last_chunk;
  for (const radio::MissionChunk& chunk : radio::SplitMission(kMissionId, MissionAroundLaunch())) {
    last_chunk = ground.RunUntilFinished(ground.scheduler().SendMissionChunk(kVehicleId, chunk));
    ASSERT_TRUE(last_chunk && last_chunk->status == radio::RequestStatus::kCompleted);
  }
  radio::Command start;
  start.type = radio::CommandType::kStartMission;
  start.mission_id = kMissionId;
  EXPECT_EQ(CommandResultOf(ground.Request(start)), radio::CommandResult::kAccepted);

  EXPECT_TRUE(ground.RunUntil(
      [&] {
        const auto& t = ground.telemetry();
        return t &&
               (t->mode == radio::FlightMode::kTakeoff || t->mode == radio::FlightMode::kSearch) &&
               t->altitude_m > kAirborneAltitudeM;
      },
      kFlightDeadline))
      << "the vehicle did not climb past 20 m in takeoff or search";

  radio::Command return_to_launch;
  return_to_launch.type = radio::CommandType::kReturnToLaunch;
  EXPECT_EQ(CommandResultOf(ground.Request(return_to_launch)), radio::CommandResult::kAccepted);

  // Every turn answered in time: the vehicle answers as bytes arrive, not at its
  // next physics step, and keeps half duplex although UDP takes no airtime. One
  // late answer is tolerated for a loaded machine; a systematic fault misses many.
  EXPECT_LE(ground.scheduler().stats().missed_replies, 1U);
  EXPECT_LE(ground.scheduler().stats().retries, 1U);

  vehicle.Signal(SIGTERM);
  const RunResult run = vehicle.Finish(Clock::now() + kExitDeadline);
  EXPECT_EQ(run.exit_code, 0);
  ASSERT_EQ(run.lines.size(), 1U) << "expected the one-line JSON summary";
  const Json summary = Json::parse(run.lines[0]);
  EXPECT_EQ(summary.at("id"), 3);
  EXPECT_EQ(summary.at("mode"), "return_to_launch");
  EXPECT_GT(summary.at("sim_seconds").get<double>(), 0.0);
  EXPECT_LT(summary.at("sim_seconds").get<double>(), 120.0);
  EXPECT_GT(summary.at("frames_heard").get<int>(), 0);
  EXPECT_GT(summary.at("replies_sent").get<int>(), 0);
  EXPECT_EQ(summary.at("fire_reports_queued"), 0);
  EXPECT_GT(summary.at("final_altitude_m").get<double>(), kStillAirborneM);
}

INSTANTIATE_TEST_SUITE_P(VehicleCommand, VehicleCommandFlight,
                         ::testing::Values(LinkSettings{"slots", "crc16"},
                                           LinkSettings{"poll", "xor"}),
                         [](const auto& test) { return std::string(test.param.mode); });

// --duration-s ends the run by itself, with the summary, also when nobody talks.
TEST(VehicleCommand, StopsAfterTheDurationWithASummary) {
  const RunResult run = RunFireswarm(
      "vehicle --udp 127.0.0.1:0 127.0.0.1:9 --speed 20 --duration-s 2 --checksum crc16");
  EXPECT_EQ(run.exit_code, 0);
  ASSERT_EQ(run.lines.size(), 1U);
  const Json summary = Json::parse(run.lines[0]);
  EXPECT_EQ(summary.at("id"), 1);
  EXPECT_EQ(summary.at("mode"), "idle");
  EXPECT_NEAR(summary.at("sim_seconds").get<double>(), 2.0, 0.02);
  EXPECT_EQ(summary.at("frames_heard"), 0);
}

bool Mentions(const RunResult& run, const std::string& text) {
  return std::any_of(run.lines.begin(), run.lines.end(),
                     [&](const std::string& line) { return line.find(text) != std::string::npos; });
}

TEST(VehicleCommand, BadFlagsExitTwoNamingTheFlag) {
  const std::string udp = " --udp 127.0.0.1:0 127.0.0.1:9";
  struct Case {
    std::string args;
    std::vector<std::string> named;
  };
  for (const Case& c : std::vector<Case>{
           {"vehicle --id 3", {"--udp", "--serial"}},
           {"vehicle" + udp + " --serial /dev/null", {"--udp", "--serial"}},
           {"vehicle --udp 127.0.0.1:0", {"--udp"}},
           {"vehicle --id 0" + udp, {"--id"}},
           {"vehicle --id 255" + udp, {"--id"}},
           {"vehicle --mode token" + udp, {"--mode"}},
           {"vehicle --checksum sum" + udp, {"--checksum"}},
           {"vehicle" + udp, {"--param-file", "--keys"}},
           {"vehicle --param-file /nonexistent/v.json" + udp, {"/nonexistent/v.json.key"}},
           {"vehicle --camera flir" + udp, {"--camera"}},
           {"vehicle --speed 0.5" + udp, {"--speed"}},
           {"vehicle --duration-s -1" + udp, {"--duration-s"}},
           {"vehicle --fire-east-m 5000" + udp, {"--fire-east-m"}},
           {"vehicle --serial /dev/null --print-bound-port", {"--print-bound-port"}},
       }) {
    const RunResult run = RunFireswarm(c.args);
    EXPECT_EQ(run.exit_code, 2) << c.args;
    for (const std::string& flag : c.named) EXPECT_TRUE(Mentions(run, flag)) << c.args;
  }
}

TEST(VehicleCommand, HelpDescribesTheLinks) {
  const RunResult help = RunFireswarm("vehicle --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_TRUE(Mentions(help, "usage: fireswarm vehicle"));
  EXPECT_TRUE(Mentions(help, "--udp"));
  EXPECT_TRUE(Mentions(help, "--serial"));
}

}  // namespace
}  // namespace fireswarm::app
