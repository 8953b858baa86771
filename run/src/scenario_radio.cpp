// The scenario's radio channels (issue 21): `radio.channels` and
// `radio.channel_overrides`.
#include <set>
#include <string>

#include "fireswarm/radio/channel_router.hpp"
#include "scenario_parts.hpp"

namespace fireswarm::run {

RadioConfig RadioConfig::ChannelAt(int channel) const {
  RadioConfig out = *this;
  for (const ChannelOverride& o : channel_overrides) {
    if (o.channel != channel) continue;
    out.baud = o.baud.value_or(baud);
    out.turnaround_ms = o.turnaround_ms.value_or(turnaround_ms);
    out.loss = o.loss.value_or(loss);
  }
  return out;
}

namespace internal {

namespace {

RadioConfig::ChannelOverride ReadChannelOverride(const Field& field, int channels) {
  const Mapping entry(field, {"channel", "baud", "turnaround_ms", "loss", "vehicles"});
  RadioConfig::ChannelOverride out;
  out.channel = static_cast<int>(entry.Required("channel").Integer(0, channels - 1));
  if (const std::optional<Field> baud = entry.Find("baud")) {
    out.baud = static_cast<int>(baud->Integer(1, kMaxBaud));
  }
  if (const std::optional<Field> turnaround = entry.Find("turnaround_ms")) {
    out.turnaround_ms = turnaround->Number(Range{0.0, kMaxTurnaroundMs});
  }
  if (const std::optional<Field> loss = entry.Find("loss"))
    out.loss = loss->Number(Range{0.0, 1.0});
  if (const std::optional<Field> vehicles = entry.Find("vehicles")) {
    for (const Field& id : vehicles->Elements()) {
      out.vehicles.push_back(static_cast<int>(id.Integer(kMinReceiverId, kMaxReceiverId)));
    }
  }
  return out;
}

}  // namespace

void ReadChannels(const Mapping& radio, RadioConfig& out) {
  out.channels = radio.Integer("channels", out.channels, 1, static_cast<int>(radio::kMaxChannels));
  const std::optional<Field> overrides = radio.Find("channel_overrides");
  if (!overrides) return;
  std::set<int> channels_seen;
  std::set<int> vehicles_seen;
  for (const Field& element : overrides->Elements()) {
    RadioConfig::ChannelOverride entry = ReadChannelOverride(element, out.channels);
    if (!channels_seen.insert(entry.channel).second) {
      element.Fail("channel " + std::to_string(entry.channel) + " is overridden twice");
    }
    for (const int id : entry.vehicles) {
      if (!vehicles_seen.insert(id).second) {
        element.Fail("vehicle " + std::to_string(id) + " is fixed on two channels");
      }
    }
    out.channel_overrides.push_back(std::move(entry));
  }
}

}  // namespace internal

}  // namespace fireswarm::run
