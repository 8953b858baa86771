// `fireswarm radio-bench`: N vehicles and the server on one simulated half-duplex
// channel; prints what the link delivers, as a table or one JSON object.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "air_capture.hpp"
#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/bench/radio_bench.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/messages.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;
using bench::RadioBenchConfig;
using bench::RadioBenchResult;

constexpr const char* kName = "radio-bench";
constexpr double kMaxTurnaroundMs = 65.535;  // u16 microseconds in a SlotSchedule
using Milliseconds = std::chrono::duration<double, std::milli>;

struct Flags {
  int vehicles = 10;
  int channels = 1;
  double seconds = 60.0;
  double drain_seconds = 30.0;
  int baud = 57'600;
  double turnaround_ms = 5.0;
  double loss = 0.0;
  double bit_error_rate = 0.0;
  std::string mode = "slots";
  std::string checksum = "crc16";
  std::uint64_t seed = 1;
  double report_rate = 2.0;
  double telemetry_hz = 1.0;
  int mission_waypoints = 0;
  bool json = false;
  std::string capture;  // raw air capture path, empty = none
  std::string lcm_log;  // radio_frame_t LCM log path, empty = none
};

[[noreturn]] void BadFlag(const std::string& flag, const std::string& requirement,
                          const std::string& got) {
  throw UsageError("fireswarm radio-bench: --" + flag + " must be " + requirement + ", got '" +
                   got + "'");
}

constexpr int kTableDecimals = 3;

template <typename T>
std::string Text(T value) {
  std::ostringstream out;
  if constexpr (std::is_floating_point_v<T>) out << std::fixed << std::setprecision(kTableDecimals);
  out << value;
  return out.str();
}

// RadioBenchConfig field -> the flag that sets it, so Validate()'s messages name flags.
constexpr std::array<std::pair<const char*, const char*>, 11> kFlagOfField{{
    {"vehicles", "vehicles"},
    {"channels", "channels"},
    {"seconds", "seconds"},
    {"drain_seconds", "drain-seconds"},
    {"baud", "baud"},
    {"turnaround", "turnaround-ms"},
    {"loss", "loss"},
    {"bit_error_rate", "bit-error-rate"},
    {"reports_per_minute", "report-rate"},
    {"telemetry_hz", "telemetry-hz"},
    {"mission_waypoints", "mission-waypoints"},
}};

// "RadioBenchConfig.<field> must be ..." -> "--<flag> must be ...".
std::string InFlagTerms(std::string message) {
  constexpr std::string_view kPrefix = "RadioBenchConfig.";
  for (const auto& [field, flag] : kFlagOfField) {
    const std::string config_name = std::string(kPrefix) + field + " ";
    if (message.rfind(config_name, 0) == 0) {
      return "--" + std::string(flag) + " " + message.substr(config_name.size());
    }
  }
  return message;
}

// The ranges live in RadioBenchConfig::Validate(); here only what a flag needs
// before it can become a config value.
RadioBenchConfig ToConfig(const Flags& f) {
  const auto mode = radio::ParseLinkMode(f.mode);
  if (!mode) BadFlag("mode", "poll or slots", f.mode);
  const auto checksum = radio::ParseChecksumMode(f.checksum);
  if (!checksum) BadFlag("checksum", "xor, crc16 or secure", f.checksum);
  // The scheduler sends the turnaround as u16 microseconds in a SlotSchedule.
  if (!(f.turnaround_ms >= 0 && f.turnaround_ms <= kMaxTurnaroundMs)) {
    BadFlag("turnaround-ms", "in [0, 65.535]", Text(f.turnaround_ms));
  }
  RadioBenchConfig c;
  c.vehicles = f.vehicles;
  c.channels = f.channels;
  c.seconds = f.seconds;
  c.drain_seconds = f.drain_seconds;
  c.mode = *mode;
  c.checksum = *checksum;
  c.baud = f.baud;
  c.turnaround = std::chrono::round<common::Nanos>(Milliseconds(f.turnaround_ms));
  c.loss = f.loss;
  c.bit_error_rate = f.bit_error_rate;
  c.reports_per_minute = f.report_rate;
  c.telemetry_hz = f.telemetry_hz;
  c.mission_waypoints = f.mission_waypoints;
  c.seed = f.seed;
  try {
    c.Validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError("fireswarm radio-bench: " + InFlagTerms(e.what()));
  }
  return c;
}

