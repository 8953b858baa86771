// The LCM types through real LCM: encode/decode, memq://, udpm:// on loopback,
// and log files (lcm::LogFile and the file:// provider). No mocks, no sleeps:
// waiting is lcm.handleTimeout() against a deadline.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <random>
#include <string>
#include <vector>

#include "fireswarm/fire_report_t.hpp"
#include "fireswarm/fire_track_list_t.hpp"
#include "fireswarm/fire_track_t.hpp"
#include "fireswarm/mission_status_t.hpp"
#include "fireswarm/operator_command_t.hpp"
#include "fireswarm/radio_frame_t.hpp"
#include "fireswarm/radio_stats_t.hpp"
#include "fireswarm/vehicle_state_t.hpp"

namespace fireswarm {
namespace {

using std::chrono::milliseconds;
constexpr milliseconds kReceiveTimeout{2'000};
constexpr std::int64_t kUtime = 1'700'000'000'123'456;  // 2023-11-14, microseconds

// Every field gets a value distinct from its zero default, so a field lost in
// encoding or decoding changes the re-encoded bytes.
template <typename Message>
Message Sample();

template <>
vehicle_state_t Sample<vehicle_state_t>() {
  vehicle_state_t m{};
  m.utime = kUtime;
  m.receiver_id = 254;
  m.has_position = true;
  m.vehicle_time_ms = 3'600'123;
  m.lat_deg = 47.3977419;
  m.lon_deg = -8.5455938;
  m.altitude_m = 60.5;
  m.velocity_north_mps = 4.25;
  m.velocity_east_mps = -3.5;
  m.velocity_up_mps = 0.75;
  m.roll_deg = -12.5;
  m.pitch_deg = 15.0;
  m.heading_deg = 359.99;
  m.battery_v = 15.2;
  m.battery_percent = 81.0;
  m.flight_mode = vehicle_state_t::MODE_INVESTIGATE;
  m.flags = vehicle_state_t::FLAG_GPS_FIX | vehicle_state_t::FLAG_MISSION_VALID;
  m.pending_reports = 255;
  m.mission_id = 65'535;
  m.waypoint_index = 17;
  m.link_state = vehicle_state_t::LINK_DEGRADED;
  m.telemetry_age_s = 1.25;
  m.missed_replies = 2;
  return m;
}

template <>
fire_report_t Sample<fire_report_t>() {
  fire_report_t m{};
  m.utime = kUtime;
  m.vehicle_id = 7;
  m.report_id = 65'000;
  m.detection_utime = kUtime - 250'000;
  m.lat_deg = 47.40012;
  m.lon_deg = 8.54901;
  m.covariance_m2[0][0] = 16.0;
  m.covariance_m2[0][1] = -2.5;
  m.covariance_m2[1][0] = -2.5;
  m.covariance_m2[1][1] = 9.0;
  m.observer_lat_deg = 47.4;
  m.observer_lon_deg = 8.549;
  m.observer_altitude_m = 80.0;
  m.pixel_count = 42;
  m.peak_temperature_c = 612.5;
  m.confidence = 0.875;
  return m;
}

template <>
fire_track_t Sample<fire_track_t>() {
  fire_track_t m{};
  m.utime = kUtime;
  m.track_id = 3;
  m.status = fire_track_t::STATUS_CONFIRMED;
  m.lat_deg = 47.40011;
  m.lon_deg = 8.54903;
  m.covariance_m2[0][0] = 4.0;
  m.covariance_m2[0][1] = 0.5;
  m.covariance_m2[1][0] = 0.5;
  m.covariance_m2[1][1] = 3.0;
  m.report_count = 5;
  m.vehicle_ids = {2, 7, 254};
  m.vehicle_count = static_cast<std::int16_t>(m.vehicle_ids.size());
  m.first_seen_utime = kUtime - 60'000'000;
  m.last_seen_utime = kUtime - 1'000'000;
  return m;
}

template <>
fire_track_list_t Sample<fire_track_list_t>() {
  fire_track_list_t m{};
  m.utime = kUtime;
  m.tracks.push_back(Sample<fire_track_t>());
  m.tracks.push_back(Sample<fire_track_t>());
  m.tracks[1].track_id = 4;
  m.tracks[1].status = fire_track_t::STATUS_REJECTED;
  m.tracks[1].vehicle_ids = {9};
  m.tracks[1].vehicle_count = 1;
  m.track_count = static_cast<std::int32_t>(m.tracks.size());
  return m;
}

template <>
mission_status_t Sample<mission_status_t>() {
  mission_status_t m{};
  m.utime = kUtime;
  m.state = mission_status_t::STATE_RUNNING;
  m.mission_id = 12;
  m.coverage_fraction = 0.625;
  m.elapsed_s = 431.5;
  m.vehicles_active = 5;
  m.vehicles_lost = 1;
  m.fires_tentative = 2;
  m.fires_confirmed = 3;
  return m;
}

template <>
radio_stats_t Sample<radio_stats_t>() {
  radio_stats_t m{};
  m.utime = kUtime;
  m.window_s = 10.0;
  m.busy_fraction = 0.71;
  m.payload_bytes_per_s = 3'120.5;
  m.frames_sent = 1'000'001;
  m.frames_received = 999'000;
  m.checksum_errors = 17;
  m.collisions = 4;
  m.retries = 23;
  m.timeouts = 9;
  m.vehicle_ids = {1, 2, 200};
  m.telemetry_age_s = {0.5, 1.75, 12.0};
  m.vehicle_count = static_cast<std::int16_t>(m.vehicle_ids.size());
  m.secured = true;
  m.out_of_turn = 80;
  m.auth_failures = {0, 3, 0};
  m.replays = {1, 0, 0};
  m.vehicle_channel = {0, 1, 0};
  m.channel_count = 2;
  m.channel_busy_fraction = {0.71, 0.4};
  m.channel_payload_bytes_per_s = {2'000.0, 1'120.5};
  m.channel_frames_sent = {600'001, 400'000};
  m.channel_frames_received = {599'000, 400'000};
  m.channel_retries = {20, 3};
  m.channel_timeouts = {9, 0};
  m.channel_vehicles = {2, 1};
  m.channel_silent = {false, true};
  return m;
}

template <>
operator_command_t Sample<operator_command_t>() {
  operator_command_t m{};
  m.utime = kUtime;
  m.command = operator_command_t::RETASK_VEHICLE;
  m.target_vehicle = 7;
  m.lat_deg = 47.401;
  m.lon_deg = 8.55;
  m.radius_m = 35.0;
  m.reason = "smoke seen from the road, \xC3\xA9tage 2";  // UTF-8 survives
  return m;
}

template <>
radio_frame_t Sample<radio_frame_t>() {
  radio_frame_t m{};
  m.utime = kUtime;
  m.transmitter_radio = 3;
  m.transmitter_receiver_id = 0;
  m.start_us = 12'345'678;
  m.end_us = 12'349'844;
  m.collided = true;
  m.bytes = {0x70, 0x96, 0xAC, 0x07, 0x01, 0x01, 0x00, 0xFF, 0x80};
  m.byte_count = static_cast<std::int32_t>(m.bytes.size());
  return m;
}

template <typename Message>
std::vector<std::uint8_t> Encode(const Message& message) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  EXPECT_EQ(message.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  return bytes;
}

// Collects every message of one type that arrives on one channel.
template <typename Message>
class Inbox {
 public:
  Inbox(lcm::LCM& lcm, const std::string& channel)
      : lcm_(lcm), subscription_(lcm.subscribe(channel, &Inbox::OnMessage, this)) {}
  ~Inbox() { lcm_.unsubscribe(subscription_); }
  Inbox(const Inbox&) = delete;
  Inbox& operator=(const Inbox&) = delete;

  const std::vector<Message>& messages() const { return messages_; }
  bool empty() const { return messages_.empty(); }

 private:
  void OnMessage(const lcm::ReceiveBuffer*, const std::string&, const Message* message) {
    messages_.push_back(*message);
  }

  lcm::LCM& lcm_;
  lcm::Subscription* subscription_;
  std::vector<Message> messages_;
};

// Dispatches messages until `done()` holds. False on an LCM error or at `timeout`.
template <typename Done>
bool HandleUntil(lcm::LCM& lcm, Done done, milliseconds timeout = kReceiveTimeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    const auto left =
        std::chrono::duration_cast<milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0 || lcm.handleTimeout(static_cast<int>(left.count())) < 0) return false;
  }
  return true;
}

// ---- every type: encode/decode and memq:// ---------------------------------------

template <typename Message>
class LcmType : public ::testing::Test {};

using AllTypes =
    ::testing::Types<vehicle_state_t, fire_report_t, fire_track_t, fire_track_list_t,
                     mission_status_t, radio_stats_t, operator_command_t, radio_frame_t>;
TYPED_TEST_SUITE(LcmType, AllTypes);

TYPED_TEST(LcmType, DecodeOfEncodeKeepsEveryField) {
  const TypeParam sent = Sample<TypeParam>();
  const std::vector<std::uint8_t> bytes = Encode(sent);
  TypeParam decoded{};
  ASSERT_EQ(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  EXPECT_EQ(Encode(decoded), bytes);
  EXPECT_EQ(decoded.utime, kUtime);
}

TYPED_TEST(LcmType, DecodeOfTruncatedBytesFails) {
  const std::vector<std::uint8_t> bytes = Encode(Sample<TypeParam>());
  TypeParam decoded{};
  EXPECT_LT(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size()) - 1), 0);
}

