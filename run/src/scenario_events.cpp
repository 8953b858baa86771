// The scenario's `fires`, `random_fires`, `distractors` and `faults`.
#include <array>
#include <string>

#include "scenario_parts.hpp"

namespace fireswarm::run {
namespace {

using internal::Field;
using internal::Mapping;
using internal::Range;

// Indexed by the enums' values (scenario.hpp lists them in this order).
constexpr std::array<std::string_view, 11> kFaultKindNames{
    "stream_cut",   "frozen",         "bias",           "extra_noise", "ballast",    "total_loss",
    "radio_silent", "server_restart", "vehicle_reboot", "gps_loss",    "radio_burst"};
constexpr std::array<std::string_view, 4> kFaultSensorNames{"gps", "baro", "attitude", "battery"};

bool IsSensorFault(FaultKind kind) {
  return kind == FaultKind::kStreamCut || kind == FaultKind::kFrozen || kind == FaultKind::kBias ||
         kind == FaultKind::kExtraNoise;
}

FireSpec ReadFire(const Field& field, const Scenario& scenario) {
  const Mapping fire(field, {"lat", "lon", "start_s", "radius_m"});
  FireSpec out;
  out.position = internal::ReadLatLon(fire);
  out.start_s = fire.Number("start_s", out.start_s, Range{0.0, scenario.duration_s, false, true});
  out.radius_m = fire.Number("radius_m", out.radius_m, Range{0.0, internal::kMaxFireRadiusM, true});
  if (!internal::InSearchArea(scenario.area, out.position)) {
    field.Fail("lies outside the search area (the area minus its no-fly zones)");
  }
  return out;
}

RandomFiresSpec ReadRandomFires(const Field& field, std::uint64_t scenario_seed) {
  const Mapping random(field, {"count", "seed", "radius_m", "min_spacing_m"});
  RandomFiresSpec out;
  out.count = static_cast<int>(random.Required("count").Integer(1, internal::kMaxRandomFires));
  const std::optional<Field> seed = random.Find("seed");
  out.seed = seed ? seed->Unsigned64() : scenario_seed;
  out.radius_m =
      random.Number("radius_m", out.radius_m, Range{0.0, internal::kMaxFireRadiusM, true});
  out.min_spacing_m =
      random.Number("min_spacing_m", out.min_spacing_m, Range{0.0, internal::kMaxFireSpacingM});
  return out;
}

DistractorSpec ReadDistractor(const Field& field, const planner::SearchArea& area) {
  const Mapping distractor(field, {"lat", "lon", "radius_m", "temp_c"});
  DistractorSpec out;
  out.position = internal::ReadLatLon(distractor);
  internal::CheckNearArea(field, area, out.position);
  out.radius_m = distractor.Number("radius_m", out.radius_m,
                                   Range{0.0, internal::kMaxDistractorRadiusM, true});
  out.temp_c = distractor.Number(
      "temp_c", out.temp_c, Range{internal::kMinDistractorTempC, internal::kMaxDistractorTempC});
  return out;
}

template <std::size_t N>
std::array<double, N> ReadVector(const Field& field, const Range& range) {
  const std::vector<Field> values = field.Elements();
  if (values.size() != N) {
    field.Fail("must be a list of " + std::to_string(N) + " numbers, got " +
               std::to_string(values.size()));
  }
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = values[i].Number(range);
  return out;
}

// The keys that only some kinds take: refused on the others, required where needed.
void ReadFaultParameters(const Mapping& fault, FaultSpec& out) {
  const auto only_for = [&fault](std::string_view key, bool allowed, const std::string& kinds) {
    const std::optional<Field> field = fault.Find(key);
    if (field && !allowed) field->Fail("applies only to kind " + kinds);
    return field;
  };
  const std::optional<Field> sensor =
      only_for("sensor", IsSensorFault(out.kind), "stream_cut|frozen|bias|extra_noise");
  if (sensor) out.sensor = static_cast<FaultSensor>(sensor->OneOf(kFaultSensorNames));
  const std::optional<Field> bias = only_for("bias", out.kind == FaultKind::kBias, "bias");
  const std::optional<Field> noise =
      only_for("noise_factor", out.kind == FaultKind::kExtraNoise, "extra_noise");
  const std::optional<Field> ballast =
      only_for("ballast_offset_m", out.kind == FaultKind::kBallast, "ballast");
  const std::optional<Field> loss =
      only_for("loss", out.kind == FaultKind::kRadioBurst, "radio_burst");
  const auto required = [&fault](const std::optional<Field>& field, std::string_view key) {
    return field ? *field : fault.Required(key);  // Required throws "missing (required)"
  };
  if (out.kind == FaultKind::kBias) {
    out.bias =
        ReadVector<3>(required(bias, "bias"), Range{-internal::kMaxBias, internal::kMaxBias});
  }
  if (out.kind == FaultKind::kExtraNoise) {
    out.noise_factor =
        required(noise, "noise_factor").Number(Range{1.0, internal::kMaxNoiseFactor, true});
  }
  if (out.kind == FaultKind::kBallast) {
    out.ballast_offset_m =
        ReadVector<2>(required(ballast, "ballast_offset_m"),
                      Range{-internal::kMaxBallastOffsetM, internal::kMaxBallastOffsetM});
  }
  if (out.kind == FaultKind::kRadioBurst) {
    out.loss = required(loss, "loss").Number(Range{0.0, 1.0, true});
  }
}

// `duration_s`: refused where a fault has none, required for a radio burst, and
// each kind's own default and range.
void ReadFaultDuration(const Mapping& fault, FaultSpec& out) {
  const std::optional<Field> duration = fault.Find("duration_s");
  if (!duration) {
    if (out.kind == FaultKind::kRadioBurst) fault.Required("duration_s");  // throws
    if (out.kind == FaultKind::kServerRestart) out.duration_s = 0.0;       // at once
    if (out.kind == FaultKind::kVehicleReboot) out.duration_s = kDefaultRebootS;
    return;
  }
  if (out.kind == FaultKind::kTotalLoss) {
    duration->Fail("total_loss is permanent: it takes no duration_s");
  }
  double max_s = internal::kMaxDurationS;
  if (out.kind == FaultKind::kServerRestart) max_s = internal::kMaxServerDownS;
  if (out.kind == FaultKind::kVehicleReboot) max_s = kMaxRebootS;
  out.duration_s = duration->Number(Range{0.0, max_s, true});
}

FaultSpec ReadFault(const Field& field, const Scenario& scenario) {
  const Mapping fault(field, {"vehicle", "at_s", "kind", "duration_s", "sensor", "bias",
                              "noise_factor", "ballast_offset_m", "loss"});
  FaultSpec out;
  out.kind = static_cast<FaultKind>(fault.Required("kind").OneOf(kFaultKindNames));
  if (out.kind == FaultKind::kServerRestart || out.kind == FaultKind::kRadioBurst) {
    if (const std::optional<Field> vehicle = fault.Find("vehicle")) {
      vehicle->Fail(out.kind == FaultKind::kServerRestart
                        ? "server_restart concerns the server: it takes no vehicle"
                        : "radio_burst concerns every radio channel: it takes no vehicle");
    }
  } else {
    const Field vehicle = fault.Required("vehicle");
    out.vehicle = static_cast<int>(vehicle.Integer(kMinReceiverId, kMaxReceiverId));
    const std::vector<int> ids = scenario.fleet.ReceiverIds();
    if (out.vehicle < ids.front() || out.vehicle > ids.back()) {
      vehicle.Fail("is not one of the fleet's receiver IDs " + std::to_string(ids.front()) + ".." +
                   std::to_string(ids.back()) + ", got " + std::to_string(out.vehicle));
    }
  }
  out.at_s = fault.Required("at_s").Number(Range{0.0, scenario.duration_s, false, true});
  ReadFaultDuration(fault, out);
  ReadFaultParameters(fault, out);
  return out;
}

}  // namespace

std::string_view ToString(FaultKind kind) {
  return kFaultKindNames.at(static_cast<std::size_t>(kind));
}

std::string_view ToString(FaultSensor sensor) {
  return kFaultSensorNames.at(static_cast<std::size_t>(sensor));
}

namespace internal {

void ReadEvents(const Mapping& root, Scenario& scenario) {
  if (const std::optional<Field> fires = root.Find("fires")) {
    for (const Field& fire : fires->Elements()) scenario.fires.push_back(ReadFire(fire, scenario));
  }
  if (const std::optional<Field> random = root.Find("random_fires")) {
    scenario.random_fires = ReadRandomFires(*random, scenario.seed);
  }
  if (const std::optional<Field> distractors = root.Find("distractors")) {
    for (const Field& distractor : distractors->Elements()) {
      scenario.distractors.push_back(ReadDistractor(distractor, scenario.area));
    }
  }
  if (const std::optional<Field> faults = root.Find("faults")) {
    for (const Field& fault : faults->Elements()) {
      scenario.faults.push_back(ReadFault(fault, scenario));
    }
  }
}

}  // namespace internal
}  // namespace fireswarm::run