nlohmann::ordered_json ToJson(const RadioBenchConfig& c, const RadioBenchResult& r,
                              double wall_seconds) {
  nlohmann::ordered_json j;
  j["mode"] = std::string(radio::ToString(c.mode));
  j["checksum"] = std::string(radio::ToString(c.checksum));
  j["vehicles"] = c.vehicles;
  j["channels"] = c.channels;
  j["baud"] = c.baud;
  j["turnaround_ms"] = Milliseconds(c.turnaround).count();
  j["loss"] = c.loss;
  j["bit_error_rate"] = c.bit_error_rate;
  j["report_rate_per_min"] = c.reports_per_minute;
  j["seed"] = c.seed;
  j["seconds"] = c.seconds;
  j["sim_seconds"] = r.sim_seconds;
  j["busy_fraction"] = r.busy_fraction;
  j["payload_bytes_per_s"] = r.payload_bytes_per_s;
  j["telemetry_hz_min"] = r.telemetry_hz_min;
  j["telemetry_hz_mean"] = r.telemetry_hz_mean;
  j["telemetry_age_p50_s"] = r.telemetry_age_p50_s;
  j["telemetry_age_p99_s"] = r.telemetry_age_p99_s;
  j["telemetry_age_max_s"] = r.telemetry_age_max_s;
  j["report_latency_p50_s"] = r.report_latency_p50_s;
  j["report_latency_p99_s"] = r.report_latency_p99_s;
  j["report_latency_max_s"] = r.report_latency_max_s;
  j["reports_sent"] = r.reports_sent;
  j["reports_received"] = r.reports_received;
  j["reports_lost"] = r.reports_lost;
  j["duplicate_reports"] = r.duplicate_reports;
  j["transmissions"] = r.transmissions;
  j["collisions"] = r.collisions;
  j["retries"] = r.retries;
  j["missed_replies"] = r.missed_replies;
  j["checksum_errors"] = r.checksum_errors;
  j["bursts"] = r.bursts;
  j["turns_granted"] = r.slots_granted;
  j["requests_completed"] = r.requests_completed;
  j["requests_failed"] = r.requests_failed;
  j["mission_waypoints"] = c.mission_waypoints;
  j["mission_upload_s"] = r.mission_upload_s ? nlohmann::ordered_json(*r.mission_upload_s)
                                             : nlohmann::ordered_json(nullptr);
  nlohmann::ordered_json per_vehicle = nlohmann::ordered_json::array();
  for (const bench::VehicleLinkFigures& v : r.per_vehicle) {
    per_vehicle.push_back({{"receiver_id", v.vehicle},
                           {"telemetry_hz", v.telemetry_hz},
                           {"telemetry_age_p50_s", v.telemetry_age_p50_s},
                           {"telemetry_age_p99_s", v.telemetry_age_p99_s},
                           {"reports_sent", v.reports_sent}});
  }
  j["per_vehicle"] = per_vehicle;
  nlohmann::ordered_json per_channel = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < r.per_channel.size(); ++k) {
    const bench::ChannelFigures& ch = r.per_channel[k];
    per_channel.push_back({{"channel", k},
                           {"vehicles", ch.vehicles},
                           {"busy_fraction", ch.busy_fraction},
                           {"server_step_s", ch.server_step_s}});
  }
  j["per_channel"] = per_channel;
  j["wall_seconds"] = wall_seconds;
  return j;
}

void PrintTable(const RadioBenchConfig& c, const RadioBenchResult& r, double wall_seconds) {
  std::cout << std::fixed << std::setprecision(kTableDecimals);
  std::cout << "radio-bench: " << c.vehicles << " vehicles on " << c.channels << " channel"
            << (c.channels == 1 ? "" : "s") << ", " << radio::ToString(c.mode)
            << " mode, " << c.baud << " baud, turnaround " << Milliseconds(c.turnaround).count()
            << " ms, loss " << c.loss << ", " << radio::ToString(c.checksum) << ", " << c.seconds
            << " s (+ drain)\n";
  const auto row = [](const char* name, const auto& value) {
    std::cout << "  " << std::left << std::setw(34) << name << value << "\n";
  };
  row(c.channels == 1 ? "channel busy fraction" : "busiest channel busy fraction",
      r.busy_fraction);
  row("useful payload bytes/s", r.payload_bytes_per_s);
  row("telemetry rate min / mean (Hz)",
      Text(r.telemetry_hz_min) + " / " + Text(r.telemetry_hz_mean));
  row("telemetry age p50 / p99 (s)",
      Text(r.telemetry_age_p50_s) + " / " + Text(r.telemetry_age_p99_s));
  const auto stalest = std::max_element(
      r.per_vehicle.begin(), r.per_vehicle.end(),
      [](const auto& a, const auto& b) { return a.telemetry_age_p99_s < b.telemetry_age_p99_s; });
  if (stalest != r.per_vehicle.end()) {
    row("stalest vehicle age p50 / p99 (s)", Text(stalest->telemetry_age_p50_s) + " / " +
                                                 Text(stalest->telemetry_age_p99_s) + " (vehicle " +
                                                 Text(int{stalest->vehicle}) + ", " +
                                                 Text(stalest->telemetry_hz) + " Hz)");
  }
  row("report latency p50 / p99 (s)",
      Text(r.report_latency_p50_s) + " / " + Text(r.report_latency_p99_s));
  row("reports sent / lost", Text(r.reports_sent) + " / " + Text(r.reports_lost));
  row("collisions", r.collisions);
  row("retries", r.retries);
  row("missed replies", r.missed_replies);
  row("frames with checksum errors", r.checksum_errors);
  if (c.mission_waypoints > 0) {
    row("mission upload (s)", r.mission_upload_s ? Text(*r.mission_upload_s) : "failed");
  }
  if (r.per_channel.size() > 1) {
    for (std::size_t k = 0; k < r.per_channel.size(); ++k) {
      const bench::ChannelFigures& ch = r.per_channel[k];
      std::cout << "  channel " << k << ": " << ch.vehicles << " vehicles, busy "
                << Text(ch.busy_fraction) << ", server step CPU " << Text(ch.server_step_s)
                << " s\n";
    }
  }
  row("simulated / wall time (s)", Text(r.sim_seconds) + " / " + Text(wall_seconds));
}

}  // namespace