TYPED_TEST(LcmType, PublishedOverMemqArrivesIntact) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  const std::string channel = std::string("TEST_") + TypeParam::getTypeName();
  Inbox<TypeParam> inbox(lcm, channel);
  const TypeParam sent = Sample<TypeParam>();
  ASSERT_EQ(lcm.publish(channel, &sent), 0);
  ASSERT_TRUE(HandleUntil(lcm, [&] { return !inbox.empty(); }));
  ASSERT_EQ(inbox.messages().size(), 1U);
  EXPECT_EQ(Encode(inbox.messages()[0]), Encode(sent));
}

// ---- fields worth reading back one by one -----------------------------------------

template <typename Message>
Message RoundTrip(const Message& message) {
  const std::vector<std::uint8_t> bytes = Encode(message);
  Message decoded{};
  EXPECT_GT(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
  return decoded;
}

TEST(LcmTypeFields, NestedTracksArraysAndCovarianceSurvive) {
  const fire_track_list_t list = RoundTrip(Sample<fire_track_list_t>());
  ASSERT_EQ(list.track_count, 2);
  ASSERT_EQ(list.tracks.size(), 2U);
  EXPECT_EQ(list.tracks[0].vehicle_ids, (std::vector<std::int16_t>{2, 7, 254}));
  EXPECT_EQ(list.tracks[0].status, fire_track_t::STATUS_CONFIRMED);
  EXPECT_EQ(list.tracks[1].status, fire_track_t::STATUS_REJECTED);
  EXPECT_DOUBLE_EQ(list.tracks[0].covariance_m2[0][1], 0.5);
  EXPECT_DOUBLE_EQ(list.tracks[0].lat_deg, 47.40011);
}

TEST(LcmTypeFields, StringsBytesAndFlagsSurvive) {
  const operator_command_t command = RoundTrip(Sample<operator_command_t>());
  EXPECT_EQ(command.reason, Sample<operator_command_t>().reason);
  EXPECT_EQ(command.command, operator_command_t::RETASK_VEHICLE);

  const radio_frame_t frame = RoundTrip(Sample<radio_frame_t>());
  EXPECT_EQ(frame.bytes, Sample<radio_frame_t>().bytes);
  EXPECT_TRUE(frame.collided);

  const vehicle_state_t state = RoundTrip(Sample<vehicle_state_t>());
  EXPECT_EQ(state.receiver_id, 254);
  EXPECT_TRUE(state.has_position);
  EXPECT_EQ(state.mission_id, 65'535);
  EXPECT_EQ(state.flags & vehicle_state_t::FLAG_GPS_FIX, vehicle_state_t::FLAG_GPS_FIX);
  EXPECT_DOUBLE_EQ(state.lon_deg, -8.5455938);
}

// ---- udpm:// on loopback -------------------------------------------------------

constexpr const char* kNoMulticastRoute =
    "udpm:// needs a multicast route and this machine has none; as root run "
    "`ip link set lo up && ip route add 224.0.0.0/4 dev lo`";

// A random number of this process, so parallel test runs use their own port and channel.
unsigned Nonce() {
  return std::random_device{}() ^ static_cast<unsigned>(getpid());
}

TEST(LcmUdpm, VehicleStateCrossesLoopback) {
  const unsigned nonce = Nonce();
  const std::string url =
      "udpm://239.255.76.67:" + std::to_string(20'000 + nonce % 40'000U) + "?ttl=0";
  lcm::LCM publisher(url);
  lcm::LCM subscriber(url);
  if (!publisher.good() || !subscriber.good()) GTEST_SKIP() << kNoMulticastRoute;
  const std::string channel = "TEST_VEHICLE_STATE_" + std::to_string(nonce);
  Inbox<vehicle_state_t> inbox(subscriber, channel);

  // The receive socket may join the group after the first publish: publish again
  // each round until something arrives.
  const vehicle_state_t sent = Sample<vehicle_state_t>();
  const auto arrived = [&] { return !inbox.empty(); };
  for (int round = 0; round < 20 && !arrived(); ++round) {
    if (publisher.publish(channel, &sent) != 0) GTEST_SKIP() << kNoMulticastRoute;
    HandleUntil(subscriber, arrived, milliseconds(100));
  }
  // The provider came up, so a route exists: silence now is a failure, not a skip.
  ASSERT_FALSE(inbox.empty()) << "udpm:// provider is up but nothing arrived within 2 s";
  EXPECT_EQ(Encode(inbox.messages()[0]), Encode(sent));
}

// ---- log files -----------------------------------------------------------------

class LcmLog : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string dir = ::testing::TempDir() + "lcmtypes_log_XXXXXX";
    ASSERT_NE(mkdtemp(dir.data()), nullptr);
    dir_ = dir;
    path_ = (dir_ / "capture.lcmlog").string();
  }
  void TearDown() override {
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }

  // Writes one event per kChannels entry, 1 ms apart: two vehicles, a report, a frame.
  void WriteLog() {
    lcm::LogFile log(path_, "w");
    ASSERT_TRUE(log.good());
    vehicle_state_t second_vehicle = Sample<vehicle_state_t>();
    second_vehicle.receiver_id = 8;
    std::vector<std::uint8_t> payloads[] = {
        // not const: LogEvent::data is void*
        Encode(Sample<vehicle_state_t>()), Encode(Sample<fire_report_t>()), Encode(second_vehicle),
        Encode(Sample<radio_frame_t>())};
    for (std::size_t i = 0; i < std::size(payloads); ++i) {
      lcm::LogEvent event{};
      event.eventnum = static_cast<std::int64_t>(i);
      event.timestamp = kUtime + static_cast<std::int64_t>(i) * 1'000;
      event.channel = kChannels[i];
      event.datalen = static_cast<std::int32_t>(payloads[i].size());
      event.data = payloads[i].data();
      ASSERT_EQ(log.writeEvent(&event), 0);
    }
  }

  static constexpr const char* kChannels[] = {"VEHICLE_STATE", "FIRE_REPORT", "VEHICLE_STATE",
                                              "RADIO_FRAME"};
  std::filesystem::path dir_;
  std::string path_;
};