int RunRadioBench(const std::vector<std::string>& args) {
  Flags f;
  po::options_description options("radio-bench options");
  auto add = options.add_options();
  add("vehicles", po::value(&f.vehicles)->default_value(f.vehicles), "number of vehicles, 1..254");
  add("channels", po::value(&f.channels)->default_value(f.channels),
      "radio channels (separate frequencies, one server modem each), 1..16; vehicles in "
      "balanced groups");
  add("seconds", po::value(&f.seconds)->default_value(f.seconds), "simulated seconds of reports");
  add("drain-seconds", po::value(&f.drain_seconds)->default_value(f.drain_seconds),
      "at most this long afterwards for queued reports to arrive");
  add("baud", po::value(&f.baud)->default_value(f.baud), "serial baud rate, 8N1");
  add("turnaround-ms", po::value(&f.turnaround_ms)->default_value(f.turnaround_ms),
      "radio receive-to-transmit turnaround");
  add("loss", po::value(&f.loss)->default_value(f.loss), "loss probability per reception");
  add("bit-error-rate", po::value(&f.bit_error_rate)->default_value(f.bit_error_rate),
      "probability each received bit is flipped");
  add("mode", po::value(&f.mode)->default_value(f.mode), "poll or slots");
  add("checksum", po::value(&f.checksum)->default_value(f.checksum),
      "xor, crc16 or secure (AES-256-GCM under simulation keys)");
  add("seed", po::value(&f.seed)->default_value(f.seed), "random seed");
  add("report-rate", po::value(&f.report_rate)->default_value(f.report_rate),
      "fire reports per vehicle per minute (Poisson)");
  add("telemetry-hz", po::value(&f.telemetry_hz)->default_value(f.telemetry_hz),
      "telemetry rate per vehicle");
  add("mission-waypoints", po::value(&f.mission_waypoints)->default_value(f.mission_waypoints),
      "upload a mission of this many waypoints to every vehicle at the start");
  add("json", po::bool_switch(&f.json), "print one JSON object instead of the table");
  add("capture", po::value(&f.capture)->default_value("", "none")->value_name("FILE"),
      "write the raw bytes on the air (transmissions not lost to collisions) to this file, "
      "for 'fireswarm radio-decode'");
  add("lcm-log", po::value(&f.lcm_log)->default_value("", "none")->value_name("FILE"),
      "write every transmission as a fireswarm.radio_frame_t event (channel RADIO_AIR) to this "
      "LCM log, for lcm-logplayer");
  po::variables_map values;
  if (!ParseCommandLine(kName, "[options]", options, {}, args, values)) return kExitOk;
  const RadioBenchConfig config = ToConfig(f);
  CheckOutputFlags(kName, {{"capture", f.capture}, {"lcm-log", f.lcm_log}}, {});

  std::optional<AirCapture> capture;
  if (!f.capture.empty() || !f.lcm_log.empty()) {
    const auto path_or_none = [](const std::string& p) {
      return p.empty() ? std::nullopt : std::optional<std::string>(p);
    };
    try {
      capture.emplace(path_or_none(f.capture), path_or_none(f.lcm_log));
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("fireswarm radio-bench: ") + e.what());
    }
  }
  bench::AirObserver observer;
  if (capture) observer = [&capture](const radio::AirRecord& r) { capture->Record(r); };

  const auto wall_start = std::chrono::steady_clock::now();
  const RadioBenchResult result = bench::RunRadioBench(config, observer);
  const double wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  if (capture) capture->Commit();
  if (f.json) {
    std::cout << ToJson(config, result, wall_seconds).dump() << "\n";
  } else {
    PrintTable(config, result, wall_seconds);
  }
  return kExitOk;
}

}  // namespace fireswarm::app