template <typename Message>
Message Decode(const lcm::LogEvent& event) {
  Message message{};
  EXPECT_EQ(message.decode(event.data, 0, event.datalen), event.datalen) << event.channel;
  return message;
}

TEST_F(LcmLog, LogFileReadsBackEveryEventInOrder) {
  ASSERT_NO_FATAL_FAILURE(WriteLog());
  lcm::LogFile log(path_, "r");
  ASSERT_TRUE(log.good());
  std::vector<std::string> channels;
  while (const lcm::LogEvent* event = log.readNextEvent()) {
    EXPECT_EQ(event->timestamp, kUtime + static_cast<std::int64_t>(channels.size()) * 1'000);
    channels.push_back(event->channel);
    if (event->channel == "VEHICLE_STATE") {
      const vehicle_state_t state = Decode<vehicle_state_t>(*event);
      EXPECT_EQ(state.receiver_id, channels.size() == 1 ? 254 : 8);
    } else if (event->channel == "FIRE_REPORT") {
      EXPECT_DOUBLE_EQ(Decode<fire_report_t>(*event).peak_temperature_c, 612.5);
    } else {
      EXPECT_EQ(Decode<radio_frame_t>(*event).bytes, Sample<radio_frame_t>().bytes);
    }
  }
  EXPECT_EQ(channels, std::vector<std::string>(std::begin(kChannels), std::end(kChannels)));
}

TEST_F(LcmLog, FileProviderReplaysEventsToSubscribers) {
  ASSERT_NO_FATAL_FAILURE(WriteLog());
  lcm::LCM replay("file://" + path_ + "?mode=r");
  ASSERT_TRUE(replay.good());
  Inbox<vehicle_state_t> states(replay, "VEHICLE_STATE");
  Inbox<fire_report_t> reports(replay, "FIRE_REPORT");
  Inbox<radio_frame_t> frames(replay, "RADIO_FRAME");
  ASSERT_TRUE(HandleUntil(replay, [&] {
    return states.messages().size() == 2 && reports.messages().size() == 1 &&
           frames.messages().size() == 1;
  }));
  EXPECT_EQ(states.messages()[0].receiver_id, 254);
  EXPECT_EQ(states.messages()[1].receiver_id, 8);
  EXPECT_EQ(reports.messages()[0].report_id, 65'000);
  EXPECT_TRUE(frames.messages()[0].collided);
}

}  // namespace
}  // namespace fireswarm
